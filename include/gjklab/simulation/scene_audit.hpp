// The exact audit of a simulation's narrow phase (`[oracle] audit_every = k` in scene files):
// on every k-th frame, the pairs the step queries are answered by the certified exact oracle
// (experiment/registry/certified.hpp) on the same world-frame hulls, beside what the narrow
// phase made of them. Here, in the simulation layer, because the scene layer knows neither the
// oracle nor files.
#pragma once

#include <cstdint>
#include <optional>
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
  const Polytope& hull(const scene::World& w, std::uint32_t i);

  bool depth_;
  std::vector<scene::BodyPair> pairs_;
  std::vector<std::optional<Polytope>> hulls_;
};

}  // namespace gjklab::simulation
