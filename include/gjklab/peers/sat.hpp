// The separating axis test (SAT) for two convex polytopes, with the minimum-overlap axis.
//
// Two convex polytopes are disjoint iff their projections onto some axis are disjoint, and it
// suffices to try the face normals of both hulls and the cross products of one edge direction
// of each (the facet normals of A − B are among these). This is the classic test: every
// candidate axis is projected with a scan of both hulls' vertices, so a query costs
// O((F_A + F_B + E_A·E_B)·(V_A + V_B)) with F faces, E edge directions and V vertices, cubic
// in the vertex count, against GJK's roughly linear cost per iteration.
//
// The hull features (exact::hull_features) are computed once per shape, when the SatShape is
// built, outside the query. The query itself is plain double arithmetic.
//
// Lower-dimensional shapes. A − B may have no interior (two coplanar polygons, a segment and
// a point, …); then its "facets" are not all among the axes above, and the query adds, when
// both shapes have dimension ≤ 2: for every candidate plane normal m of A − B (a flat shape's
// plane normal, or eA × eB for two segments) the in-plane axes m × e for every edge direction
// e of both shapes; for a segment paired with a point or segment, its direction, the part
// of the offset between the shapes orthogonal to it and one more axis orthogonal to it; for
// two points, their offset. Extra axes
// never change a correct answer (each is a valid separating-axis candidate, and its overlap is
// at least the depth), so these are added whenever they might be needed.
//
// Answers. intersect: no tested axis separates the projections (touching counts). depth: the
// smallest overlap over the tested axes, which equals the penetration depth (exactly, up to
// rounding) because the facet normals of A − B are tested; 0 when A − B has no interior.
// normal: that axis, oriented so that moving B by depth·normal separates the shapes (the
// convention of PenetrationResult). For separated shapes, `separation` is the gap along the
// separating axis found (a lower bound of the distance) and `normal` that axis from A to B.
#pragma once

#include <memory>
#include <span>

#include "gjklab/exact/hull_features.hpp"
#include "gjklab/geometry/types.hpp"
#include "gjklab/gjk/termination.hpp"

namespace gjklab::peers {

struct SatDefaults {
  static constexpr bool early_exit = true;
};

struct SatOptions {
  /// Stop at the first separating axis (the classic test). When false every axis is tested
  /// and `separation` is the largest gap over all axes (the best SAT lower bound of the
  /// distance).
  bool early_exit = SatDefaults::early_exit;
};

/// A shape prepared for SAT: the exact hull features of its cloud.
class SatShape {
 public:
  /// Computes the hull features (exact, with CGAL). Throws std::invalid_argument for an empty
  /// cloud or a non-finite coordinate.
  explicit SatShape(std::span<const Vec3> cloud);
  explicit SatShape(exact::HullFeatures features);
  const exact::HullFeatures& features() const { return features_; }

 private:
  exact::HullFeatures features_;
};

struct SatResult {
  bool intersect = false;
  double depth = 0;             ///< minimum overlap when intersecting; 0 when separated
  double separation = 0;        ///< gap along the separating axis when separated; 0 otherwise
  Vec3 normal = Vec3::UnitX();  ///< unit axis, oriented from A towards B (see above)
  int axes_tested = 0;          ///< candidate axes projected (parallel edge pairs skipped)
  /// Each tested axis costs the support values of both shapes in both directions, i.e. two
  /// Minkowski support evaluations: support_calls = 2·axes_tested.
  int support_calls = 0;
  /// converged, or numerical_failure when an axis or a projection was not finite.
  Termination termination = Termination::converged;
};

SatResult sat_query(const SatShape& a, const SatShape& b, const SatOptions& options = {});

}  // namespace gjklab::peers
