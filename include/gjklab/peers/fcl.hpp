// FCL (the Flexible Collision Library, 0.7) as a peer: collide and distance on fcl::Convex with
// FCL's two GJK solvers. Built only when CMake finds FCL (compile definition GJKLAB_HAVE_FCL).
//
// fcl::Convex needs the hull's faces (for its support search by hill climbing over vertex
// neighbours), so an FclShape is built from the exact hull features of the cloud
// (exact::hull_features): the extreme points and the merged faces as polygons. A flat cloud
// becomes its polygon twice (both sides); a segment or a point has no faces, and FCL then
// scans the vertices. Building a shape is outside the query.
//
// The query. `fcl-libccd` uses detail::GJKSolver_libccd, `fcl-indep` detail::GJKSolver_indep:
// first shapeIntersect with a contact request (libccd solver: libccd's MPR penetration;
// indep solver: FCL's GJK, then its EPA); when that reports no collision, shapeDistance
// (libccd solver: FCL's GJK distance built on libccd; indep solver: FCL's GJK).
// Bounds: fcl-libccd passes max_iterations as max_collision_iterations and
// max_distance_iterations. Its collide path runs libccd's MPR, whose discovery and refinement
// loops do not read that bound (see peers/libccd.hpp), and FCL gives no way to bound them from
// outside. fcl-indep passes max_iterations as gjk_max_iterations and the EPA bounds below.
//
// Answers (PenetrationResult): intersect is shapeIntersect's answer; when intersecting, depth
// and normal come from its contact (normal oriented as in PenetrationResult) and witness_a =
// witness_b = FCL's contact position. When not intersecting, distance and the witnesses come
// from shapeDistance; if shapeDistance reports contact or failure instead (the two queries
// use different algorithms and tolerances), distance is 0. FCL reports neither iterations
// nor support calls (both 0) nor why it stopped: termination is `converged`, except for
// fcl-indep when both queries fail to answer (its GJK stops at gjk_max_iterations or its EPA
// fails, FCL does not say which), reported as `step_limit`; any non-finite number in the answer
// makes it `numerical_failure`. A pair with a coordinate beyond 1e30 in magnitude is not given
// to FCL (`invalid_input`): its triple products overflow near 1e102 and an assertion inside
// FCL aborted the program there, and its libccd MPR never returned on coordinates of 1e68.
#pragma once

#include <memory>
#include <string>

#include "gjklab/exact/hull_features.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/peers/fcl_options.hpp"

namespace gjklab::peers {

enum class FclSolver { libccd, indep };

/// A cloud as an fcl::Convex (built from its exact hull features).
class FclShape {
 public:
  /// Throws std::invalid_argument for an invalid cloud.
  explicit FclShape(const Polytope& cloud);
  explicit FclShape(const exact::HullFeatures& hull);
  ~FclShape();
  FclShape(FclShape&&) noexcept;
  FclShape& operator=(FclShape&&) noexcept;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// One collide (+ distance) query. Throws std::invalid_argument if the options are invalid.
PenetrationResult fcl_query(const FclShape& a, const FclShape& b, FclSolver solver,
                            const FclOptions& options = {});

/// FCL's version (for provenance).
std::string fcl_version();
/// FCL's tolerances as the solvers set them, e.g. "libccd: collision_tolerance=…; …".
std::string fcl_settings();

}  // namespace gjklab::peers
