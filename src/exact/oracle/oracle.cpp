// The exact oracle: distance and intersection with CGAL::Polytope_distance_d.
//
// Polytope_distance_d solves the quadratic program min |Σλ_i a_i − Σμ_j b_j|² over convex
// weights with CGAL's exact QP solver. Every number type in the setup is exact: the kernel is
// Homogeneous<Gmpzf> (a double converts exactly to a Gmpzf, with homogenising weight 1), and
// both the solver's type ET and the pricing type NT are Gmpzf. (The documented setup with a
// double kernel and NT = double prices in floating point; it breaks down, for example, when
// squared coordinates overflow or underflow.) Gmpzf is a dyadic floating-point type with an
// exact mantissa, which avoids the gcd normalisations of Gmpq and measured 2–3 times faster
// than Simple_cartesian<Gmpq> with ET = NT = Gmpq at identical results.
//
// The result num/den of two Gmpzf values is turned into a GMP rational in lowest terms. Only
// the extreme points of each cloud enter the QP (the hulls are the same).
#include <CGAL/Gmpzf.h>
#include <CGAL/Homogeneous.h>
#include <CGAL/Polytope_distance_d.h>
#include <CGAL/Polytope_distance_d_traits_3.h>

#include <immintrin.h>

#include <bit>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjklab/exact/certificate.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "exact/arithmetic/gmp_support.hpp"
#include "exact/hull/hull.hpp"

namespace gjklab::exact {

namespace {

using Kernel = CGAL::Homogeneous<CGAL::Gmpzf>;
using DistanceTraits = CGAL::Polytope_distance_d_traits_3<Kernel, CGAL::Gmpzf, CGAL::Gmpzf>;
using PolytopeDistance = CGAL::Polytope_distance_d<DistanceTraits>;

constexpr std::uint64_t kExponentField = 0x7FF0000000000000;  // all ones: Inf or NaN

/// True when none of the n doubles is Inf or NaN (their exponent fields are not all ones).
bool all_finite_scalar(const double* x, std::size_t n) {
  std::uint64_t non_finite = 0;
  for (std::size_t i = 0; i < n; ++i)
    non_finite |= (std::bit_cast<std::uint64_t>(x[i]) & kExponentField) == kExponentField;
  return non_finite == 0;
}

/// The same, four doubles per instruction.
[[gnu::target("avx2")]] bool all_finite_avx2(const double* x, std::size_t n) {
  const __m256i field = _mm256_set1_epi64x(static_cast<long long>(kExponentField));
  __m256i non_finite = _mm256_setzero_si256();
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m256i bits = _mm256_castpd_si256(_mm256_loadu_pd(x + i));
    non_finite =
        _mm256_or_si256(non_finite, _mm256_cmpeq_epi64(_mm256_and_si256(bits, field), field));
  }
  return _mm256_testz_si256(non_finite, non_finite) && all_finite_scalar(x + i, n - i);
}

/// True when every coordinate is finite: one pass over the exponent fields of the packed
/// coordinates (describe_invalid_cloud, which names the point, runs only when this fails).
bool all_finite(std::span<const Vec3> cloud) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "points packed as x, y, z");
  static const bool avx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
  }();
  const double* x = cloud.empty() ? nullptr : cloud.data()->data();
  return avx2 ? all_finite_avx2(x, 3 * cloud.size()) : all_finite_scalar(x, 3 * cloud.size());
}

void check_cloud(std::span<const Vec3> cloud, const char* name) {
  if (!cloud.empty() && all_finite(cloud)) return;
  if (std::string problem = describe_invalid_cloud(cloud); !problem.empty())
    throw InvalidGeometry(std::string(name) + ": " + problem);
}

/// out := x exactly (x = mantissa · 2^exponent).
void assign(mpq_ptr out, const CGAL::Gmpzf& x) {
  mpq_set_z(out, x.man());
  const long e = x.exp();
  if (e > 0) mpq_mul_2exp(out, out, static_cast<mp_bitcnt_t>(e));
  if (e < 0) mpq_div_2exp(out, out, static_cast<mp_bitcnt_t>(-e));
}

std::vector<Kernel::Point_3> to_kernel(std::span<const Vec3> points) {
  std::vector<Kernel::Point_3> out;
  out.reserve(points.size());
  for (const Vec3& p : points)
    out.emplace_back(CGAL::Gmpzf(p.x()), CGAL::Gmpzf(p.y()), CGAL::Gmpzf(p.z()));
  return out;
}

