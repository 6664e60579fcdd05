// The distance certificate of a GJK simplex, decided in floating point with proven error bounds.
//
// The hint's pairs (a_k, b_k) give points W_k = a_k − b_k of A − B. When the origin's nearest
// point v of the affine hull of the W_k lies strictly inside their hull (every barycentric
// weight > 0), p = Σ λ_k a_k and q = Σ λ_k b_k are points of conv A and conv B with v = p − q.
// The pair is then at distance ‖v‖ iff the plane through p orthogonal to v supports A and the
// one through q supports B: v·(a − a_0) ≥ 0 for every a ∈ A and v·(b − b_0) ≤ 0 for every b ∈ B,
// provided every a_k has v·a_k = v·a_0 and every b_k has v·b_k = v·b_0. That proviso holds
// exactly, with no test, when the pairs form one connected feature pair: seen as the edges of
// a graph on their distinct A and B indices, they are connected (a vertex and a face, two
// edges, a vertex and an edge ...). Then every a_k − a_0 is an alternating sum of W's, so it
// lies in the directions of the W's affine hull, to which v is orthogonal. Otherwise (parallel
// faces, say) the proviso is checked exactly on the feature's own points.
//
// Each quantity is evaluated in long double with a running bound on its error (Approx), and a
// sign is taken only when the value exceeds its bound. The O(|A| + |B|) scan runs in double
// with a bound per point; the few points within their bound of a plane (coplanar vertices of a
// face, say) are decided exactly in integers. The nearest doubles of the distance and of the
// witness points are taken when their interval lies inside one double's rounding cell. Any
// undecided step gives nullopt, and the exact certificate decides instead. Simplices of four
// pairs (an intersecting pair's tetrahedron) are decided in double-word arithmetic
// (filtered_tetrahedron.cpp), and one pair with a0 = b0 is a shared point.
#include "exact/certificates/filtered_distance.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include "exact/arithmetic/gmp_support.hpp"
#include "exact/arithmetic/integer_geometry.hpp"
#include "exact/arithmetic/wide_int.hpp"
#include "exact/arithmetic/wide_rounding.hpp"
#include "exact/certificates/bounded_real.hpp"
#include "exact/certificates/side_scan.hpp"

namespace gjklab::exact::detail {

namespace {

// The integer overloads (integer_geometry.hpp) next to the floating-point ones below.
using detail::cross;
using detail::dot;
using detail::operator-;

using namespace bounded;

}  // namespace

std::optional<Vec3> nearest_weighted_sum(std::span<const Real> weights,
                                         std::span<const Vec3> points) {
  Vec3 out;
  for (int j = 0; j < 3; ++j) {
    Approx sum;
    Real magnitude = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Real term = weights[k] * points[k][j];
      sum.v += term;
      magnitude += std::fabs(term);
    }
    // Each term's error: its weight's (5·2^-64 relative) and the product's rounding (2^-64);
    // at most 3 additions of 2^-64 · magnitude each: 9·2^-64 · magnitude in all, below 2^-60.
    sum.err = magnitude * 0x1p-60L;
    const std::optional<double> c = nearest_double(widen(sum));
    if (!c) return std::nullopt;
    out[j] = *c;
  }
  return out;
}

