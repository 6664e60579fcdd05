// Bullet Physics (double-precision build) as a peer. Built only when CMake finds Bullet's
// double-precision libraries (compile definition GJKLAB_HAVE_BULLET).
//
// A BulletShape is a btConvexHullShape over the cloud's points with collision margin 0 (its
// support function scans the points). Building it is outside the query.
//
// `bullet-gjk`: btGjkPairDetector with btVoronoiSimplexSolver and, for penetrating pairs,
// btGjkEpaPenetrationDepthSolver (the pairing Bullet's default collision configuration uses).
//   iterations = btGjkPairDetector::m_curIter. Its GJK loop stops at a fixed bound of 1000
//   iterations that cannot be changed; reaching it is reported as step_limit. When Bullet
//   reports no result at all (neither closest points nor a penetration), termination is
//   degenerate_simplex and intersect is false.
// `bullet-epa2`: btGjkEpaSolver2::Distance, and Penetration (margins off) when GJK finds the
//   origin inside. Its bounds are compile-time constants of Bullet (GJK 128 iterations, EPA 255
//   iterations with at most 128 vertices). Status mapping: Separated, Penetrating → converged;
//   GJK_Failed (its GJK reached the iteration bound) → step_limit; EPA_Failed → degenerate_simplex.
//   It reports no iteration count (0).
// support_calls is 0 for both (Bullet does not report it).
//
// Answers (PenetrationResult): intersecting pairs get depth, normal (oriented as in
// PenetrationResult) and witness points on A and B; separated pairs get the distance and the
// closest points.
#pragma once

#include <memory>
#include <string>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/result.hpp"

namespace gjklab::peers {

class BulletShape {
 public:
  explicit BulletShape(const Polytope& cloud);
  ~BulletShape();
  BulletShape(BulletShape&&) noexcept;
  BulletShape& operator=(BulletShape&&) noexcept;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

PenetrationResult bullet_gjk_query(const BulletShape& a, const BulletShape& b);
PenetrationResult bullet_epa2_query(const BulletShape& a, const BulletShape& b);

/// Bullet's version, e.g. "3.24 (double precision)" (for provenance).
std::string bullet_version();

}  // namespace gjklab::peers
