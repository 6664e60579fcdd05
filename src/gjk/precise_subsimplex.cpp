#include "gjklab/gjk/precise_subsimplex.hpp"

#include <bit>
#include <cmath>

#include "gjklab/geometry/double_word.hpp"

namespace gjklab {

namespace {

using DVec = std::array<DoubleWord, 3>;

/// The 15 non-empty subsets of {0,1,2,3} by size, then mask: Johnson's order (johnson.cpp).
constexpr std::array<std::uint8_t, 15> kSubsetsBySize = {1,  2,  4, 8,  3,  5,  6, 9,
                                                         10, 12, 7, 11, 13, 14, 15};

int first_index(std::uint8_t mask) {
  return std::countr_zero(static_cast<unsigned>(mask));
}

/// x as hi + lo doubles: exact for float and double, and for long double within double's
/// exponent range (its 64-bit significand fits in two doubles' 106 bits).
template <class T>
DoubleWord split(T x) {
  const double hi = static_cast<double>(x);
  return {hi, static_cast<double>(x - static_cast<T>(hi)), 0};
}

/// hi + lo in T (for double: hi + lo rounded once; long double keeps more of lo).
template <class T>
T join(const DoubleWord& x) {
  return static_cast<T>(x.hi) + static_cast<T>(x.lo);
}

DoubleWord dot(const DVec& x, const DVec& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

/// The cofactors of every subset of the points (Johnson's recursion, johnson.hpp), each in
/// double-word arithmetic: delta[X][i] = Δ_i(X), total[X] = Δ(X).
struct Cofactors {
  DoubleWord delta[16][4];
  DoubleWord total[16];
};

void fill_cofactors(const std::array<DVec, 4>& y, int count, Cofactors& c) {
  const std::uint8_t all = static_cast<std::uint8_t>((1u << count) - 1);
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x) continue;
    if (std::popcount(static_cast<unsigned>(x)) == 1) {
      c.delta[x][first_index(x)] = {1, 0, 0};
      c.total[x] = {1, 0, 0};
      continue;
    }
    DoubleWord total{0, 0, 0};
    for (int j = 0; j < count; ++j) {
      if (!(x & (1u << j))) continue;
      const std::uint8_t rest = static_cast<std::uint8_t>(x & ~(1u << j));
      const int k = first_index(rest);
      const DVec edge{y[k][0] - y[j][0], y[k][1] - y[j][1], y[k][2] - y[j][2]};
      DoubleWord dj{0, 0, 0};
      for (int i = k; i < count; ++i)
        if (rest & (1u << i)) dj = dj + c.delta[rest][i] * dot(edge, y[i]);
      c.delta[x][j] = dj;
      total = total + dj;
    }
    c.total[x] = total;
  }
}

/// Johnson's two tests for subset X, on the signs of the double-word values (hi carries the
/// sign of hi + lo).
bool subset_is_valid(const Cofactors& c, std::uint8_t x, int count) {
  if (!(c.total[x].hi > 0)) return false;
  for (int i = 0; i < count; ++i) {
    const bool inside = x & (1u << i);
    if (inside && !(c.delta[x][i].hi > 0)) return false;
    if (!inside && !(c.delta[x | (1u << i)][i].hi <= 0)) return false;
  }
  return true;
}

bool has_positive_cofactors(const Cofactors& c, std::uint8_t x, int count) {
  if (!(c.total[x].hi > 0)) return false;
  for (int i = 0; i < count; ++i)
    if ((x & (1u << i)) && !(c.delta[x][i].hi > 0)) return false;
  return true;
}

/// n/d in double-word (one correction step of the quotient of the high parts).
DoubleWord quotient(const DoubleWord& n, const DoubleWord& d) {
  const double q1 = n.hi / d.hi;
  const DoubleWord r = n - d * q1;
  const double q2 = r.hi / d.hi;
  DoubleWord q;
  double_word::fast_two_sum(q1, q2, q.hi, q.lo);
  return q;
}

DVec operator-(const DVec& x, const DVec& y) {
  return {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
}
DVec scaled(const DVec& x, const DoubleWord& f) {
  return {x[0] * f, x[1] * f, x[2] * f};
}
DVec cross(const DVec& x, const DVec& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}

/// The point of the affine hull of the kept points closest to the origin, from the points
/// themselves rather than from the weights: a point's projection onto the line through an
/// edge e (y − e·(y·e)/‖e‖²) or onto the plane of a triangle with normal n (n·(y·n)/‖n‖²), in
/// double-word. Near contact its size is a tiny fraction of the points', and the weights'
/// sum Σ λ_i y_i would carry the cofactors' relative error times ‖y‖ (about 1e-18 of ‖y‖ on a
/// needle triangle of aspect 1e7): enough to turn the direction of a point 1e-12 from the
/// origin by 1e-8, and with it every support plane's lower bound. The projection's direction
/// is accurate to about 2^-100 relative.
DVec affine_closest(const std::array<DVec, 4>& y, std::uint8_t x) {
  std::array<int, 4> kept{};
  int count = 0;
  for (int i = 0; i < 4; ++i)
    if (x & (1u << i)) kept[count++] = i;
  const DVec& y0 = y[kept[0]];
  if (count == 1) return y0;
  if (count == 2) {
    const DVec e = y[kept[1]] - y0;
    return y0 - scaled(e, quotient(dot(y0, e), dot(e, e)));
  }
  if (count == 3) {
    const DVec n = cross(y[kept[1]] - y0, y[kept[2]] - y0);
    return scaled(n, quotient(dot(y0, n), dot(n, n)));
  }
  const DoubleWord zero{0, 0, 0};
  return {zero, zero, zero};  // a tetrahedron with positive cofactors holds the origin
}

/// The answer for subset X: λ_i = Δ_i(X)/Δ(X) in T, and the closest point (affine_closest)
/// rounded to T and scaled back by 2^e.
template <class T>
SubsimplexSolutionT<T> solution_of(const Cofactors& c, const std::array<DVec, 4>& y, int count,
                                   std::uint8_t x, int e) {
  SubsimplexSolutionT<T> s;
  s.found = true;
  s.subset = x;
  const T total = join<T>(c.total[x]);
  for (int i = 0; i < count; ++i)
    if (x & (1u << i)) s.weights[i] = join<T>(c.delta[x][i]) / total;
  const DVec v = affine_closest(y, x);
  for (int k = 0; k < 3; ++k)
    s.closest[k] = std::ldexp(join<T>(v[k]), e);
  return s;
}

/// ‖Σ λ_i y_i‖² over the kept points: the point the weights name, which is what a query's
/// upper bound is proven from (gjk/bracket.hpp), whatever the solution's closest point says.
template <class T>
T named_norm_squared(const SubsimplexSolutionT<T>& s, const std::array<Vec3T<T>, 4>& y) {
  Vec3T<T> named = Vec3T<T>::Zero();
  for (int i = 0; i < 4; ++i)
    if (s.subset & (1u << i)) named += s.weights[i] * y[i];
  return named.squaredNorm();
}

/// For a tetrahedron said to hold the origin: that answer, or the nearest face's where the
/// face's weights name a point nearer the origin. On a needle tetrahedron the volume is of
/// the order of the double-word cofactors' rounding, its weights are noise, and the point
/// they name can be as far as the simplex is long, while the origin lies on (or within
/// rounding of) a face; in exact arithmetic the tetrahedron's own weights name the origin, so
/// the comparison never prefers a face there.
template <class T>
SubsimplexSolutionT<T> nearest_named(const SubsimplexSolutionT<T>& full,
                                     const std::array<Vec3T<T>, 4>& y) {
  SubsimplexSolutionT<T> best = full;
  T best_norm = named_norm_squared(full, y);
  for (int drop = 0; drop < 4; ++drop) {
    std::array<Vec3T<T>, 4> face{};
    std::array<int, 3> index{};
    for (int i = 0, k = 0; i < 4; ++i)
      if (i != drop) face[k] = y[i], index[k++] = i;
    const SubsimplexSolutionT<T> f = precise_closest_point(face, 3);
    if (!f.found) continue;
    SubsimplexSolutionT<T> mapped;  // the face's answer with the tetrahedron's indices
    mapped.found = true;
    mapped.closest = f.closest;
    for (int k = 0; k < 3; ++k)
      if (f.subset & (1u << k)) {
        mapped.subset = static_cast<std::uint8_t>(mapped.subset | (1u << index[k]));
        mapped.weights[index[k]] = f.weights[k];
      }
    const T norm = named_norm_squared(mapped, y);
    if (norm < best_norm) best = mapped, best_norm = norm;
  }
  return best;
}

}  // namespace

template <class T>
SubsimplexSolutionT<T> precise_closest_point(const std::array<Vec3T<T>, 4>& y, int count) {
  if (count < 1 || count > 4) return {};
  T top = 0;
  for (int i = 0; i < count; ++i) {
    if (!is_finite(y[i])) return {};
    top = std::max(top, y[i].cwiseAbs().maxCoeff());
  }
  if (!(top > 0)) {  // every point is the origin
    SubsimplexSolutionT<T> s;
    s.found = true;
    s.subset = 1;
    s.weights[0] = 1;
    return s;
  }
  // Scale so that the largest coordinate lies in [1, 2): cofactors of degree 6 then stay
  // between about 2^-900 and 2^40 for any simplex whose extent is above 2^-150 of that.
  const int e = std::ilogb(top);
  std::array<DVec, 4> p{};
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k)
      p[i][k] = split<T>(std::ldexp(y[i][k], -e));
  Cofactors c;
  fill_cofactors(p, count, c);
  const std::uint8_t all = static_cast<std::uint8_t>((1u << count) - 1);
  for (std::uint8_t x : kSubsetsBySize)
    if ((x & all) == x && subset_is_valid(c, x, count)) {
      SubsimplexSolutionT<T> s = solution_of<T>(c, p, count, x, e);
      if (!is_finite(s.closest)) return {};
      return x == 0xF ? nearest_named(s, y) : s;
    }
  // Backup: the subset with positive cofactors whose point is nearest (singletons qualify).
  SubsimplexSolutionT<T> best;
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x || !has_positive_cofactors(c, x, count)) continue;
    const SubsimplexSolutionT<T> candidate = solution_of<T>(c, p, count, x, e);
    if (!is_finite(candidate.closest)) continue;
    if (!best.found || candidate.closest.squaredNorm() < best.closest.squaredNorm())
      best = candidate;
  }
  return best;
}

template SubsimplexSolutionT<float> precise_closest_point(const std::array<Vec3T<float>, 4>&, int);
template SubsimplexSolutionT<double> precise_closest_point(const std::array<Vec3T<double>, 4>&,
                                                           int);
template SubsimplexSolutionT<long double> precise_closest_point(
    const std::array<Vec3T<long double>, 4>&, int);

}  // namespace gjklab
