// The exact audit of a simulation's narrow phase (`[oracle] audit_every = k` in scene files):
// on every k-th frame, the pairs the step queries are answered by the certified exact oracle
// (experiment/registry/certified.hpp) on the same world-frame hulls, beside what the narrow
// phase made of them. Here, in the simulation layer, because the scene layer knows neither the
// oracle nor files.
//
// A pair with a compound body (scene/compound.hpp) is answered piece pair by piece pair, every
// piece pair (the boxes the narrow phase culls with do not limit the audit), and its row holds
// the body pair's answer as the narrow phase sees the bodies, the union of their pieces: it
// intersects when a piece pair does, its distance is the least piece-pair distance (the exact
// distance between the unions), its depth the largest piece-pair depth (the depth the narrow
// phase resolves piece by piece, not the solids' own penetration depth), and it is certified
// when every piece pair was.
#pragma once

#include <cstdint>
#include <vector>

#include "gjklab/experiment/archive/scene_archive.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/scene/world.hpp"

namespace gjklab::simulation {

class SceneAudit {
 public:
  explicit SceneAudit(bool depth) : depth_(depth) {}
  /// Before a step: the pairs it will query (every overlapping pair of the world's boxes but
  /// static–static, as World::step finds them) and their world-frame hulls, computed as the
  /// step computes them, so that the oracle sees the very doubles GJK sees.
  void before_step(const scene::World& w);
  /// After that step: the exact answers and the step's contacts of the same pairs.
  void after_step(const scene::World& w, std::int64_t frame, experiment::SceneAuditRows& rows);

 private:
  /// Body i's world hull, or its pieces' (computed once per audited step).
  const std::vector<Polytope>& parts(const scene::World& w, std::uint32_t i);

  bool depth_;
  std::vector<scene::BodyPair> pairs_;
  std::vector<std::vector<Polytope>> parts_;  ///< per body; empty: not needed this step
};

}  // namespace gjklab::simulation
