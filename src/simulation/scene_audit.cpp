#include "gjklab/simulation/scene_audit.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "gjklab/experiment/registry/certified.hpp"
#include "gjklab/scene/broadphase.hpp"

namespace gjklab::simulation {

namespace {

std::uint64_t key_of(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

}  // namespace

const Polytope& SceneAudit::hull(const scene::World& w, std::uint32_t i) {
  // The same call as World::world_hull: the same rounding, hence the same points.
  if (!hulls_[i]) hulls_[i].emplace(w.bodies()[i].shape->polytope.transformed(w.bodies()[i].pose));
  return *hulls_[i];
}

void SceneAudit::before_step(const scene::World& w) {
  std::vector<scene::Aabb> boxes;
  w.bounding_boxes(w.settings().contact_margin, boxes);
  scene::all_pairs(boxes, pairs_);  // the reference: every broad phase finds this set
  const auto& bodies = w.bodies();
  std::erase_if(pairs_, [&](const scene::BodyPair& p) {
    return bodies[p.first].is_static() && bodies[p.second].is_static();
  });
  hulls_.assign(bodies.size(), std::nullopt);
  for (const auto& [i, j] : pairs_) {
    hull(w, i);
    hull(w, j);
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
    const experiment::CertifiedAnswer c = experiment::solve_certified(
        *hulls_[i], *hulls_[j],
        SweptRadii{w.bodies()[i].shape->swept_radius, w.bodies()[j].shape->swept_radius}, options);
    rows.frame.push_back(frame);
    rows.a.push_back(i);
    rows.b.push_back(j);
    rows.intersect.push_back(c.answer.intersect ? 1 : 0);
    rows.certified.push_back(c.answer.method == exact::AnswerMethod::certified ? 1 : 0);
    rows.distance.push_back(c.answer.distance);
    rows.depth.push_back(c.answer.depth.value_or(NAN));
    const auto it = deepest.find(key_of(i, j));
    rows.narrow_depth.push_back(it == deepest.end() ? NAN : it->second);
  }
  pairs_.clear();
  hulls_.clear();
}

}  // namespace gjklab::simulation
