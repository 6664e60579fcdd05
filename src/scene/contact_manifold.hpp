// Contact manifolds of two convex shapes by face clipping, and what the narrow phase found for
// one body pair before the step merges it (World::PairOutcome). Internal to src/scene/.
#pragma once

#include <cstddef>
#include <vector>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/scene/body.hpp"
#include "gjklab/scene/world.hpp"

namespace gjklab::scene::detail {

struct ManifoldPoint {
  Vec3 point;    ///< world frame, midway between the two surfaces
  double depth;  ///< length units, > 0 penetrating
};

/// A manifold by clipping the incident face against the reference face; the normal it
/// returns through `normal` is the reference face's (oriented from a to b). Empty when neither
/// face is aligned with the normal or nothing survives the clipping. sa and sb are the shapes
/// whose faces index wa's and wb's vertices (world frame); ra and rb their rotations. The faces
/// are the cores'; swept radii move the surfaces out along the normal (points midway between
/// them, depths grown by both radii). `margin` (length units): points farther apart are dropped.
std::vector<ManifoldPoint> clip_manifold(const ConvexShape& sa, const Polytope& wa, const Mat3& ra,
                                         const ConvexShape& sb, const Polytope& wb, const Mat3& rb,
                                         Vec3& normal, double margin);

}  // namespace gjklab::scene::detail

namespace gjklab::scene {

/// What the queries of one body pair found (World::collide), merged into the step in pair order.
struct World::PairOutcome {
  std::uint32_t a = 0, b = 0;
  int iterations = 0;       ///< summed over the pair's queries
  int iterations_cold = 0;  ///< measure_cold only
  std::size_t queries = 1;  ///< narrow-phase queries run (a compound pair's piece pairs)
  std::size_t failed = 0;   ///< GJK and EPA stops other than converged
  std::size_t epa = 0;      ///< depth queries run
  bool compound = false;    ///< a pair with a compound body (its queries are not logged)
  QueryRecord query;        ///< filled when the step records queries
  std::vector<detail::ManifoldPoint> points;  ///< empty: no contact
  Vec3 normal = Vec3::UnitZ();                ///< every point's, unless `normals` is set
  /// Per point (compound pairs: each piece pair has its own normal); empty: `normal` for all.
  std::vector<Vec3> normals;
};

}  // namespace gjklab::scene
