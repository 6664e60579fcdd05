// The exact audit of a simulation's narrow phase (`[oracle] audit_every = k` in scene files):
// on every k-th frame, the pairs the step queries are answered by the certified exact oracle
// (experiment/certified.hpp) on the same world-frame hulls, beside what the narrow phase made
// of them. Here, in the command, because the scene layer knows neither the oracle nor files.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/scene/world.hpp"

namespace gjklab::cli {

/// Columns of the archive's audit/ table, one row per audited pair.
struct AuditRows {
  std::vector<std::int64_t> frame;  ///< the step's frame number (1 = the first step)
  std::vector<std::uint32_t> a, b;  ///< bodies, a < b
  std::vector<std::uint8_t> intersect;
  std::vector<std::uint8_t> certified;  ///< 1: a certificate proved the distance; 0: the QP
  /// The exact distance between the hulls, rounded to the nearest double (0 when intersecting).
  std::vector<double> distance;
  /// The exact penetration depth, rounded (with `depth = true` and intersect; else NaN).
  std::vector<double> depth;
  /// The narrow phase's deepest contact of the pair in that step: > 0 penetrating, < 0 apart
  /// (length units); NaN when it made no contact (it found the pair beyond the contact margin).
  std::vector<double> narrow_depth;
  std::size_t size() const { return frame.size(); }
};

class SceneAudit {
 public:
  explicit SceneAudit(bool depth) : depth_(depth) {}
  /// Before a step: the pairs it will query (every overlapping pair of the world's boxes but
  /// static–static, as World::step finds them) and their world-frame hulls, computed as the
  /// step computes them, so that the oracle sees the very doubles GJK sees.
  void before_step(const scene::World& w);
  /// After that step: the exact answers and the step's contacts of the same pairs.
  void after_step(const scene::World& w, std::int64_t frame, AuditRows& rows);

 private:
  const Polytope& hull(const scene::World& w, std::uint32_t i);

  bool depth_;
  std::vector<scene::BodyPair> pairs_;
  std::vector<std::optional<Polytope>> hulls_;
};

}  // namespace gjklab::cli