/// out := the exact squared distance between the hulls of the two point sets.
void squared_distance(std::span<const Vec3> a, std::span<const Vec3> b, mpq_ptr out) {
  const std::vector<Kernel::Point_3> pa = to_kernel(a), pb = to_kernel(b);
  const PolytopeDistance pd(pa.begin(), pa.end(), pb.begin(), pb.end());
  detail::Mpq den;
  assign(out, pd.squared_distance_numerator());
  assign(den.get(), pd.squared_distance_denominator());
  if (mpq_sgn(den.get()) == 0)
    throw std::logic_error("exact oracle: Polytope_distance_d returned a zero denominator");
  mpq_div(out, out, den.get());  // the quotient is canonical (lowest terms, den > 0)
  if (mpq_sgn(out) < 0)
    throw std::logic_error("exact oracle: Polytope_distance_d returned a negative distance");
}

}  // namespace

namespace {

/// The QP path's inputs: each cloud's extreme points (the hulls are the same), computed once.
struct Hulls {
  std::span<const Vec3> a, b;
  std::optional<detail::HullSummary> hull_a, hull_b;

  const detail::HullSummary& of_a() {
    if (!hull_a) hull_a = detail::hull_summary(a);
    return *hull_a;
  }
  const detail::HullSummary& of_b() {
    if (!hull_b) hull_b = detail::hull_summary(b);
    return *hull_b;
  }
};

Rational qp_distance_squared(Hulls& hulls) {
  detail::Mpq d2;
  squared_distance(hulls.of_a().extreme_points, hulls.of_b().extreme_points, d2.get());
  return detail::to_rational(d2.get());
}

Rational minkowski_depth_squared(Hulls& hulls) {
  detail::Mpq depth2;
  detail::penetration_depth_squared(hulls.of_a().extreme_points, hulls.of_b().extreme_points,
                                    depth2.get());
  return detail::to_rational(depth2.get());
}

bool same(const Rational& x, const Rational& y) {
  return x.numerator() == y.numerator() &&
         x.denominator() == y.denominator();  // both in lowest terms
}

/// The audit of OracleOptions::verify: the certified rational must equal the QP's.
void audit(const char* what, const Rational& certified, const Rational& qp) {
  if (!same(certified, qp))
    throw CertificateMismatch(std::string("exact oracle: certified ") + what + " " +
                              certified.numerator() + "/" + certified.denominator() +
                              " differs from the QP's " + qp.numerator() + "/" + qp.denominator());
}

}  // namespace

OracleAnswer solve(std::span<const Vec3> a, std::span<const Vec3> b, const OracleOptions& options,
                   const OracleHints& hints) {
  check_cloud(a, "cloud A");
  check_cloud(b, "cloud B");
  Hulls hulls{a, b, std::nullopt, std::nullopt};
  OracleAnswer answer;

  std::optional<DistanceCertificate> certificate;
  if (options.certificates)
    certificate =
        certify_distance(a, b, hints.distance.value_or(DistanceHint{}), options.certificate_steps);
  if (certificate) {
    answer.method = AnswerMethod::certified;
    answer.distance_squared = certificate->distance_squared;
    answer.witness_a = certificate->witness_a;
    answer.witness_b = certificate->witness_b;
    if (options.verify)
      audit("squared distance", answer.distance_squared, qp_distance_squared(hulls));
  } else {
    answer.method = AnswerMethod::qp;
    answer.distance_squared = qp_distance_squared(hulls);
  }
  answer.intersect = answer.distance_squared.is_zero();
  answer.distance = certificate ? certificate->distance : sqrt_to_double(answer.distance_squared);

  if (options.depth && answer.intersect) {
    std::optional<Rational> depth2;
    std::optional<DepthCertificate> depth_certificate;
    if (options.certificates && hints.depth)
      depth_certificate = certify_depth(a, b, *hints.depth, options.certificate_steps);
    if (depth_certificate) {
      depth2 = depth_certificate->depth_squared;
      answer.depth_method = AnswerMethod::certified;
      answer.depth_normal = depth_certificate->normal;
      if (options.verify) audit("squared depth", *depth2, minkowski_depth_squared(hulls));
    } else {
      answer.depth_method = AnswerMethod::qp;
      depth2 = minkowski_depth_squared(hulls);
    }
    answer.depth_squared = *depth2;
    answer.depth = sqrt_to_double(*depth2);
  }

  answer.hull_vertices_a =
      options.hull_vertices ? static_cast<int>(hulls.of_a().extreme_points.size()) : -1;
  answer.hull_vertices_b =
      options.hull_vertices ? static_cast<int>(hulls.of_b().extreme_points.size()) : -1;
  return answer;
}

int hull_vertex_count(std::span<const Vec3> cloud) {
  check_cloud(cloud, "cloud");
  return static_cast<int>(detail::hull_summary(cloud).extreme_points.size());
}

}  // namespace gjklab::exact
