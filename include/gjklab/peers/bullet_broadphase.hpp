// Bullet's dynamic AABB tree broad phase (btDbvtBroadphase, double-precision build) as a peer of
// the scene layer's broad phases. Built only when CMake finds Bullet (GJKLAB_HAVE_BULLET); the
// class is declared either way so that callers need no guard of their own beyond
// `bullet_broadphase_available()`.
//
// It lives here, with the other third-party engines, and not in scene/: the scene layer links no
// engine. It is therefore not a broad phase a world can step with; `gjklab simulate` times it
// beside the scene's own broad phases (compare_broad_phases) and the tests check its pair set.
//
// Use as in a Bullet world: one proxy per box, kept between calls; a box that changed since the
// last call is moved with setAabb (a box that did not change is left alone, as Bullet leaves
// inactive and static objects, so that it can migrate to the tree of fixed proxies), then
// calculateOverlappingPairs. Bullet's pair cache holds the pairs whose *enlarged* tree volumes
// overlap (and drops stale ones only a fraction per call), so the answer is that cache filtered
// by the exact closed-box test and put in the scene's order: the same set and order as
// scene::all_pairs. Boxes that are not finite or are inverted are kept out of the tree (Bullet
// assumes finite, ordered bounds) and tested against every box.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::peers {

/// An axis-aligned box, world frame, length units (the layout of scene::Aabb).
struct BroadphaseBox {
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();
};

/// True when Bullet was built in (otherwise BulletDbvtBroadphase's constructor throws).
bool bullet_broadphase_available();

class BulletDbvtBroadphase {
 public:
  BulletDbvtBroadphase();
  ~BulletDbvtBroadphase();
  BulletDbvtBroadphase(const BulletDbvtBroadphase&) = delete;
  BulletDbvtBroadphase& operator=(const BulletDbvtBroadphase&) = delete;

  /// The pairs (i, j), i < j, of closed boxes that overlap, sorted. A call with a different
  /// number of boxes than the last one starts a new tree.
  void find_pairs(std::span<const BroadphaseBox> boxes,
                  std::vector<std::pair<std::uint32_t, std::uint32_t>>& out);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace gjklab::peers
