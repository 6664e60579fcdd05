// Result structs shared by all algorithms: one query, one input, one result.
#pragma once

#include <limits>
#include <type_traits>

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

/// Answer of a distance query, in the query's scalar type T (DistanceResult: double).
template <class T>
struct DistanceResultT {
  bool intersect = false;  ///< closed shapes share a point (within the contact tolerance)
  T distance = 0;          ///< Euclidean distance (length units); 0 when intersecting
  Vec3T<T> witness_a = Vec3T<T>::Zero();  ///< point of A closest to B (world frame)
  Vec3T<T> witness_b = Vec3T<T>::Zero();  ///< point of B closest to A; witness_a − witness_b = v
  Vec3T<T> closest = Vec3T<T>::Zero();    ///< v: the point of A − B closest to the origin
  /// A proven bracket of the exact distance (length units): lower_bound ≤ exact distance ≤
  /// upper_bound whatever the query's rounding, with `distance` inside it (gjk/bracket.hpp).
  /// lower_bound is the best support plane's, upper_bound the kept simplex point's; an
  /// intersecting answer has lower_bound 0. `converged` means this bracket is within the
  /// options' tolerance; upper_bound is infinite where nothing could be proven.
  T lower_bound = 0;
  T upper_bound = std::numeric_limits<T>::infinity();
  /// The final simplex (for penetration-depth algorithms that start from it, and for traces).
  SimplexT<T> simplex;
  int iterations = 0;
  int support_calls = 0;
  Termination termination = Termination::converged;
};
using DistanceResult = DistanceResultT<double>;

/// The answer in double (exact from float; long double rounded to nearest).
template <class T>
DistanceResult to_double(const DistanceResultT<T>& r) {
  if constexpr (std::is_same_v<T, double>) {
    return r;
  } else {
    DistanceResult out;
    out.intersect = r.intersect;
    out.distance = static_cast<double>(r.distance);
    out.witness_a = r.witness_a.template cast<double>();
    out.witness_b = r.witness_b.template cast<double>();
    out.closest = r.closest.template cast<double>();
    out.lower_bound = static_cast<double>(r.lower_bound);
    out.upper_bound = static_cast<double>(r.upper_bound);
    out.simplex = to_double(r.simplex);
    out.iterations = r.iterations;
    out.support_calls = r.support_calls;
    out.termination = r.termination;
    return out;
  }
}

/// Answer of a penetration-depth query (EPA and the depth peers).
///
/// Conventions. The depth is the distance from the origin to the boundary of A − B, i.e. the
/// length of the shortest translation that separates the shapes (0 when they only touch or
/// when A − B has no interior). `normal` is the unit direction of that translation applied to
/// B: moving B by depth·normal (or A by −depth·normal) brings the shapes into touching
/// contact, so for a shallow overlap it points from A towards B. For separated pairs the
/// same convention gives normal = (witness_b − witness_a) / distance.
template <class T>
struct PenetrationResultT {
  bool intersect = false;  ///< closed shapes share a point (touching counts as intersecting)
  /// Distance when separated (the GJK distance for EPA); 0 when intersecting.
  T distance = 0;
  /// Penetration depth (length units) when intersecting; 0 when separated.
  T depth = 0;
  Vec3T<T> normal = Vec3T<T>::UnitX();  ///< unit vector, see above; never NaN
  /// Intersecting: the deepest points, witness_a − witness_b = depth·normal.
  /// Separated: the closest points, witness_b − witness_a = distance·normal.
  Vec3T<T> witness_a = Vec3T<T>::Zero();
  Vec3T<T> witness_b = Vec3T<T>::Zero();
  int iterations = 0;     ///< main-loop iterations of the depth phase (see each algorithm)
  int support_calls = 0;  ///< Minkowski support evaluations of the whole query
  Termination termination = Termination::converged;
};

using PenetrationResult = PenetrationResultT<double>;

/// The answer in double (exact from float; long double rounded to nearest).
template <class T>
PenetrationResult to_double(const PenetrationResultT<T>& r) {
  PenetrationResult out;
  out.intersect = r.intersect;
  out.distance = static_cast<double>(r.distance);
  out.depth = static_cast<double>(r.depth);
  out.normal = r.normal.template cast<double>();
  out.witness_a = r.witness_a.template cast<double>();
  out.witness_b = r.witness_b.template cast<double>();
  out.iterations = r.iterations;
  out.support_calls = r.support_calls;
  out.termination = r.termination;
  return out;
}

}  // namespace gjklab
