// The distance and intersection certificate: exact GJK warm-started from a floating-point
// simplex (see certificate.hpp). No CGAL here.
//
// The simplex's points W_k = A_i − B_j are integer vectors in a common frame: the unit of the
// points it starts from, refined whenever a point it needs is finer. The point of their hull
// closest to the origin is v = N / D with an integer vector N and an integer D > 0, from
// Cramer's rule on the Gram system of the sub-simplex that holds it; every test below is a
// comparison of integers. The steps run first on fixed-width integers (Wide), which need no
// allocation; when those overflow (coordinates of very different magnitudes) they run again
// on GMP's. Both give the same answer, since both are exact.
#include <gmp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "exact/arithmetic/gmp_support.hpp"
#include "exact/arithmetic/integer_geometry.hpp"
#include "exact/arithmetic/wide_int.hpp"
#include "exact/arithmetic/wide_rounding.hpp"
#include "exact/certificates/filtered_distance.hpp"
#include "gjklab/exact/certificate.hpp"

namespace gjklab::exact {

namespace {

using detail::Int;
using detail::Vec3Of;
using detail::Wide;
using detail::operator-;
using detail::cross;
using detail::dot;

/// The point of the hull of a few integer points closest to the origin: v = numerator /
/// denominator, v = Σ weights[k]·W_k / denominator over the points in `subset`.
template <class I>
struct ExactClosest {
  std::uint8_t subset = 0;  ///< bit k ↔ point k
  std::array<I, 4> weights;
  I denominator;  ///< > 0
  Vec3Of<I> numerator;
};

/// The closest point of the affine hull of the points of `subset` (bit k ↔ w[k]), with its
/// barycentric weights; nullopt when those points are affinely dependent.
template <class I>
std::optional<ExactClosest<I>> affine_closest(std::span<const Vec3Of<I>> w, std::uint8_t subset) {
  std::array<int, 4> idx{};
  int k = 0;
  for (int i = 0; i < static_cast<int>(w.size()); ++i)
    if (subset & (1u << i)) idx[k++] = i;
  ExactClosest<I> c;
  c.subset = subset;
  const Vec3Of<I>& w0 = w[idx[0]];
  if (k == 1) {
    c.weights[idx[0]] = 1;
    c.denominator = 1;
    c.numerator = w0;
    return c;
  }
  if (k == 4) {
    // Four points span space when independent: the closest point of the affine hull is the
    // origin, with barycentric weights from Cramer's rule on [e1 e2 e3]·μ = −w0.
    const Vec3Of<I> e1 = w[idx[1]] - w0, e2 = w[idx[2]] - w0, e3 = w[idx[3]] - w0;
    const Vec3Of<I> minus_w0 = {-w0[0], -w0[1], -w0[2]};
    const Vec3Of<I> e23 = cross(e2, e3);
    I det = dot(e1, e23);
    if (sgn(det) == 0) return std::nullopt;
    I l1 = dot(minus_w0, e23);
    I l2 = dot(e1, cross(minus_w0, e3));
    I l3 = dot(e1, cross(e2, minus_w0));
    if (sgn(det) < 0) {
      det = -det;
      l1 = -l1;
      l2 = -l2;
      l3 = -l3;
    }
    c.weights[idx[0]] = det - l1 - l2 - l3;
    c.weights[idx[1]] = l1;
    c.weights[idx[2]] = l2;
    c.weights[idx[3]] = l3;
    c.denominator = det;
    c.numerator = {0, 0, 0};
    return c;
  }
  // Two or three points: minimise ‖w0 + Σ μ_i e_i‖² (Gram system G μ = r, r_i = −e_i·w0).
  const Vec3Of<I> e1 = w[idx[1]] - w0;
  if (k == 2) {
    const I g = dot(e1, e1);
    if (sgn(g) == 0) return std::nullopt;
    const I r = -dot(e1, w0);
    c.weights[idx[0]] = g - r;
    c.weights[idx[1]] = r;
    c.denominator = g;
  } else {
    const Vec3Of<I> e2 = w[idx[2]] - w0;
    const I g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
    const I r1 = -dot(e1, w0), r2 = -dot(e2, w0);
    const I det = g11 * g22 - g12 * g12;
    if (sgn(det) == 0) return std::nullopt;
    const I l1 = r1 * g22 - g12 * r2, l2 = g11 * r2 - g12 * r1;
    c.weights[idx[0]] = det - l1 - l2;
    c.weights[idx[1]] = l1;
    c.weights[idx[2]] = l2;
    c.denominator = det;
  }
  c.numerator = {0, 0, 0};
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < 3; ++j)
      c.numerator[j] += c.weights[idx[i]] * w[idx[i]][j];
  return c;
}

/// True if v = c's point is the closest point of the hull of all of w: v lies in the hull of
/// its subset (weights ≥ 0) and every point satisfies v·w_k ≥ v·v (D·(N·W_k) ≥ N·N).
template <class I>
bool is_closest(const ExactClosest<I>& c, std::span<const Vec3Of<I>> w) {
  for (std::size_t k = 0; k < w.size(); ++k)
    if ((c.subset & (1u << k)) && sgn(c.weights[k]) < 0) return false;
  const I nn = dot(c.numerator, c.numerator);
  for (std::size_t k = 0; k < w.size(); ++k)
    if (!(c.subset & (1u << k)) && c.denominator * dot(c.numerator, w[k]) < nn) return false;
  return true;
}

/// The exact closest point of the hull of 1 … 4 integer points: the full set first (the
/// usual case for a converged hint), then every other subset until one passes is_closest.
/// By Carathéodory some affinely independent subset holds the closest point in its relative
/// interior, so the search succeeds; nullopt only guards against the impossible.
template <class I>
std::optional<ExactClosest<I>> closest_on_hull(std::span<const Vec3Of<I>> w) {
  const auto full = static_cast<std::uint8_t>((1u << w.size()) - 1);
  for (std::uint8_t subset = full; subset > 0; --subset) {
    std::optional<ExactClosest<I>> c = affine_closest(w, subset);
    if (c && is_closest(*c, w)) return c;
  }
  return std::nullopt;
}

/// The same integer as a GMP one (the outputs' conversions work on mpz).
const Int& as_mpz(const Int& x) {
  return x;
}
Int as_mpz(const Wide& x) {
  Int z;
  x.to_mpz(z.get_mpz_t());
  return z;
}

/// The double nearest to num/den·2^exponent: without GMP where the fast conversion proves
/// its answer, else with it.
double nearest_double_of(const Int& num, const Int& den, long exponent) {
  return detail::nearest_double(num.get_mpz_t(), den.get_mpz_t(), exponent);
}
double nearest_double_of(const Wide& num, const Wide& den, long exponent) {
  if (const std::optional<double> r = detail::nearest_quotient(num, den, exponent)) return *r;
  return nearest_double_of(as_mpz(num), as_mpz(den), exponent);
}

/// The double nearest to √(nn / dd · 4^exponent) (nn ≥ 0, dd > 0).
double nearest_sqrt_of(const Int& nn, const Int& dd, long exponent) {
  detail::Mpq q;  // not in lowest terms: nearest_sqrt needs no gcd
  mpz_mul_2exp(mpq_numref(q.get()), nn.get_mpz_t(), exponent > 0 ? 2 * exponent : 0);
  mpz_mul_2exp(mpq_denref(q.get()), dd.get_mpz_t(), exponent < 0 ? -2 * exponent : 0);
  return detail::nearest_sqrt(q.get());
}
double nearest_sqrt_of(const Wide& nn, const Wide& dd, long exponent) {
  if (const std::optional<double> r = detail::nearest_sqrt(nn, dd, 2 * exponent)) return *r;
  return nearest_sqrt_of(as_mpz(nn), as_mpz(dd), exponent);
}

/// The exact squared distance N·N / D² · 4^exponent and its nearest double square root. The
/// rational's digits are made on first use (reducing it costs more than the certificate).
template <class I>
void set_distance(const Vec3Of<I>& n, const I& d, long exponent, DistanceCertificate& out) {
  I nn = dot(n, n), dd = d * d;
  out.distance = nearest_sqrt_of(nn, dd, exponent);
  out.distance_squared =
      detail::lazy_rational(false, [nn = std::move(nn), dd = std::move(dd), exponent](mpq_ptr q) {
        const Int num = as_mpz(nn), den = as_mpz(dd);
        mpq_set_num(q, num.get_mpz_t());
        mpq_set_den(q, den.get_mpz_t());
        if (exponent > 0) mpz_mul_2exp(mpq_numref(q), mpq_numref(q), 2 * exponent);
        if (exponent < 0) mpz_mul_2exp(mpq_denref(q), mpq_denref(q), -2 * exponent);
      });
}

/// The nearest double to Σ weights[k]·points[k] / denominator · 2^exponent, per coordinate.
template <class I>
Vec3 nearest_combination(const ExactClosest<I>& c, std::span<const Vec3Of<I>> points,
                         long exponent) {
  Vec3 out;
  for (int j = 0; j < 3; ++j) {
    I sum = 0;
    for (std::size_t k = 0; k < points.size(); ++k)
      if (c.subset & (1u << k)) sum += c.weights[k] * points[k][j];
    out[j] = nearest_double_of(sum, c.denominator, exponent);
  }
  return out;
}

/// The weights of c's points as long doubles λ_k = weights[k] / denominator, each with a
/// relative error below 5·2^-64 (ratio_estimate); only Wide
/// (with GMP's integers the exact rounding is used directly).
bool weight_estimates(const ExactClosest<Wide>& c, std::size_t size,
                      std::array<long double, 4>& out) {
  for (std::size_t k = 0; k < size; ++k) {
    out[k] = 0;
    if (!(c.subset & (1u << k))) continue;
    if (sgn(c.weights[k]) < 0) return false;
    out[k] = detail::ratio_estimate(c.weights[k], c.denominator);
  }
  return true;
}
bool weight_estimates(const ExactClosest<Int>&, std::size_t, std::array<long double, 4>&) {
  return false;
}

/// The nearest doubles to the witness Σ weights[k]·x_k / denominator of the points x_k of one
/// cloud (`cloud[index[k]]`, the same points as `points` in the frame's units): from long double
/// weights where that shows them, else exactly.
template <class I>
Vec3 nearest_witness(const ExactClosest<I>& c, std::span<const Vec3Of<I>> points,
                     std::span<const Vec3> cloud, std::span<const std::int32_t> index,
                     long exponent) {
  std::array<long double, 4> weights{};
  if (weight_estimates(c, points.size(), weights)) {
    std::array<Vec3, 4> x;
    for (std::size_t k = 0; k < points.size(); ++k)
      x[k] = cloud[index[k]];
    if (const std::optional<Vec3> w = detail::nearest_weighted_sum({weights.data(), points.size()},
                                                                   {x.data(), points.size()}))
      return *w;
  }
  return nearest_combination(c, points, exponent);
}

/// The exact GJK state: the simplex's index pairs and their points in A, in B and in A − B
/// (at most four; fixed storage, as the state is rebuilt for every certificate).
template <class I>
struct ExactSimplex {
  std::array<IndexPair, 4> pairs;
  std::array<Vec3Of<I>, 4> a, b, w;
  std::size_t size = 0;

