// The answer of a distance sub-algorithm on one simplex, shared by the sub-algorithms that
// are not Johnson's (signed volumes, Voronoi regions); and the evaluation of a closest point
// inside a triangle that every sub-algorithm (Johnson's too) uses.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// The sub-simplex whose convex hull holds the point of a simplex closest to the origin.
template <class T>
struct SubsimplexSolutionT {
  bool found = false;                   ///< false when the sub-algorithm could not decide
  std::uint8_t subset = 0;              ///< bitmask of the kept points (bit i ↔ y_i)
  std::array<T, 4> weights{};           ///< barycentric weights λ_i of the kept points; 0 outside
  Vec3T<T> closest = Vec3T<T>::Zero();  ///< v = Σ λ_i y_i (three kept points: see below)
};
using SubsimplexSolution = SubsimplexSolutionT<double>;

/// True if the point p at distance `moved` from Σ λ y (the weights λ of the triangle y_i y_j
/// y_k, its plane's normal n = (y_j − y_i) × (y_k − y_i)) certainly lies inside the triangle:
/// p's own weights differ from λ_k by at most (moved + rounding)/h_k, h_k = ‖n‖/‖opposite
/// edge‖ the triangle's height over the edge opposite y_k, and every λ_k exceeds twice that.
/// The rounding term, 64·ε·max‖y‖, covers the sum's and p's own rounding.
template <class T>
bool foot_inside_triangle(const Vec3T<T>& yi, const Vec3T<T>& yj, const Vec3T<T>& yk,
                          const std::array<T, 3>& weights, T n_norm, T moved, T max_norm) {
  const T shift = moved + 64 * std::numeric_limits<T>::epsilon() * max_norm;
  const std::array<T, 3> opposite{(yk - yj).norm(), (yk - yi).norm(), (yj - yi).norm()};
  for (int k = 0; k < 3; ++k)
    if (!(weights[k] * n_norm > 2 * shift * opposite[k])) return false;
  return true;
}

/// A bound of the rounding of n = e1 × e2 across n itself, times ‖n‖: the tilt of the computed
/// normal. Each component of n is within 8u(|e1_a e2_b| + |e1_b e2_a|) (u the unit roundoff; the
/// products, their difference and the rounding of the edges themselves, doubled), and only
/// its part across n turns it: Σ_c δn_c·√(1 − n̂_c²). A plane's foot n (y·n)/‖n‖² then has its
/// length, the distance GJK reports, within ‖y‖·tilt/‖n‖ of the exact foot's.
template <class T>
T normal_tilt(const Vec3T<T>& e1, const Vec3T<T>& e2, const Vec3T<T>& n, T n_norm) {
  const T u = std::numeric_limits<T>::epsilon() / 2;
  T tilt = 0;
  for (int c = 0; c < 3; ++c) {
    const int a = (c + 1) % 3, b = (c + 2) % 3;
    const T dn = 8 * u * (std::abs(e1[a] * e2[b]) + std::abs(e1[b] * e2[a]));
    const T nc = n[c] / n_norm;
    tilt += dn * std::sqrt(std::max(T(0), 1 - nc * nc));
  }
  return tilt;
}

