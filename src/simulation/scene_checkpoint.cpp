#include "scene_checkpoint.hpp"

#include <algorithm>
#include <exception>
#include <string>

#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/run/provenance.hpp"

namespace gjklab::simulation {

namespace {

void append(const Vec3& v, std::vector<double>& out) {
  out.insert(out.end(), v.data(), v.data() + 3);
}

Vec3 vec3_at(const std::vector<double>& v, std::size_t row) {
  return Vec3(v.at(3 * row), v.at(3 * row + 1), v.at(3 * row + 2));
}

experiment::SceneHeader header_of(const SceneRun& run, bool finite, bool complete) {
  const SceneSetup& s = run.setup;
  const scene::WorldSettings& st = s.world->settings();
  experiment::SceneHeader h;
  h.scene_name = s.name;
  h.scene_file = run.scene_path;
  h.scene_toml = s.text;
  h.seed = s.seed;
  h.frames = static_cast<std::uint64_t>(run.progress.done);
  h.pose_every = static_cast<std::uint64_t>(s.pose_every);
  h.contacts_every = static_cast<std::uint64_t>(s.contacts_every);
  h.audit_every = static_cast<std::uint64_t>(s.audit_every);
  h.audit_depth = s.audit_depth;
  h.queries_every = static_cast<std::uint64_t>(s.queries_every);
  h.body_size = s.body_size;
  h.dt = st.dt;
  h.contact_margin = st.contact_margin;
  h.broad_phase = std::string(scene::to_string(st.broad_phase));
  h.narrow_algorithm = st.query ? st.query->name : std::string(scene::kDefaultNarrowPhase);
  h.depth_algorithm = st.depth ? st.depth->name : std::string("epa");
  h.warm_start = st.warm_start;
  h.finite = finite;
  h.complete = complete;
  return h;
}

experiment::SceneBodyRows bodies_of(const SceneSetup& s) {
  experiment::SceneBodyRows r;
  r.shape = s.shape_names;
  for (const scene::RigidBody& b : s.world->bodies()) {
    r.mass.push_back(b.mass);
    r.size.push_back(b.shape->size);
    r.is_static.push_back(b.is_static() ? 1 : 0);
  }
  return r;
}

/// Each distinct shape once, in the order bodies first use it.
experiment::SceneShapeRows shapes_of(const scene::World& w) {
  experiment::SceneShapeRows r;
  r.offset.push_back(0);
  std::vector<const scene::ConvexShape*> seen;
  for (const scene::RigidBody& b : w.bodies()) {
    auto it = std::find(seen.begin(), seen.end(), b.shape.get());
    if (it == seen.end()) {
      seen.push_back(b.shape.get());
      r.radius.push_back(b.shape->swept_radius);
      for (const Vec3& v : b.shape->polytope.vertices())
        append(v, r.vertices);
      r.offset.push_back(static_cast<std::int64_t>(r.vertices.size() / 3));
      it = seen.end() - 1;
    }
    r.body_shape.push_back(static_cast<std::uint32_t>(it - seen.begin()));
  }
  return r;
}

experiment::SceneState state_of(const scene::World& w, std::int64_t target) {
  experiment::SceneState s;
  for (const scene::RigidBody& b : w.bodies()) {
    append(b.pose.translation, s.bodies.position);
    const auto& q = b.orientation.coeffs();  // x y z w
    s.bodies.orientation_xyzw.insert(s.bodies.orientation_xyzw.end(), q.data(), q.data() + 4);
    append(b.velocity, s.bodies.velocity);
    append(b.angular_velocity, s.bodies.angular_velocity);
    s.bodies.touching.push_back(b.touching ? 1 : 0);
  }
  const scene::CarriedState c = w.carried_state();
  s.time = c.time;
  s.steps = c.steps;
  s.frames_target = static_cast<std::uint64_t>(target);
  for (const scene::PairState& ps : c.pairs) {
    s.pairs.pair_a.push_back(ps.a);
    s.pairs.pair_b.push_back(ps.b);
    s.pairs.simplex_size.push_back(static_cast<std::uint32_t>(ps.simplex.size()));
    s.pairs.point_count.push_back(static_cast<std::uint32_t>(ps.local_a.size()));
    for (const SimplexVertex& v : ps.simplex) {
      append(v.w, s.simplex.simplex_w);
      append(v.a, s.simplex.simplex_a);
      append(v.b, s.simplex.simplex_b);
      s.simplex.simplex_index_a.push_back(v.index_a);
      s.simplex.simplex_index_b.push_back(v.index_b);
    }
    for (std::size_t k = 0; k < ps.local_a.size(); ++k) {
      append(ps.local_a[k], s.points.point_local_a);
      s.points.point_impulse.insert(s.points.point_impulse.end(), ps.impulses[k].begin(),
                                    ps.impulses[k].end());
    }
  }
  return s;
}

void restore_bodies(const experiment::SceneBodyStateRows& r, scene::World& w) {
  auto& bodies = w.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    scene::RigidBody& b = bodies[i];
    b.pose.translation = vec3_at(r.position, i);
    // Quat(w, x, y, z): the integrator's own quaternion, so the rotation is recomputed as it was.
    const double* q = r.orientation_xyzw.data() + 4 * i;
    b.orientation = Quat(q[3], q[0], q[1], q[2]);
    b.pose.rotation = b.orientation.toRotationMatrix();
    b.velocity = vec3_at(r.velocity, i);
    b.angular_velocity = vec3_at(r.angular_velocity, i);
    b.touching = r.touching[i] != 0;
  }
}

scene::CarriedState carried_of(const experiment::SceneState& s) {
  scene::CarriedState c;
  c.time = s.time;
  c.steps = s.steps;
  std::size_t v = 0, q = 0;
  for (std::size_t k = 0; k < s.pairs.pair_a.size(); ++k) {
    scene::PairState ps;
    ps.a = s.pairs.pair_a[k];
    ps.b = s.pairs.pair_b[k];
    for (std::uint32_t j = 0; j < s.pairs.simplex_size[k]; ++j, ++v)
      ps.simplex.push_back({vec3_at(s.simplex.simplex_w, v), vec3_at(s.simplex.simplex_a, v),
                            vec3_at(s.simplex.simplex_b, v), s.simplex.simplex_index_a.at(v),
                            s.simplex.simplex_index_b.at(v)});
    for (std::uint32_t j = 0; j < s.pairs.point_count[k]; ++j, ++q) {
      ps.local_a.push_back(vec3_at(s.points.point_local_a, q));
      const std::vector<double>& i = s.points.point_impulse;
      ps.impulses.push_back({i.at(3 * q), i.at(3 * q + 1), i.at(3 * q + 2)});
    }
    c.pairs.push_back(std::move(ps));
  }
  return c;
}

}  // namespace

void fill_archive(SceneRun& run, bool finite, bool complete) {
  experiment::SceneArchive& a = run.archive;
  a.header = header_of(run, finite, complete);
  a.provenance = experiment::build_provenance();
  a.bodies = bodies_of(run.setup);
  a.shapes =
      run.setup.queries_every > 0 ? shapes_of(*run.setup.world) : experiment::SceneShapeRows{};
  if (complete)
    a.state.reset();
  else
    a.state = state_of(*run.setup.world, run.progress.target);
}

std::int64_t restore_state(const experiment::SceneState& state, scene::World& w,
                           const std::string& file) {
  const std::size_t n = w.bodies().size();
  if (state.bodies.touching.size() != n)
    throw experiment::ArchiveError("archive " + file + ": state/ does not match the scene's " +
                                   std::to_string(n) + " bodies");
  restore_bodies(state.bodies, w);
  try {
    w.restore(carried_of(state));
  } catch (const std::exception& e) {
    throw experiment::ArchiveError("archive " + file + ": state/ is inconsistent: " + e.what());
  }
  return static_cast<std::int64_t>(state.frames_target);
}

}  // namespace gjklab::simulation
