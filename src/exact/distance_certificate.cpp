// The distance and intersection certificate: exact GJK warm-started from a floating-point
// simplex (see certificate.hpp). No CGAL here.
//
// The simplex's points W_k = A_i − B_j are integer vectors in the clouds' common frame. The
// point of their hull closest to the origin is v = N / D with an integer vector N and an
// integer D > 0, from Cramer's rule on the Gram system of the sub-simplex that holds it; every
// test below is a comparison of integers.
#include <gmp.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "gjklab/exact/certificate.hpp"
#include "gmp_support.hpp"
#include "integer_geometry.hpp"

namespace gjklab::exact {

namespace {

using detail::Int;
using detail::IntVec;
using detail::operator-;
using detail::cross;
using detail::dot;

/// The point of the hull of a few integer points closest to the origin: v = numerator /
/// denominator, v = Σ weights[k]·W_k / denominator over the points in `subset`.
struct ExactClosest {
  std::uint8_t subset = 0;  ///< bit k ↔ point k
  std::array<Int, 4> weights;
  Int denominator;  ///< > 0
  IntVec numerator;
};

/// The closest point of the affine hull of the points of `subset` (bit k ↔ w[k]), with its
/// barycentric weights; nullopt when those points are affinely dependent.
std::optional<ExactClosest> affine_closest(std::span<const IntVec> w, std::uint8_t subset) {
  std::array<int, 4> idx{};
  int k = 0;
  for (int i = 0; i < static_cast<int>(w.size()); ++i)
    if (subset & (1u << i)) idx[k++] = i;
  ExactClosest c;
  c.subset = subset;
  const IntVec& w0 = w[idx[0]];
  if (k == 1) {
    c.weights[idx[0]] = 1;
    c.denominator = 1;
    c.numerator = w0;
    return c;
  }
  if (k == 4) {
    // Four points span space when independent: the closest point of the affine hull is the
    // origin, with barycentric weights from Cramer's rule on [e1 e2 e3]·μ = −w0.
    const IntVec e1 = w[idx[1]] - w0, e2 = w[idx[2]] - w0, e3 = w[idx[3]] - w0;
    const IntVec minus_w0 = {-w0[0], -w0[1], -w0[2]};
    Int det = dot(e1, cross(e2, e3));
    if (sgn(det) == 0) return std::nullopt;
    Int l1 = dot(minus_w0, cross(e2, e3));
    Int l2 = dot(e1, cross(minus_w0, e3));
    Int l3 = dot(e1, cross(e2, minus_w0));
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
  const IntVec e1 = w[idx[1]] - w0;
  if (k == 2) {
    const Int g = dot(e1, e1);
    if (sgn(g) == 0) return std::nullopt;
    const Int r = -dot(e1, w0);
    c.weights[idx[0]] = g - r;
    c.weights[idx[1]] = r;
    c.denominator = g;
  } else {
    const IntVec e2 = w[idx[2]] - w0;
    const Int g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
    const Int r1 = -dot(e1, w0), r2 = -dot(e2, w0);
    const Int det = g11 * g22 - g12 * g12;
    if (sgn(det) == 0) return std::nullopt;
    const Int l1 = r1 * g22 - g12 * r2, l2 = g11 * r2 - g12 * r1;
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
bool is_closest(const ExactClosest& c, std::span<const IntVec> w) {
  for (std::size_t k = 0; k < w.size(); ++k)
    if ((c.subset & (1u << k)) && sgn(c.weights[k]) < 0) return false;
  const Int nn = dot(c.numerator, c.numerator);
  for (std::size_t k = 0; k < w.size(); ++k)
    if (!(c.subset & (1u << k)) && c.denominator * dot(c.numerator, w[k]) < nn) return false;
  return true;
}

/// The exact closest point of the hull of 1 … 4 integer points: the full set first (the
/// usual case for a converged hint), then every other subset until one passes is_closest.
/// By Carathéodory some affinely independent subset holds the closest point in its relative
/// interior, so the search succeeds; nullopt only guards against the impossible.
std::optional<ExactClosest> closest_on_hull(std::span<const IntVec> w) {
  const auto full = static_cast<std::uint8_t>((1u << w.size()) - 1);
  for (std::uint8_t subset = full; subset > 0; --subset) {
    std::optional<ExactClosest> c = affine_closest(w, subset);
    if (c && is_closest(*c, w)) return c;
  }
  return std::nullopt;
}

/// q := N·N / D² · 4^exponent, in lowest terms.
void squared_length(const IntVec& n, const Int& d, long exponent, mpq_ptr q) {
  const Int nn = dot(n, n), dd = d * d;
  mpq_set_num(q, nn.get_mpz_t());
  mpq_set_den(q, dd.get_mpz_t());
  mpq_canonicalize(q);
  if (exponent > 0) mpq_mul_2exp(q, q, static_cast<mp_bitcnt_t>(2 * exponent));
  if (exponent < 0) mpq_div_2exp(q, q, static_cast<mp_bitcnt_t>(-2 * exponent));
}

/// The nearest double to Σ weights[k]·points[k] / denominator · 2^exponent, per coordinate.
Vec3 nearest_combination(const ExactClosest& c, std::span<const IntVec> points, long exponent) {
  Vec3 out;
  Int sum;
  for (int j = 0; j < 3; ++j) {
    sum = 0;
    for (std::size_t k = 0; k < points.size(); ++k)
      if (c.subset & (1u << k)) sum += c.weights[k] * points[k][j];
    out[j] = detail::nearest_double(sum.get_mpz_t(), c.denominator.get_mpz_t(), exponent);
  }
  return out;
}

/// The exact GJK state: the simplex's index pairs and their points in A, in B and in A − B.
struct ExactSimplex {
  std::vector<exact::IndexPair> pairs;
  std::vector<IntVec> a, b, w;

  bool contains(const IntVec& x) const { return std::find(w.begin(), w.end(), x) != w.end(); }
  void push(const exact::IndexPair& p, IntVec pa, IntVec pb) {
    IntVec pw = pa - pb;
    pairs.push_back(p);
    a.push_back(std::move(pa));
    b.push_back(std::move(pb));
    w.push_back(std::move(pw));
  }
  void keep(std::uint8_t subset) {
    std::size_t out = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      if (!(subset & (1u << k))) continue;
      if (out != k) {
        pairs[out] = pairs[k];
        a[out] = std::move(a[k]);
        b[out] = std::move(b[k]);
        w[out] = std::move(w[k]);
      }
      ++out;
    }
    pairs.resize(out);
    a.resize(out);
    b.resize(out);
    w.resize(out);
  }
};

/// The hint's usable points: in range, not repeated, at most four.
ExactSimplex starting_simplex(std::span<const Vec3> a, std::span<const Vec3> b,
                              const DistanceHint& hint, long exponent) {
  ExactSimplex s;
  auto in_range = [](std::int32_t i, std::size_t n) {
    return i >= 0 && static_cast<std::size_t>(i) < n;
  };
  for (const IndexPair& p : hint.simplex) {
    if (s.pairs.size() == 4) break;
    if (!in_range(p.a, a.size()) || !in_range(p.b, b.size())) continue;
    IntVec pa = detail::to_integer(a[p.a], exponent), pb = detail::to_integer(b[p.b], exponent);
    if (s.contains(pa - pb)) continue;
    s.push(p, std::move(pa), std::move(pb));
  }
  if (s.pairs.empty())
    s.push({0, 0}, detail::to_integer(a[0], exponent), detail::to_integer(b[0], exponent));
  return s;
}

}  // namespace

std::optional<DistanceCertificate> certify_distance(std::span<const Vec3> a,
                                                    std::span<const Vec3> b,
                                                    const DistanceHint& hint, int max_steps) {
  if (a.empty() || b.empty()) return std::nullopt;
  const detail::IntegerFrame frame = detail::integer_frame(a, b);
  ExactSimplex simplex = starting_simplex(a, b, hint, frame.exponent);
  for (int step = 0; step <= max_steps; ++step) {
    const std::optional<ExactClosest> c = closest_on_hull(simplex.w);
    if (!c) return std::nullopt;
    const auto finish = [&](bool intersect) {
      DistanceCertificate out;
      out.intersect = intersect;
      out.witness_a = nearest_combination(*c, simplex.a, frame.exponent);
      out.witness_b = nearest_combination(*c, simplex.b, frame.exponent);
      simplex.keep(c->subset);
      detail::Mpq d2;
      if (!intersect) squared_length(c->numerator, c->denominator, frame.exponent, d2.get());
      out.distance_squared = detail::to_rational(d2.get());
      out.distance = detail::nearest_sqrt(d2.get());
      out.feature.simplex = simplex.pairs;
      out.repair_steps = step;
      return out;
    };
    if (detail::is_zero(c->numerator)) return finish(true);  // the origin is in the hull

    // Separated iff min over a of N·A − max over b of N·B ≥ N·N / D.
    const detail::Extreme low = detail::extreme_point(a, c->numerator, frame, false);
    const detail::Extreme high = detail::extreme_point(b, c->numerator, frame, true);
    if (c->denominator * (low.value - high.value) >= dot(c->numerator, c->numerator))
      return finish(false);

    // Not the closest point: continue from its sub-simplex and the violating support point.
    const IndexPair next{static_cast<std::int32_t>(low.index),
                         static_cast<std::int32_t>(high.index)};
    IntVec pa = detail::to_integer(a[low.index], frame.exponent);
    IntVec pb = detail::to_integer(b[high.index], frame.exponent);
    simplex.keep(c->subset);
    // In exact arithmetic the new point violates the test, so it is not in the simplex and
    // the distance strictly decreases; a repeat would mean a bug, and is never an answer.
    if (simplex.contains(pa - pb) || simplex.pairs.size() >= 4) return std::nullopt;
    simplex.push(next, std::move(pa), std::move(pb));
  }
  return std::nullopt;
}

}  // namespace gjklab::exact
