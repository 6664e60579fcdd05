#include "gjklab/simulation/recording.hpp"

#include <chrono>

#include "gjklab/peers/bullet_broadphase.hpp"
#include "gjklab/scene/broadphase.hpp"

namespace gjklab::simulation {

namespace {

void append_pose(const Pose& p, std::vector<double>& out) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out.push_back(p.rotation(r, c));
  out.insert(out.end(), p.translation.data(), p.translation.data() + 3);
}

void append(const Vec3& v, std::vector<double>& out) {
  out.insert(out.end(), v.data(), v.data() + 3);
}

template <class F>
std::int64_t time_ns(F&& search) {
  const auto t0 = std::chrono::steady_clock::now();
  search();
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() -
                                                              t0)
      .count();
}

}  // namespace

void record_frame(const scene::World& w, const scene::StepStats& st, double body_size,
                  experiment::SceneFrameRows& f) {
  f.time.push_back(w.time());
  f.kinetic_energy.push_back(w.kinetic_energy());
  f.potential_energy.push_back(w.potential_energy());
  f.max_penetration.push_back(w.max_penetration() / body_size);
  f.iterations_mean.push_back(st.iterations_mean);
  f.iterations_cold_mean.push_back(st.iterations_cold_mean);
  f.contacts.push_back(static_cast<std::int64_t>(st.contacts));
  f.candidate_pairs.push_back(static_cast<std::int64_t>(st.candidate_pairs));
  f.narrow_queries.push_back(static_cast<std::int64_t>(st.narrow_queries));
  f.epa_queries.push_back(static_cast<std::int64_t>(st.epa_queries));
  f.failed_queries.push_back(static_cast<std::int64_t>(st.failed_queries));
  f.broadphase_ns.push_back(st.broadphase_ns);
  f.narrowphase_ns.push_back(st.narrowphase_ns);
  f.solver_ns.push_back(st.solver_ns);
}

void record_poses(const scene::World& w, std::int64_t frame, experiment::ScenePoseRows& r) {
  for (std::uint32_t i = 0; i < w.bodies().size(); ++i) {
    const scene::RigidBody& b = w.bodies()[i];
    if (b.is_static()) continue;
    r.frame.push_back(frame);
    r.body.push_back(i);
    append(b.pose.translation, r.position);
    r.orientation.insert(r.orientation.end(), {b.orientation.w(), b.orientation.x(),
                                               b.orientation.y(), b.orientation.z()});
    append(b.velocity, r.velocity);
    r.touching.push_back(b.touching ? 1 : 0);
  }
}

void record_contacts(const scene::World& w, std::int64_t frame,
                     experiment::SceneContactRows& r) {
  for (const scene::Contact& c : w.contacts()) {
    r.frame.push_back(frame);
    r.a.push_back(c.a);
    r.b.push_back(c.b);
    append(c.point, r.point);
    append(c.normal, r.normal);
    r.depth.push_back(c.depth);
    r.normal_impulse.push_back(c.normal_impulse);
  }
}

void record_queries(const std::vector<Pose>& before, const std::vector<scene::QueryRecord>& log,
                    std::int64_t frame, experiment::SceneQueryRows& q) {
  for (const scene::QueryRecord& r : log) {
    q.frame.push_back(frame);
    q.a.push_back(r.a);
    q.b.push_back(r.b);
    append_pose(before[r.a], q.pose_a);
    append_pose(before[r.b], q.pose_b);
    q.warm_size.push_back(static_cast<std::uint8_t>(r.warm_size));
    q.warm_index_a.insert(q.warm_index_a.end(), r.warm_index_a.begin(), r.warm_index_a.end());
    q.warm_index_b.insert(q.warm_index_b.end(), r.warm_index_b.begin(), r.warm_index_b.end());
    q.iterations.push_back(r.iterations);
    q.intersect.push_back(r.intersect ? 1 : 0);
    q.distance.push_back(r.distance);
  }
}

struct BroadPhaseComparison::Impl {
  scene::BroadPhase all{scene::BroadPhaseKind::all_pairs};
  scene::BroadPhase grid{scene::BroadPhaseKind::grid};
  scene::BroadPhase sap{scene::BroadPhaseKind::sweep_and_prune};
  std::unique_ptr<peers::BulletDbvtBroadphase> dbvt =
      peers::bullet_broadphase_available() ? std::make_unique<peers::BulletDbvtBroadphase>()
                                           : nullptr;
  std::vector<scene::Aabb> boxes;
  std::vector<peers::BroadphaseBox> peer_boxes;
  std::vector<scene::BodyPair> a, g, s, d;
};

BroadPhaseComparison::BroadPhaseComparison() : impl_(std::make_unique<Impl>()) {}
BroadPhaseComparison::~BroadPhaseComparison() = default;

void BroadPhaseComparison::run(const scene::World& w, experiment::SceneFrameRows& rows) {
  Impl& m = *impl_;
  w.bounding_boxes(w.settings().contact_margin, m.boxes);
  rows.all_pairs_ns.push_back(time_ns([&] { m.all.find_pairs(m.boxes, m.a); }));
  rows.grid_ns.push_back(time_ns([&] { m.grid.find_pairs(m.boxes, m.g); }));
  rows.sap_ns.push_back(time_ns([&] { m.sap.find_pairs(m.boxes, m.s); }));
  bool agree = m.a == m.g && m.a == m.s;
  if (m.dbvt) {
    // The copy into the peer's box type is not the broad phase's work: outside the timing.
    m.peer_boxes.resize(m.boxes.size());
    for (std::size_t i = 0; i < m.boxes.size(); ++i)
      m.peer_boxes[i] = {m.boxes[i].lower, m.boxes[i].upper};
    rows.dbvt_ns.push_back(time_ns([&] { m.dbvt->find_pairs(m.peer_boxes, m.d); }));
    agree = agree && m.a == m.d;
  }
  rows.broad_phases_agree.push_back(agree ? 1 : 0);
}

}  // namespace gjklab::simulation
