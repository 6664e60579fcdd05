// Sphere-swept shapes: a convex core swept by a ball (a sphere is a point core, a capsule a
// segment core, a rounded polytope any polytope core).
//
// The swept shape A ⊕ ball(r_A) has the support map s_A(d) + r_A·d/‖d‖ (SphereSwept). Distance
// queries need not see it: the distance between two swept shapes is the distance between their
// cores minus r_A + r_B, and they intersect exactly when the cores are at most r_A + r_B apart.
// So GJK runs on the cores (polytopes, with their exact stopping tests) and the answer is
// shifted afterwards; only the boolean GJK, which has no distance to shift, walks the swept
// support map itself.
#pragma once

#include <algorithm>

#include "gjklab/geometry/types.hpp"
#include "gjklab/gjk/result.hpp"

namespace gjklab {

/// The radii of a pair of sphere-swept shapes (length units, each >= 0); zero radii are the
/// plain cores.
struct SweptRadii {
  double a = 0;
  double b = 0;

  double sum() const { return a + b; }
  bool any() const { return a != 0 || b != 0; }
};

namespace detail {

/// The unit vector from the core witness a to the core witness b, or +x when they coincide
/// (the direction is then arbitrary, and callers only use it with a zero core distance).
inline Vec3 core_axis(const Vec3& witness_a, const Vec3& witness_b) {
  const Vec3 d = witness_b - witness_a;
  const double n = d.norm();
  return n > 0 ? Vec3(d / n) : Vec3::UnitX();
}

}  // namespace detail

/// The distance answer for the swept shapes from the answer for their cores.
///
/// Separated cores at distance δ > r_A + r_B: distance δ − (r_A + r_B), witnesses moved from
/// the core witnesses towards each other by the radii. Cores at most r_A + r_B apart (touching
/// counts as intersecting, as everywhere): intersect, distance 0, and the witnesses are the
/// moved points, which then lie inside the other shape (along the core axis). Intersecting
/// cores: unchanged. The bracket is shifted like the distance (and clamped at 0);
/// iterations, support calls, the simplex and the termination stay the core query's.
inline DistanceResult swept_distance(DistanceResult core, const SweptRadii& radii) {
  if (core.intersect) return core;
  const Vec3 axis = detail::core_axis(core.witness_a, core.witness_b);
  core.witness_a += radii.a * axis;
  core.witness_b -= radii.b * axis;
  core.lower_bound = std::max(0.0, core.lower_bound - radii.sum());
  core.upper_bound = std::max(0.0, core.upper_bound - radii.sum());
  if (core.distance <= radii.sum()) {
    core.intersect = true;
    core.distance = 0;
  } else {
    core.distance -= radii.sum();
  }
  return core;
}

/// The penetration answer for the swept shapes from the answer for their cores (EPA and the
/// penetration queries of the peers; see PenetrationResult for the conventions).
///
/// Intersecting cores with depth p and normal n: depth p + r_A + r_B along the same n, the
/// deepest points moved outwards by the radii (witness_a − witness_b = depth·n still holds).
/// Separated cores at distance δ: separated by δ − (r_A + r_B) when that is positive, else
/// intersecting with depth r_A + r_B − δ along n = (witness_b − witness_a)/δ, with the moved
/// witnesses as deepest points.
template <class Result>
Result swept_penetration(Result core, const SweptRadii& radii) {
  const double r = radii.sum();
  if (core.intersect) {
    core.depth += r;
    core.witness_a += radii.a * core.normal;
    core.witness_b -= radii.b * core.normal;
    return core;
  }
  core.witness_a += radii.a * core.normal;
  core.witness_b -= radii.b * core.normal;
  if (core.distance <= r) {
    core.intersect = true;
    core.depth = r - core.distance;
    core.distance = 0;
  } else {
    core.distance -= r;
  }
  return core;
}

}  // namespace gjklab
