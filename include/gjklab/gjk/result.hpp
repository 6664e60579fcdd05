// Result structs shared by all algorithms: one query, one input, one result.
#pragma once

#include "gjklab/geometry/types.hpp"
#include "gjklab/gjk/simplex.hpp"
#include "gjklab/gjk/termination.hpp"

namespace gjklab {

/// Answer of a boolean (intersection-only) query.
struct BooleanResult {
  bool intersect = false;  ///< closed shapes share a point (touching counts as intersecting)
  int iterations = 0;      ///< main-loop iterations executed
  int support_calls = 0;   ///< support evaluations of the Minkowski difference (one per shape pair)
  Termination termination = Termination::converged;
};

/// Answer of a distance query.
struct DistanceResult {
  bool intersect = false;         ///< closed shapes share a point (within the contact tolerance)
  double distance = 0;            ///< Euclidean distance (length units); 0 when intersecting
  Vec3 witness_a = Vec3::Zero();  ///< point of A closest to B (world frame)
  Vec3 witness_b = Vec3::Zero();  ///< point of B closest to A; witness_a − witness_b = v
  Vec3 closest = Vec3::Zero();    ///< v: the point of A − B closest to the origin
  /// Best lower bound of the distance seen, max(0, v·w/‖v‖) over the iterations; the true
  /// distance lies in [lower_bound, distance] up to rounding.
  double lower_bound = 0;
  /// The final simplex (for penetration-depth algorithms that start from it, and for traces).
  Simplex simplex;
  int iterations = 0;
  int support_calls = 0;
  Termination termination = Termination::converged;
};

/// Answer of a penetration-depth query (EPA and the depth peers).
///
/// Conventions. The depth is the distance from the origin to the boundary of A − B, i.e. the
/// length of the shortest translation that separates the shapes (0 when they only touch or
/// when A − B has no interior). `normal` is the unit direction of that translation applied to
/// B: moving B by depth·normal (or A by −depth·normal) brings the shapes into touching
/// contact, so for a shallow overlap it points from A towards B. For separated pairs the
/// same convention gives normal = (witness_b − witness_a) / distance.
struct PenetrationResult {
  bool intersect = false;  ///< closed shapes share a point (touching counts as intersecting)
  /// Distance when separated (the GJK distance for EPA); 0 when intersecting.
  double distance = 0;
  /// Penetration depth (length units) when intersecting; 0 when separated.
  double depth = 0;
  Vec3 normal = Vec3::UnitX();  ///< unit vector, see above; never NaN
  /// Intersecting: the deepest points, witness_a − witness_b = depth·normal.
  /// Separated: the closest points, witness_b − witness_a = distance·normal.
  Vec3 witness_a = Vec3::Zero();
  Vec3 witness_b = Vec3::Zero();
  int iterations = 0;     ///< main-loop iterations of the depth phase (see each algorithm)
  int support_calls = 0;  ///< Minkowski support evaluations of the whole query
  Termination termination = Termination::converged;
};

}  // namespace gjklab
