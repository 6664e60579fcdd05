// The intersection certificate of a GJK tetrahedron, decided in double-word arithmetic with
// proven error bounds (geometry/double_word.hpp).
//
// Four pairs give points W_k = a_k − b_k of A − B. The origin is Σ λ_k W_k with barycentric
// weights λ_k = D_k / D, D = Σ D_k, where D_k is the signed volume of the tetrahedron with W_k
// replaced by the origin:
//   D_0 = W1·(W2 × W3),  D_1 = −W0·(W2 × W3),  D_2 = W3·(W0 × W1),  D_3 = −W2·(W0 × W1).
// When every D_k is decided non-zero with one sign, the origin lies strictly inside, so the
// hulls share the point p = Σ λ_k a_k = Σ λ_k b_k (the exact certificate's common point: the
// weights of a non-degenerate tetrahedron are unique). Each coordinate of p is N_j / D with
// N_j = Σ D_k a_kj, and its nearest double c is proven by the sign of N_j − c·D against half
// the spacing of the doubles around c. These are polynomials of degree 4 in the coordinates,
// evaluated to about 2^-100 relative, where long double's 2^-64 leaves the rounding of p
// undecided about half the time.
//
// The points are first scaled by a power of two so that the largest coordinate lies in
// [1, 2): exact while no non-zero coordinate becomes subnormal (checked), and the rounding of
// p commutes with it while p's coordinates stay normal (checked). Anything undecided, a face
// through the origin included, gives nullopt and the exact certificate decides.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "exact/arithmetic/wide_rounding.hpp"
#include "exact/certificates/filtered_distance.hpp"
#include "gjklab/geometry/double_word.hpp"

namespace gjklab::exact::detail {

namespace {

using DVec = std::array<DoubleWord, 3>;

[[gnu::always_inline]] inline DoubleWord dot(const DVec& x, const DVec& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}
[[gnu::always_inline]] inline DVec cross(const DVec& x, const DVec& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}

/// The scale 2^-e that brings the largest coordinate of the eight points into [1, 2), as e;
/// nullopt when all are zero, when e is extreme, or when scaling would make a non-zero
/// coordinate subnormal (and so inexact).
std::optional<long> scale_exponent(std::span<const Vec3, 4> a, std::span<const Vec3, 4> b) {
  double top = 0, bottom = std::numeric_limits<double>::infinity();
  for (const auto* cloud : {&a, &b})
    for (const Vec3& p : *cloud)
      for (int j = 0; j < 3; ++j) {
        const double x = std::fabs(p[j]);
        top = std::max(top, x);
        if (x > 0) bottom = std::min(bottom, x);
      }
  if (!(top >= std::numeric_limits<double>::min()) || !std::isfinite(top)) return std::nullopt;
  const long e = static_cast<long>((std::bit_cast<std::uint64_t>(top) >> 52) & 0x7FF) - 1023;
  if (e > 1000 || e < -1000) return std::nullopt;
  if (bottom * power_of_two(-e) < std::numeric_limits<double>::min()) return std::nullopt;
  return e;
}

/// Half the distance from c to its neighbours below and above: the rounding cell of a normal
/// c is (c − below, c + above). Below a power of two the spacing halves.
void half_gaps(double c, double& below, double& above) {
  const auto bits = std::bit_cast<std::uint64_t>(std::fabs(c));
  const long lsb = static_cast<long>(bits >> 52) - 1075;  // |c| is a multiple of 2^lsb
  const bool power = (bits & ((std::uint64_t{1} << 52) - 1)) == 0;
  const double away = power_of_two(lsb - 1), toward = power ? away / 2 : away;
  below = c > 0 ? toward : away;
  above = c > 0 ? away : toward;
}

double upper(double x) {
  return x + std::fabs(x) * 0x1p-50;
}
double lower(double x) {
  return x - std::fabs(x) * 0x1p-50;
}

/// The nearest double to n/d (d decided > 0) when the evaluation shows it; the candidate
/// from the quotient of the leading parts, corrected once by the residual.
[[gnu::always_inline]] inline std::optional<double> nearest_quotient(const DoubleWord& n,
                                                                     const DoubleWord& d) {
  const double first = n.hi / d.hi;
  const double c = first + (n - d * first).hi / d.hi;
  if (!std::isnormal(c)) return std::nullopt;
  const DoubleWord r = n - d * c;  // (n/d − c)·d
  double below, above;
  half_gaps(c, below, above);
  // Bounds of the exact r and d; each sum's own rounding is covered by the 2^-50 margins.
  const double slack = upper(std::fabs(r.lo) + r.err);
  const double r_max = upper(r.hi + slack), r_min = lower(r.hi - slack);
  const double d_min = lower(d.hi - upper(std::fabs(d.lo) + d.err));
  if (!(d_min > 0)) return std::nullopt;
  // −below·d < r < above·d; the products by powers of two are exact in this range.
  if (r_max < lower(above * d_min) && -r_min < lower(below * d_min)) return c;
  return std::nullopt;
}

/// enclosed_origin_witness's body, inlined into one copy per instruction set below.
[[gnu::always_inline]] inline std::optional<Vec3> witness(std::span<const Vec3, 4> a,
                                                          std::span<const Vec3, 4> b) {
  const std::optional<long> e = scale_exponent(a, b);
  if (!e) return std::nullopt;
  const double scale = power_of_two(-*e);
  std::array<DVec, 4> w;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      w[k][j] = exact_difference(a[k][j] * scale, b[k][j] * scale);
  const DVec w23 = cross(w[2], w[3]), w01 = cross(w[0], w[1]);
  std::array<DoubleWord, 4> volume = {dot(w[1], w23), -dot(w[0], w23), dot(w[3], w01),
                                      -dot(w[2], w01)};
  bool all_positive = true, all_negative = true;
  for (const DoubleWord& v : volume) {
    all_positive = all_positive && positive(v);
    all_negative = all_negative && negative(v);
  }
  if (!all_positive && !all_negative) return std::nullopt;
  if (all_negative)
    for (DoubleWord& v : volume)
      v = -v;
  const DoubleWord total = (volume[0] + volume[1]) + (volume[2] + volume[3]);
  const double unscale = power_of_two(*e);
  Vec3 out;
  for (int j = 0; j < 3; ++j) {
    DoubleWord n = volume[0] * (a[0][j] * scale);
    for (int k = 1; k < 4; ++k)
      n = n + volume[k] * (a[k][j] * scale);
    const std::optional<double> c = nearest_quotient(n, total);
    if (!c || !(std::fabs(*c * unscale) >= std::numeric_limits<double>::min())) return std::nullopt;
    out[j] = *c * unscale;
  }
  return out;
}

/// The products' fma as one instruction, on processors that have it (nearly all x86-64 since
/// 2013); elsewhere a call to the C library's fma, which is as exact.
[[gnu::target("fma")]] std::optional<Vec3> witness_with_fma(std::span<const Vec3, 4> a,
                                                            std::span<const Vec3, 4> b) {
  return witness(a, b);
}
std::optional<Vec3> witness_without_fma(std::span<const Vec3, 4> a, std::span<const Vec3, 4> b) {
  return witness(a, b);
}

bool has_fma() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("fma");
}

}  // namespace

std::optional<Vec3> enclosed_origin_witness(std::span<const Vec3, 4> a,
                                            std::span<const Vec3, 4> b) {
  static const bool fma = has_fma();
  return fma ? witness_with_fma(a, b) : witness_without_fma(a, b);
}

}  // namespace gjklab::exact::detail