/// The closest point to the origin of the triangle y_i y_j y_k, for a sub-simplex whose weights
/// put it inside the triangle: `weighted` is the sub-algorithm's v = Σ λ y. The projection onto
/// the triangle's plane, v = n (y·n) / ‖n‖² with n = (y_j − y_i) × (y_k − y_i) and y the vertex
/// of least norm, is parallel to n up to n's rounding, a relative u·‖e1‖‖e2‖/‖n‖ (u the unit
/// roundoff, e1 and e2 the edges); the sum loses a relative u·max‖y‖/‖v‖ of its direction to
/// cancellation. Near contact (‖v‖ a relative 1e-9 of the points, fcl issue 445's boxes) that
/// left v tilted off the normal by 1e-7, so that a vertex of the face itself looked like the
/// support point beyond the origin and the query ended there, 5 times the depth away from the
/// right answer. The projection replaces the sum only as a correction of the sum's rounding:
///  - where its direction is the more accurate one (‖e1‖‖e2‖/‖n‖ < max‖y‖/‖v‖, compared squared
///    on points scaled by 1/max‖y‖), and
///  - where the plane's foot lies inside the triangle as far as rounding can tell: within
///    64·ε·max‖y‖ (ε the machine epsilon) of the sum, a bound far above the sum's own
///    rounding, or, farther away, where every weight is large enough that moving the point by that
///    distance cannot make it negative (foot_inside_triangle). Otherwise the sub-algorithm's choice
///    of the triangle was decided by rounding (a weight near 0 that is negative in exact
///    arithmetic), the plane's foot lies outside the triangle, and ‖v‖ would drop below the
///    distance (a needle triangle of parallel edges 1.2e-8 rad apart: 2.43e-11 for 2.71e-11). The
///    second case is a sliver triangle whose weights lost 1e-9 of the sum to rounding while each is
///    far from 0 (fcl issue 399's boxes, 3.4e-5 deep: the sum said "apart, 1.7e-9"). This
///    second case also needs the foot's length to be as accurate as the points: the tilt of the
///    computed normal (normal_tilt) moves it by up to ‖y‖·tilt/‖n‖, which must stay within
///    64·ε·max‖y‖; a needle triangle's normal is too uncertain for that, and its foot came out
///    below the distance (nearly parallel segments 1.34e-9 apart: 1.3397e-9, and a point
///    5.8e-13 from a needle taken for contact).
template <class T>
Vec3T<T> triangle_closest_point(const Vec3T<T>& yi, const Vec3T<T>& yj, const Vec3T<T>& yk,
                                const Vec3T<T>& weighted, const std::array<T, 3>& weights) {
  const T ni = yi.squaredNorm(), nj = yj.squaredNorm(), nk = yk.squaredNorm();
  const T mm = std::max({ni, nj, nk});
  if (!(mm > 0) || !std::isfinite(mm)) return weighted;
  const Vec3T<T> e1 = yj - yi, e2 = yk - yi;
  const Vec3T<T> n = e1.cross(e2);
  const T nn = n.squaredNorm();
  // ‖e1‖²‖e2‖²‖v‖² < ‖n‖² max‖y‖², each factor divided by max‖y‖² so that no product over- or
  // underflows for points that a cross product can take.
  const T lhs = (e1.squaredNorm() / mm) * (e2.squaredNorm() / mm) * (weighted.squaredNorm() / mm);
  if (!(nn > 0) || !(lhs < (nn / mm) / mm)) return weighted;
  const Vec3T<T>& nearest = ni <= nj ? (ni <= nk ? yi : yk) : (nj <= nk ? yj : yk);
  const Vec3T<T> projection = (nearest.dot(n) / nn) * n;
  if (!is_finite(projection)) return weighted;
  const T moved_squared = (projection - weighted).squaredNorm();
  const T slack = 64 * std::numeric_limits<T>::epsilon();
  if (moved_squared <= slack * slack * mm) return projection;
  const T n_norm = std::sqrt(nn), max_norm = std::sqrt(mm);
  const bool length_accurate =
      nearest.norm() * normal_tilt(e1, e2, n, n_norm) <= slack * max_norm * n_norm;
  const bool inside = length_accurate && foot_inside_triangle(yi, yj, yk, weights, n_norm,
                                                              std::sqrt(moved_squared), max_norm);
  return inside ? projection : weighted;
}

/// A sub-algorithm's solution with its v recomputed by triangle_closest_point when it keeps
/// exactly three points (of y).
template <class Solution, class T>
void refine_triangle_point(Solution& s, const std::array<Vec3T<T>, 4>& y) {
  if (std::popcount(static_cast<unsigned>(s.subset)) != 3) return;
  std::array<int, 3> kept{};
  int count = 0;
  for (int i = 0; i < 4; ++i)
    if (s.subset & (1u << i)) kept[count++] = i;
  s.closest = triangle_closest_point(y[kept[0]], y[kept[1]], y[kept[2]], s.closest,
                                     {s.weights[kept[0]], s.weights[kept[1]], s.weights[kept[2]]});
}

}  // namespace gjklab
