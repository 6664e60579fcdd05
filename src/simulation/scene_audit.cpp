#include "gjklab/simulation/scene_audit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "gjklab/experiment/registry/certified.hpp"
#include "gjklab/scene/broadphase.hpp"
#include "gjklab/scene/compound.hpp"

namespace gjklab::simulation {

namespace {

std::uint64_t key_of(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

/// Body i's swept radius of part k (a compound's pieces have none).
double radius_of(const scene::RigidBody& b, std::size_t k) {
  return b.compound ? b.compound->pieces[k].swept_radius : b.shape->swept_radius;
}

/// One audit row's exact answer (see the header for a pair with a compound body).
struct PairAnswer {
  bool intersect = false;
  bool certified = true;
  double distance = std::numeric_limits<double>::infinity();  ///< length units
  double depth = NAN;                                         ///< length units
};

PairAnswer answer_of(const std::vector<Polytope>& a, const scene::RigidBody& ba,
                     const std::vector<Polytope>& b, const scene::RigidBody& bb,
                     const exact::OracleOptions& options) {
  PairAnswer out;
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t l = 0; l < b.size(); ++l) {
      const exact::OracleAnswer c =
          experiment::solve_certified(a[k], b[l], SweptRadii{radius_of(ba, k), radius_of(bb, l)},
                                      options)
              .answer;
      out.intersect = out.intersect || c.intersect;
      out.certified = out.certified && c.method == exact::AnswerMethod::certified;
      // Rounding to the nearest double is monotone: the least rounded distance is the rounded
      // least distance.
      out.distance = std::min(out.distance, c.distance);
      if (c.depth) out.depth = std::isnan(out.depth) ? *c.depth : std::max(out.depth, *c.depth);
    }
  return out;
}

}  // namespace

const std::vector<Polytope>& SceneAudit::parts(const scene::World& w, std::uint32_t i) {
  // The same calls as World::world_hull and World::world_pieces: the same rounding, hence the
  // same points.
  std::vector<Polytope>& out = parts_[i];
  const scene::RigidBody& b = w.bodies()[i];
  if (!out.empty()) return out;
  if (b.compound)
    for (const scene::ConvexShape& piece : b.compound->pieces)
      out.push_back(piece.polytope.transformed(b.pose));
  else
    out.push_back(b.shape->polytope.transformed(b.pose));
  return out;
}

void SceneAudit::before_step(const scene::World& w) {
  std::vector<scene::Aabb> boxes;
  w.bounding_boxes(w.settings().contact_margin, boxes);
  scene::all_pairs(boxes, pairs_);  // the reference: every broad phase finds this set
  const auto& bodies = w.bodies();
  std::erase_if(pairs_, [&](const scene::BodyPair& p) {
    return bodies[p.first].is_static() && bodies[p.second].is_static();
  });
  parts_.assign(bodies.size(), {});
  for (const auto& [i, j] : pairs_) {
    parts(w, i);
    parts(w, j);
  }
}

void SceneAudit::after_step(const scene::World& w, std::int64_t frame,
                            experiment::SceneAuditRows& rows) {
  // The narrow phase's answer per pair: its deepest contact point.
  std::unordered_map<std::uint64_t, double> deepest;
  for (const scene::Contact& c : w.contacts()) {
    const auto [it, fresh] = deepest.try_emplace(key_of(c.a, c.b), c.depth);
    if (!fresh) it->second = std::max(it->second, c.depth);
  }
  exact::OracleOptions options;
  options.depth = depth_;
  options.hull_vertices = false;  // not asked for: an exact hull of each cloud per pair
  for (const auto& [i, j] : pairs_) {
    const PairAnswer c = answer_of(parts_[i], w.bodies()[i], parts_[j], w.bodies()[j], options);
    rows.frame.push_back(frame);
    rows.a.push_back(i);
    rows.b.push_back(j);
    rows.intersect.push_back(c.intersect ? 1 : 0);
    rows.certified.push_back(c.certified ? 1 : 0);
    rows.distance.push_back(c.distance);
    rows.depth.push_back(c.depth);
    const auto it = deepest.find(key_of(i, j));
    rows.narrow_depth.push_back(it == deepest.end() ? NAN : it->second);
  }
  pairs_.clear();
  parts_.clear();
}

}  // namespace gjklab::simulation