namespace {

/// The hint's pairs, when they are distinct, in range and at most four.
struct Feature {
  int size = 0;
  std::array<IndexPair, 4> pairs;
  std::array<Vec3, 4> a, b;  ///< the pairs' points
  /// The pairs, as edges between their A and B indices, form one connected graph (see the
  /// file comment): then v·a_k = v·a_0 and v·b_k = v·b_0 hold with no test.
  bool connected = false;
};

int distinct_count(const std::array<std::int32_t, 4>& ids, int n) {
  int count = 0;
  for (int i = 0; i < n; ++i)
    if (std::find(ids.begin(), ids.begin() + i, ids[i]) == ids.begin() + i) ++count;
  return count;
}

/// One node for 1 pair, a shared index for 2, and for 3 distinct pairs four distinct indices
/// in all (a path or a star; 5 or 6 would mean two components).
bool is_connected(const Feature& f) {
  std::array<std::int32_t, 4> ia{}, ib{};
  for (int k = 0; k < f.size; ++k) {
    ia[k] = f.pairs[k].a;
    ib[k] = f.pairs[k].b;
  }
  if (f.size == 2) return ia[0] == ia[1] || ib[0] == ib[1];
  if (f.size == 3) return distinct_count(ia, 3) + distinct_count(ib, 3) == 4;
  return f.size == 1;
}

std::optional<Feature> feature_of(std::span<const Vec3> a, std::span<const Vec3> b,
                                  const DistanceHint& hint) {
  Feature f;
  if (hint.simplex.empty() || hint.simplex.size() > 4) return std::nullopt;
  for (const IndexPair& p : hint.simplex) {
    if (p.a < 0 || p.b < 0 || static_cast<std::size_t>(p.a) >= a.size() ||
        static_cast<std::size_t>(p.b) >= b.size())
      return std::nullopt;
    if (std::find(f.pairs.begin(), f.pairs.begin() + f.size, p) != f.pairs.begin() + f.size)
      return std::nullopt;
    f.pairs[f.size] = p;
    f.a[f.size] = a[p.a];
    f.b[f.size] = b[p.b];
    ++f.size;
  }
  f.connected = is_connected(f);
  return f;
}

/// The floating-point geometry of a feature whose nearest point to the origin is inside it:
/// a positive multiple `direction` of v, the squared distance ‖v‖², and p and q.
struct Nearest {
  AVec direction;
  Approx distance_squared;
  AVec p, q;
};

bool single_a(const Feature& f) {
  for (int k = 1; k < f.size; ++k)
    if (f.pairs[k].a != f.pairs[0].a) return false;
  return true;
}
bool single_b(const Feature& f) {
  for (int k = 1; k < f.size; ++k)
    if (f.pairs[k].b != f.pairs[0].b) return false;
  return true;
}

/// p and q from v = p − q when one side of the feature is a single vertex (p = a_0 exactly,
/// q = a_0 − v: v has a small relative error, unlike the weights of a small triangle); else
/// p = a_0 + Σ_{k≥1} λ_k (a_k − a_0) for the weights λ_1 … (and q likewise).
void set_witnesses(const Feature& f, std::span<const Approx> weights, const AVec& v, Nearest& out) {
  const AVec a0 = input(f.a[0]), b0 = input(f.b[0]);
  if (single_a(f)) {
    out.p = a0;
    out.q = a0 - v;
    return;
  }
  if (single_b(f)) {
    out.q = b0;
    out.p = b0 + v;
    return;
  }
  out.p = a0;
  out.q = b0;
  for (int k = 1; k < f.size; ++k) {
    out.p = out.p + weights[k - 1] * (input(f.a[k]) - a0);
    out.q = out.q + weights[k - 1] * (input(f.b[k]) - b0);
  }
}

std::optional<Nearest> nearest_of_point(const Feature& f) {
  Nearest out;
  out.direction = input(f.a[0]) - input(f.b[0]);
  if (!nonzero(out.direction)) return std::nullopt;
  out.distance_squared = dot(out.direction, out.direction);
  set_witnesses(f, {}, out.direction, out);
  return out;
}

/// Segment W0 W1, e = W1 − W0: v = W0 + λ e with λ = −e·W0 / e·e strictly inside (0, 1), and
/// (e·e)·v = e × (W0 × e).
std::optional<Nearest> nearest_of_segment(const Feature& f) {
  const AVec w0 = input(f.a[0]) - input(f.b[0]), w1 = input(f.a[1]) - input(f.b[1]);
  const AVec e = w1 - w0;
  const Approx along0 = dot(e, w0), along1 = dot(e, w1), ee = dot(e, e);
  if (!negative(along0) || !positive(along1) || !positive(ee)) return std::nullopt;
  const AVec side = cross(w0, e);
  if (!nonzero(side)) return std::nullopt;  // the origin on the segment's line
  Nearest out;
  out.direction = cross(e, side);
  out.distance_squared = dot(side, side) / ee;
  const Approx weight = -along0 / ee;
  set_witnesses(f, {&weight, 1}, w0 + weight * e, out);
  return out;
}

/// Triangle W0 W1 W2, n = (W1 − W0) × (W2 − W0): v = (n·W0 / n·n) n, with barycentric weights
/// n·(W1 × W2), n·(W2 × W0), n·(W0 × W1) over n·n, all strictly positive.
std::optional<Nearest> nearest_of_triangle(const Feature& f) {
  std::array<AVec, 3> w;
  for (int k = 0; k < 3; ++k)
    w[k] = input(f.a[k]) - input(f.b[k]);
  const AVec n = cross(w[1] - w[0], w[2] - w[0]);
  const Approx height = dot(n, w[0]), nn = dot(n, n);
  const std::array<Approx, 3> area = {dot(n, cross(w[1], w[2])), dot(n, cross(w[2], w[0])),
                                      dot(n, cross(w[0], w[1]))};
  if (!std::all_of(area.begin(), area.end(), positive) || !positive(nn)) return std::nullopt;
  Nearest out;
  if (positive(height))
    out.direction = n;
  else if (negative(height))
    out.direction = {-n[0], -n[1], -n[2]};
  else
    return std::nullopt;  // the origin in the triangle's plane
  out.distance_squared = height * height / nn;
  const std::array<Approx, 2> weights = {area[1] / nn, area[2] / nn};
  set_witnesses(f, weights, (height / nn) * n, out);
  return out;
}

/// Points of a cloud whose side of the plane the double scan could not decide.

std::optional<ScanDirection> scan_direction(const AVec& v) {
  Real top = 0;
  for (const Approx& c : v)
    top = std::max(top, std::fabs(c.v));
  if (!(top > 0) || !std::isfinite(top)) return std::nullopt;
  const Real scale = std::ldexp(Real{1}, -std::ilogb(top));  // exact: a power of two
  ScanDirection out;
  for (int i = 0; i < 3; ++i) {
    out.d[i] = static_cast<double>(v[i].v * scale);
    // Error of d_i against the exact scaled component: v's bound, plus the rounding to double
    // (relative 2^-53, or absolute 2^-1075 below the normal range).
    const Real error = v[i].err * scale * kSafety + 0x1p-52L * std::fabs(out.d[i]) + 0x1p-1074L;
    out.w[i] = static_cast<double>((error + 0x1p-50L * std::fabs(out.d[i])) * (1 + 0x1p-45L));
  }
  return out;
}

/// The exact direction of v (a positive multiple) in integers of the frame 2^exponent.
template <class I>
Vec3Of<I> exact_direction(const Feature& f, long exponent) {
  std::array<Vec3Of<I>, 3> w;
  for (int k = 0; k < f.size; ++k)
    w[k] = to_integer<I>(f.a[k], exponent) - to_integer<I>(f.b[k], exponent);
  if (f.size == 1) return w[0];
  if (f.size == 2) {
    const Vec3Of<I> e = w[1] - w[0];
    return cross(e, cross(w[0], e));
  }
  Vec3Of<I> n = cross(w[1] - w[0], w[2] - w[0]);
  if (sgn(dot(n, w[0])) < 0) n = {-n[0], -n[1], -n[2]};
  return n;
}

long feature_frame(const Feature& f);

/// The finest unit of the feature's and the tied points' coordinates.
long tie_frame(const Feature& f, std::span<const Vec3> a, std::span<const Vec3> b,
               const Ties& ties_a, const Ties& ties_b) {
  long lowest = feature_frame(f);
  const auto take = [&](const Vec3& p) {
    for (int i = 0; i < 3; ++i)
      if (p[i] != 0) lowest = std::min(lowest, base_exponent(p[i]));
  };
  for (std::size_t i : ties_a)
    take(a[i]);
  for (std::size_t i : ties_b)
    take(b[i]);
  return lowest;
}

/// The tied points decided exactly: v·(a − a_0) ≥ 0 and v·(b − b_0) ≤ 0; and for a feature
/// that is not connected, v·(a_k − a_0) = 0 and v·(b_k − b_0) = 0 for its own points.
template <class I>
bool ties_hold(const Feature& f, std::span<const Vec3> a, std::span<const Vec3> b,
               const Ties& ties_a, const Ties& ties_b) {
  const long exponent = tie_frame(f, a, b, ties_a, ties_b);
  const Vec3Of<I> v = exact_direction<I>(f, exponent);
  const Vec3Of<I> a0 = to_integer<I>(f.a[0], exponent), b0 = to_integer<I>(f.b[0], exponent);
  for (std::size_t i : ties_a)
    if (sgn(dot(v, to_integer<I>(a[i], exponent) - a0)) < 0) return false;
  for (std::size_t i : ties_b)
    if (sgn(dot(v, to_integer<I>(b[i], exponent) - b0)) > 0) return false;
  if (f.connected) return true;
  for (int k = 1; k < f.size; ++k)
    if (sgn(dot(v, to_integer<I>(f.a[k], exponent) - a0)) != 0 ||
        sgn(dot(v, to_integer<I>(f.b[k], exponent) - b0)) != 0)
      return false;
  return true;
}

/// Both planes support their clouds: the double scan, then the ties exactly.
bool planes_support(const Feature& f, std::span<const Vec3> a, std::span<const Vec3> b,
                    const AVec& direction) {
  const std::optional<ScanDirection> s = scan_direction(direction);
  if (!s) return false;
  // The feature's own points lie on the planes (exactly, or checked so in ties_hold).
  std::array<std::int32_t, 4> own_a{}, own_b{};
  for (int k = 0; k < f.size; ++k) {
    own_a[k] = f.pairs[k].a;
    own_b[k] = f.pairs[k].b;
  }
  thread_local Ties ties_a, ties_b;
  ties_a.clear();
  ties_b.clear();
  if (!scan_side(a, f.a[0], *s, 1.0, {own_a.data(), std::size_t(f.size)}, ties_a)) return false;
  if (!scan_side(b, f.b[0], *s, -1.0, {own_b.data(), std::size_t(f.size)}, ties_b)) return false;
  if (ties_a.empty() && ties_b.empty() && f.connected) return true;
  try {
    return ties_hold<Wide>(f, a, b, ties_a, ties_b);
  } catch (const WideOverflow&) {
    return ties_hold<Int>(f, a, b, ties_a, ties_b);  // the same test, with room to grow
  }
}

/// The finest unit of the feature's coordinates: each is an integer multiple of 2^result.
long feature_frame(const Feature& f) {
  long lowest = std::numeric_limits<long>::max();
  for (int k = 0; k < f.size; ++k)
    for (const Vec3* p : {&f.a[k], &f.b[k]})
      for (int i = 0; i < 3; ++i)
        if ((*p)[i] != 0) lowest = std::min(lowest, base_exponent((*p)[i]));
  return lowest == std::numeric_limits<long>::max() ? 0 : lowest;
}

/// The feature's points and W_k = a_k − b_k as integers of its frame.
template <class I>
struct IntegerFeature {
  long exponent = 0;
  std::array<Vec3Of<I>, 4> a, b, w;
};

template <class I>
IntegerFeature<I> integer_feature(const Feature& f) {
  IntegerFeature<I> out;
  out.exponent = feature_frame(f);
  for (int k = 0; k < f.size; ++k) {
    out.a[k] = to_integer<I>(f.a[k], out.exponent);
    out.b[k] = to_integer<I>(f.b[k], out.exponent);
    out.w[k] = out.a[k] - out.b[k];
  }
  return out;
}

/// ‖v‖² = num/den·4^exponent exactly (see Nearest): |W0|², |W0 × e|²/|e|² or (n·W0)²/|n|².
template <class I>
struct Fraction {
  I num, den;
  long exponent = 0;
};

template <class I>
Fraction<I> exact_distance_squared(const Feature& f) {
  const IntegerFeature<I> x = integer_feature<I>(f);
  Fraction<I> out{0, 1, x.exponent};
  if (f.size == 1) {
    out.num = dot(x.w[0], x.w[0]);
  } else if (f.size == 2) {
    const Vec3Of<I> e = x.w[1] - x.w[0], side = cross(x.w[0], e);
    out.num = dot(side, side);
    out.den = dot(e, e);
  } else {
    const Vec3Of<I> n = cross(x.w[1] - x.w[0], x.w[2] - x.w[0]);
    const I h = dot(n, x.w[0]);
    out.num = h * h;
    out.den = dot(n, n);
  }
  return out;
}

void set_exact_distance_squared(const Feature& f, mpq_ptr out) {
  const Fraction<Int> d2 = exact_distance_squared<Int>(f);
  const long shift = 2 * d2.exponent;
  mpz_mul_2exp(mpq_numref(out), d2.num.get_mpz_t(), shift > 0 ? shift : 0);
  mpz_mul_2exp(mpq_denref(out), d2.den.get_mpz_t(), shift < 0 ? -shift : 0);
}

/// The distance's nearest double, exactly (when the long double interval straddles a rounding
/// boundary): with Wide integers, or GMP's where those overflow or the value is not normal.
double exact_distance(const Feature& f) {
  try {
    const Fraction<Wide> d2 = exact_distance_squared<Wide>(f);
    if (const std::optional<double> r = detail::nearest_sqrt(d2.num, d2.den, 2 * d2.exponent))
      return *r;
  } catch (const WideOverflow&) {
  }
  Mpq d2;
  set_exact_distance_squared(f, d2.get());
  return detail::nearest_sqrt(d2.get());
}

/// The barycentric weights of the feature's nearest point as integers: p = (D·a_0 + Σ_{k≥1} c_k
/// (a_k − a_0)) / D, D > 0 (see the nearest_of_* above).
template <class I>
void exact_weights(const IntegerFeature<I>& x, int size, std::array<I, 3>& c, I& d) {
  const auto& w = x.w;
  if (size == 2) {
    const Vec3Of<I> e = w[1] - w[0];
    c[0] = -dot(e, w[0]);
    d = dot(e, e);
  } else if (size == 3) {
    const Vec3Of<I> n = cross(w[1] - w[0], w[2] - w[0]);
    c[0] = dot(n, cross(w[2], w[0]));
    c[1] = dot(n, cross(w[0], w[1]));
    d = dot(n, n);
  }
}

double nearest_quotient_of(const Int& num, const Int& den, long exponent) {
  return detail::nearest_double(num.get_mpz_t(), den.get_mpz_t(), exponent);
}
double nearest_quotient_of(const Wide& num, const Wide& den, long exponent) {
  if (const std::optional<double> r = detail::nearest_quotient(num, den, exponent)) return *r;
  Int n, d;
  num.to_mpz(n.get_mpz_t());
  den.to_mpz(d.get_mpz_t());
  return nearest_quotient_of(n, d, exponent);
}

/// The feature's weights λ_0 = (D − Σ c_k)/D, λ_k = c_k/D as long doubles (ratio_estimate);
/// false for GMP's integers, whose sums are rounded exactly instead.
bool weight_estimates(const std::array<Wide, 3>& c, const Wide& d, int size,
                      std::array<long double, 4>& out) {
  Wide rest = d;
  for (int k = 1; k < size; ++k) {
    if (sgn(c[k - 1]) < 0) return false;  // not for a feature decided to hold its point
    out[k] = ratio_estimate(c[k - 1], d);
    rest -= c[k - 1];
  }
  if (sgn(rest) < 0) return false;
  out[0] = ratio_estimate(rest, d);
  return true;
}
bool weight_estimates(const std::array<Int, 3>&, const Int&, int, std::array<long double, 4>&) {
  return false;
}

/// The witness points' nearest doubles: from the exact weights in long double where that shows
/// them (nearest_weighted_sum), else exactly.
template <class I>
std::pair<Vec3, Vec3> exact_witnesses(const Feature& f) {
  const IntegerFeature<I> x = integer_feature<I>(f);
  std::array<I, 3> c{0, 0, 0};
  I d = 1;
  exact_weights(x, f.size, c, d);
  std::array<long double, 4> weights{};
  const bool estimated = weight_estimates(c, d, f.size, weights);
  const auto combine = [&](const std::array<Vec3Of<I>, 4>& points, const std::array<Vec3, 4>& xs) {
    if (estimated)
      if (const std::optional<Vec3> w = nearest_weighted_sum({weights.data(), std::size_t(f.size)},
                                                             {xs.data(), std::size_t(f.size)}))
        return *w;
    Vec3 out;
    for (int j = 0; j < 3; ++j) {
      I sum = d * points[0][j];
      for (int k = 1; k < f.size; ++k)
        sum += c[k - 1] * (points[k][j] - points[0][j]);
      out[j] = nearest_quotient_of(sum, d, x.exponent);
    }
    return out;
  };
  return {combine(x.a, f.a), combine(x.b, f.b)};
}

std::pair<Vec3, Vec3> exact_witnesses(const Feature& f) {
  try {
    return exact_witnesses<Wide>(f);
  } catch (const WideOverflow&) {
    return exact_witnesses<Int>(f);
  }
}

/// The certificate from a decided Nearest: the roundings in long double where their interval
/// shows them, else exactly.
DistanceCertificate answer(const Feature& f, const Nearest& nearest, bool intersect) {
  DistanceCertificate out;
  out.intersect = intersect;
  const std::optional<Vec3> p = nearest_point(nearest.p), q = nearest_point(nearest.q);
  if (p && q) {
    out.witness_a = *p;
    out.witness_b = *q;
  } else {
    std::tie(out.witness_a, out.witness_b) = exact_witnesses(f);
  }
  if (!intersect) {
    const std::optional<double> distance = nearest_sqrt(nearest.distance_squared);
    out.distance = distance ? *distance : exact_distance(f);
    out.distance_squared =
        lazy_rational(false, [f](mpq_ptr value) { set_exact_distance_squared(f, value); });
  }
  out.feature.simplex.assign(f.pairs.begin(), f.pairs.begin() + f.size);
  return out;
}

/// Four pairs: the hulls intersect when the origin is decided strictly inside the pairs'
/// tetrahedron, with its common point as both witnesses.
std::optional<DistanceCertificate> tetrahedron_certificate(const Feature& f) {
  const std::optional<Vec3> common = enclosed_origin_witness(f.a, f.b);
  if (!common) return std::nullopt;
  DistanceCertificate out;
  out.intersect = true;
  out.witness_a = out.witness_b = *common;
  out.feature.simplex.assign(f.pairs.begin(), f.pairs.end());
  return out;
}

}  // namespace

std::optional<DistanceCertificate> certify_distance_filtered(std::span<const Vec3> a,
                                                             std::span<const Vec3> b,
                                                             const DistanceHint& hint) {
  const std::optional<Feature> f = feature_of(a, b, hint);
  if (!f) return std::nullopt;
  if (f->size == 4) return tetrahedron_certificate(*f);
  if (f->size == 1 && f->a[0] == f->b[0]) {  // a shared point: intersecting
    Nearest same;
    set_witnesses(*f, {}, AVec{}, same);
    return answer(*f, same, true);
  }
  const std::optional<Nearest> nearest = f->size == 1   ? nearest_of_point(*f)
                                         : f->size == 2 ? nearest_of_segment(*f)
                                                        : nearest_of_triangle(*f);
  if (!nearest || !planes_support(*f, a, b, nearest->direction)) return std::nullopt;
  return answer(*f, *nearest, false);
}

}  // namespace gjklab::exact::detail