  std::span<const Vec3Of<I>> points_a() const { return {a.data(), size}; }
  std::span<const Vec3Of<I>> points_b() const { return {b.data(), size}; }
  std::span<const Vec3Of<I>> points_w() const { return {w.data(), size}; }
  bool contains(const Vec3Of<I>& x) const {
    return std::find(w.begin(), w.begin() + size, x) != w.begin() + size;
  }
  void push(const IndexPair& p, Vec3Of<I> pa, Vec3Of<I> pb) {
    w[size] = pa - pb;
    a[size] = std::move(pa);
    b[size] = std::move(pb);
    pairs[size++] = p;
  }
  void keep(std::uint8_t subset) {
    std::size_t out = 0;
    for (std::size_t k = 0; k < size; ++k) {
      if (!(subset & (1u << k))) continue;
      if (out != k) {
        pairs[out] = pairs[k];
        a[out] = std::move(a[k]);
        b[out] = std::move(b[k]);
        w[out] = std::move(w[k]);
      }
      ++out;
    }
    size = out;
  }
};

bool in_range(std::int32_t i, std::size_t n) {
  return i >= 0 && static_cast<std::size_t>(i) < n;
}

/// The hint's usable points: in range, not repeated, at most four.
template <class I>
ExactSimplex<I> starting_simplex(std::span<const Vec3> a, std::span<const Vec3> b,
                                 const DistanceHint& hint, long exponent) {
  ExactSimplex<I> s;
  for (const IndexPair& p : hint.simplex) {
    if (s.size == 4) break;
    if (!in_range(p.a, a.size()) || !in_range(p.b, b.size())) continue;
    Vec3Of<I> pa = detail::to_integer<I>(a[p.a], exponent);
    Vec3Of<I> pb = detail::to_integer<I>(b[p.b], exponent);
    if (s.contains(pa - pb)) continue;
    s.push(p, std::move(pa), std::move(pb));
  }
  if (s.size == 0)
    s.push({0, 0}, detail::to_integer<I>(a[0], exponent), detail::to_integer<I>(b[0], exponent));
  return s;
}

/// Exact GJK from the hint, with every point an integer vector in units of 2^exponent.
/// Throws FrameTooCoarse when a point it needs is not integral in that unit, and
/// WideOverflow when I = Wide is too narrow.
template <class I>
std::optional<DistanceCertificate> certify_in_frame(std::span<const Vec3> a,
                                                    std::span<const Vec3> b,
                                                    const DistanceHint& hint, int max_steps,
                                                    long exponent) {
  const detail::IntegerFrame frame{exponent};
  ExactSimplex<I> simplex = starting_simplex<I>(a, b, hint, exponent);
  for (int step = 0; step <= max_steps; ++step) {
    const std::optional<ExactClosest<I>> c = closest_on_hull<I>(simplex.points_w());
    if (!c) return std::nullopt;
    const auto finish = [&](bool intersect) {
      DistanceCertificate out;
      out.intersect = intersect;
      std::array<std::int32_t, 4> index_a{}, index_b{};
      for (std::size_t k = 0; k < simplex.size; ++k) {
        index_a[k] = simplex.pairs[k].a;
        index_b[k] = simplex.pairs[k].b;
      }
      out.witness_a = nearest_witness(*c, simplex.points_a(), a, index_a, exponent);
      out.witness_b = nearest_witness(*c, simplex.points_b(), b, index_b, exponent);
      simplex.keep(c->subset);
      if (!intersect) set_distance(c->numerator, c->denominator, exponent, out);
      out.feature.simplex.assign(simplex.pairs.begin(), simplex.pairs.begin() + simplex.size);
      out.repair_steps = step;
      return out;
    };
    if (detail::is_zero(c->numerator)) return finish(true);  // the origin is in the hull

    // Separated iff min over a of N·A − max over b of N·B ≥ N·N / D.
    const detail::Extreme<I> low = detail::extreme_point(a, c->numerator, frame, false);
    const detail::Extreme<I> high = detail::extreme_point(b, c->numerator, frame, true);
    if (c->denominator * (low.value - high.value) >= dot(c->numerator, c->numerator))
      return finish(false);

    // Not the closest point: continue from its sub-simplex and the violating support point.
    const IndexPair next{static_cast<std::int32_t>(low.index),
                         static_cast<std::int32_t>(high.index)};
    Vec3Of<I> pa = detail::to_integer<I>(a[low.index], exponent);
    Vec3Of<I> pb = detail::to_integer<I>(b[high.index], exponent);
    simplex.keep(c->subset);
    // In exact arithmetic the new point violates the test, so it is not in the simplex and
    // the distance strictly decreases; a repeat would mean a bug, and is never an answer.
    if (simplex.contains(pa - pb) || simplex.size >= 4) return std::nullopt;
    simplex.push(next, std::move(pa), std::move(pb));
  }
  return std::nullopt;
}

/// The unit of the points the certificate starts from (the hint's, and the pair (0, 0)): the
/// finest unit in which each of their coordinates is an integer. Points found later may need
/// a finer one (FrameTooCoarse).
long starting_exponent(std::span<const Vec3> a, std::span<const Vec3> b, const DistanceHint& hint) {
  long lowest = std::numeric_limits<long>::max();
  const auto take = [&](const Vec3& p) {
    for (int i = 0; i < 3; ++i)
      if (p[i] != 0) lowest = std::min(lowest, detail::base_exponent(p[i]));
  };
  take(a[0]);
  take(b[0]);
  for (const IndexPair& p : hint.simplex)
    if (in_range(p.a, a.size()) && in_range(p.b, b.size())) {
      take(a[p.a]);
      take(b[p.b]);
    }
  return lowest == std::numeric_limits<long>::max() ? 0 : lowest;
}

/// Frame refinements tried before the clouds' own frame (integer_frame, one pass over every
/// coordinate, in which every point is integral) is used.
constexpr int kFrameRefinements = 8;

/// certify_in_frame in the coarsest unit that works: the starting points' unit, refined each
/// time a point needs a finer one.
template <class I>
std::optional<DistanceCertificate> certify_with(std::span<const Vec3> a, std::span<const Vec3> b,
                                                const DistanceHint& hint, int max_steps) {
  long exponent = starting_exponent(a, b, hint);
  for (int attempt = 0; attempt < kFrameRefinements; ++attempt) {
    try {
      return certify_in_frame<I>(a, b, hint, max_steps, exponent);
    } catch (const detail::FrameTooCoarse& finer) {
      exponent = finer.exponent;  // strictly lower: a point was not integral in the old unit
    }
  }
  return certify_in_frame<I>(a, b, hint, max_steps, detail::integer_frame(a, b).exponent);
}

}  // namespace

namespace detail {

std::optional<DistanceCertificate> certify_distance_exact(std::span<const Vec3> a,
                                                          std::span<const Vec3> b,
                                                          const DistanceHint& hint, int max_steps) {
  if (a.empty() || b.empty()) return std::nullopt;
  try {
    return certify_with<Wide>(a, b, hint, max_steps);
  } catch (const detail::WideOverflow&) {
    // The integers outgrew the fixed width (coordinates of very different magnitudes): the
    // same steps with GMP integers, which give the same answer.
  }
  return certify_with<Int>(a, b, hint, max_steps);
}

}  // namespace detail

std::optional<DistanceCertificate> certify_distance(std::span<const Vec3> a,
                                                    std::span<const Vec3> b,
                                                    const DistanceHint& hint, int max_steps) {
  if (a.empty() || b.empty()) return std::nullopt;
  // Nearly every converged hint is decided in floating point; the rest by exact GJK.
  if (std::optional<DistanceCertificate> filtered = detail::certify_distance_filtered(a, b, hint))
    return filtered;
  return detail::certify_distance_exact(a, b, hint, max_steps);
}

}  // namespace gjklab::exact
