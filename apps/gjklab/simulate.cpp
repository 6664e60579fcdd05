#include "gjklab/simulate.hpp"

#include <hdf5.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/run/provenance.hpp"
#include "gjklab/peers/bullet_broadphase.hpp"
#include "gjklab/scene_audit.hpp"
#include "gjklab/scene_file.hpp"
#include "gjklab/stop_signals.hpp"

namespace gjklab::cli {

namespace fs = std::filesystem;

namespace {

/// Schema of the scene archive (documented in docs/scenes.md); bumped on any change.
constexpr int kSceneSchemaVersion = 3;  // 2: frames/dbvt_ns, audit/; 3: queries/, shapes/

struct SimulationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Columns of the frames/ table, one value per frame.
struct FrameRows {
  std::vector<double> time, kinetic_energy, potential_energy, max_penetration, iterations_mean,
      iterations_cold_mean;
  std::vector<std::int64_t> contacts, candidate_pairs, narrow_queries, epa_queries, failed_queries,
      broadphase_ns, narrowphase_ns, solver_ns;
  // With compare_broad_phases: the pair search alone, timed on the same boxes (dbvt_ns only
  // when Bullet is built in).
  std::vector<std::int64_t> all_pairs_ns, grid_ns, sap_ns, dbvt_ns;
  std::vector<std::uint8_t> broad_phases_agree;
};

struct PoseRows {
  std::vector<std::int64_t> frame;
  std::vector<std::uint32_t> body;
  std::vector<double> position, orientation, velocity;  // 3, 4 (w x y z), 3 per row
  std::vector<std::uint8_t> touching;
};

struct ContactRows {
  std::vector<std::int64_t> frame;
  std::vector<std::uint32_t> a, b;
  std::vector<double> point, normal, depth, normal_impulse;  // 3, 3, 1, 1 per row
};

/// Columns of the queries/ table: one row per narrow-phase query of the recorded frames.
struct QueryRows {
  std::vector<std::int64_t> frame;
  std::vector<std::uint32_t> a, b;
  /// Per row, each body's pose at the step's start: the rotation's 9 entries (row-major), then
  /// the translation; the query ran on every shape vertex v moved to rotation·v + translation.
  std::vector<double> pose_a, pose_b;  // 12 per row
  std::vector<std::uint8_t> warm_size;
  std::vector<std::int32_t> warm_index_a, warm_index_b;  // 4 per row, −1 past warm_size
  std::vector<std::int32_t> iterations;
  std::vector<std::uint8_t> intersect;
  std::vector<double> distance;
};

// ---- HDF5: a small writer of whole datasets (the run is held in memory until the end) ----

class H5 {
 public:
  explicit H5(std::string path) : path_(std::move(path)) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw SimulationError("archive " + path_ + ": " + what);
  }
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) fail(what);
    return id;
  }

 private:
  std::string path_;
};

/// Closes an HDF5 identifier on scope exit.
struct Closer {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Closer() {
    if (id >= 0) close(id);
  }
};

template <class T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  if constexpr (std::is_same_v<T, std::int64_t>) return H5T_NATIVE_INT64;
  if constexpr (std::is_same_v<T, std::uint32_t>) return H5T_NATIVE_UINT32;
  if constexpr (std::is_same_v<T, std::int32_t>) return H5T_NATIVE_INT32;
  if constexpr (std::is_same_v<T, std::uint8_t>) return H5T_NATIVE_UINT8;
}

/// A 1-D (width 1) or rows × width dataset, chunked and deflated.
template <class T>
void write_column(const H5& h, hid_t group, const std::string& name, const std::vector<T>& v,
                  hsize_t width = 1) {
  const hsize_t rows = v.size() / width;
  const hsize_t dims[2] = {rows, width};
  const int rank = width == 1 ? 1 : 2;
  Closer space{h.check(H5Screate_simple(rank, dims, nullptr), "dataspace " + name), H5Sclose};
  Closer plist{h.check(H5Pcreate(H5P_DATASET_CREATE), "plist " + name), H5Pclose};
  if (rows > 0) {
    const hsize_t chunk[2] = {std::min<hsize_t>(rows, 16384), width};
    H5Pset_chunk(plist.id, rank, chunk);
    H5Pset_shuffle(plist.id);
    H5Pset_deflate(plist.id, 4);
  }
  Closer ds{h.check(H5Dcreate2(group, name.c_str(), native_type<T>(), space.id, H5P_DEFAULT,
                               plist.id, H5P_DEFAULT),
                    "cannot create " + name),
            H5Dclose};
  if (rows > 0 && H5Dwrite(ds.id, native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    h.fail("cannot write " + name);
}

void write_strings(const H5& h, hid_t group, const std::string& name,
                   const std::vector<std::string>& v) {
  std::vector<const char*> ptrs;
  for (const auto& s : v)
    ptrs.push_back(s.c_str());
  const hsize_t dims[1] = {v.size()};
  Closer type{h.check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose};
  H5Tset_size(type.id, H5T_VARIABLE);
  H5Tset_cset(type.id, H5T_CSET_UTF8);
  Closer space{h.check(H5Screate_simple(1, dims, nullptr), "dataspace " + name), H5Sclose};
  Closer ds{h.check(H5Dcreate2(group, name.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT,
                               H5P_DEFAULT),
                    "cannot create " + name),
            H5Dclose};
  if (!v.empty() && H5Dwrite(ds.id, type.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()) < 0)
    h.fail("cannot write " + name);
}

void string_attribute(const H5& h, hid_t obj, const std::string& name, const std::string& value) {
  Closer type{h.check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose};
  H5Tset_size(type.id, H5T_VARIABLE);
  H5Tset_cset(type.id, H5T_CSET_UTF8);
  Closer space{h.check(H5Screate(H5S_SCALAR), "scalar space"), H5Sclose};
  Closer a{h.check(H5Acreate2(obj, name.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT),
                   "cannot create attribute " + name),
           H5Aclose};
  const char* p = value.c_str();
  if (H5Awrite(a.id, type.id, &p) < 0) h.fail("cannot write attribute " + name);
}

template <class T>
void number_attribute(const H5& h, hid_t obj, const std::string& name, T value) {
  Closer space{h.check(H5Screate(H5S_SCALAR), "scalar space"), H5Sclose};
  Closer a{
      h.check(H5Acreate2(obj, name.c_str(), native_type<T>(), space.id, H5P_DEFAULT, H5P_DEFAULT),
              "cannot create attribute " + name),
      H5Aclose};
  if (H5Awrite(a.id, native_type<T>(), &value) < 0) h.fail("cannot write attribute " + name);
}

Closer make_group(const H5& h, hid_t parent, const std::string& name) {
  return {h.check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                  "cannot create group " + name),
          H5Gclose};
}

/// A whole dataset (any rank) as a flat vector, converted to T by HDF5.
template <class T>
std::vector<T> read_column(const H5& h, hid_t file, const std::string& name) {
  Closer ds{h.check(H5Dopen2(file, name.c_str(), H5P_DEFAULT), "no dataset " + name), H5Dclose};
  Closer space{h.check(H5Dget_space(ds.id), "dataspace " + name), H5Sclose};
  const hssize_t n = H5Sget_simple_extent_npoints(space.id);
  if (n < 0) h.fail("cannot size " + name);
  std::vector<T> out(static_cast<std::size_t>(n));
  if (n > 0 && H5Dread(ds.id, native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    h.fail("cannot read " + name);
  return out;
}

bool has_dataset(hid_t file, const std::string& name) {
  return H5Lexists(file, name.c_str(), H5P_DEFAULT) > 0;
}

std::string read_string_attribute(const H5& h, hid_t obj, const std::string& name) {
  Closer a{h.check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "no attribute " + name), H5Aclose};
  Closer type{h.check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose};
  H5Tset_size(type.id, H5T_VARIABLE);
  H5Tset_cset(type.id, H5T_CSET_UTF8);
  char* p = nullptr;
  if (H5Aread(a.id, type.id, &p) < 0 || !p) h.fail("cannot read attribute " + name);
  std::string out(p);
  H5free_memory(p);
  return out;
}

template <class T>
T read_number_attribute(const H5& h, hid_t obj, const std::string& name) {
  Closer a{h.check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "no attribute " + name), H5Aclose};
  T value{};
  if (H5Aread(a.id, native_type<T>(), &value) < 0) h.fail("cannot read attribute " + name);
  return value;
}

// ---- the run ----

struct Recording {
  FrameRows frames;
  PoseRows poses;
  ContactRows contacts;
  AuditRows audit;
  QueryRows queries;
};

void append_pose(const Pose& p, std::vector<double>& out) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out.push_back(p.rotation(r, c));
  out.insert(out.end(), p.translation.data(), p.translation.data() + 3);
}

/// The step's queries (logged by the world) with the poses the bodies had before it.
void record_queries(const std::vector<Pose>& before, const std::vector<scene::QueryRecord>& log,
                    std::int64_t frame, QueryRows& q) {
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

void record_poses(const scene::World& w, std::int64_t frame, PoseRows& r) {
  for (std::uint32_t i = 0; i < w.bodies().size(); ++i) {
    const scene::RigidBody& b = w.bodies()[i];
    if (b.is_static()) continue;
    r.frame.push_back(frame);
    r.body.push_back(i);
    for (int k = 0; k < 3; ++k)
      r.position.push_back(b.pose.translation[k]);
    r.orientation.insert(r.orientation.end(), {b.orientation.w(), b.orientation.x(),
                                               b.orientation.y(), b.orientation.z()});
    for (int k = 0; k < 3; ++k)
      r.velocity.push_back(b.velocity[k]);
    r.touching.push_back(b.touching ? 1 : 0);
  }
}

void record_contacts(const scene::World& w, std::int64_t frame, ContactRows& r) {
  for (const scene::Contact& c : w.contacts()) {
    r.frame.push_back(frame);
    r.a.push_back(c.a);
    r.b.push_back(c.b);
    for (int k = 0; k < 3; ++k)
      r.point.push_back(c.point[k]);
    for (int k = 0; k < 3; ++k)
      r.normal.push_back(c.normal[k]);
    r.depth.push_back(c.depth);
    r.normal_impulse.push_back(c.normal_impulse);
  }
}

/// The broad phases on the world's current boxes, timed (pair search only): the scene's three
/// and, when Bullet is built in, Bullet's dbvt (kept between frames like the others).
struct BroadPhaseComparison {
  scene::BroadPhase all{scene::BroadPhaseKind::all_pairs};
  scene::BroadPhase grid{scene::BroadPhaseKind::grid};
  scene::BroadPhase sap{scene::BroadPhaseKind::sweep_and_prune};
  std::unique_ptr<peers::BulletDbvtBroadphase> dbvt =
      peers::bullet_broadphase_available() ? std::make_unique<peers::BulletDbvtBroadphase>()
                                           : nullptr;
  std::vector<scene::Aabb> boxes;
  std::vector<peers::BroadphaseBox> peer_boxes;
  std::vector<scene::BodyPair> a, g, s, d;

  void run(const scene::World& w, FrameRows& rows) {
    w.bounding_boxes(w.settings().contact_margin, boxes);
    rows.all_pairs_ns.push_back(time([&] { all.find_pairs(boxes, a); }));
    rows.grid_ns.push_back(time([&] { grid.find_pairs(boxes, g); }));
    rows.sap_ns.push_back(time([&] { sap.find_pairs(boxes, s); }));
    bool agree = a == g && a == s;
    if (dbvt) {
      // The copy into the peer's box type is not the broad phase's work: outside the timing.
      peer_boxes.resize(boxes.size());
      for (std::size_t i = 0; i < boxes.size(); ++i)
        peer_boxes[i] = {boxes[i].lower, boxes[i].upper};
      rows.dbvt_ns.push_back(time([&] { dbvt->find_pairs(peer_boxes, d); }));
      agree = agree && a == d;
    }
    rows.broad_phases_agree.push_back(agree ? 1 : 0);
  }
  template <class F>
  static std::int64_t time(F&& search) {
    const auto t0 = std::chrono::steady_clock::now();
    search();
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() -
                                                                t0)
        .count();
  }
};

void record_frame(const scene::World& w, const scene::StepStats& st, double size, FrameRows& f) {
  f.time.push_back(w.time());
  f.kinetic_energy.push_back(w.kinetic_energy());
  f.potential_energy.push_back(w.potential_energy());
  f.max_penetration.push_back(w.max_penetration() / size);
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

enum class Outcome { finished, stopped, not_finite };

/// Where a run stands and when it writes checkpoints.
struct Progress {
  std::int64_t done = 0;        ///< frames simulated
  std::int64_t target = 0;      ///< frames the run is to reach
  std::int64_t checkpoint = 0;  ///< frames between checkpoints (0: none)
  std::int64_t stop_after = 0;  ///< stop after this many frames of this invocation (0: never)
};

/// Steps the scene from p.done to p.target; stops early when the state stops being finite, on
/// a stop signal or after p.stop_after frames. `checkpoint` is called every p.checkpoint frames.
template <class Checkpoint>
Outcome simulate(SceneSetup& s, Recording& r, Progress& p, Checkpoint&& checkpoint) {
  BroadPhaseComparison compare;
  SceneAudit audit(s.audit_depth);
  scene::World& w = *s.world;
  if (p.done == 0) record_poses(w, 0, r.poses);
  std::vector<Pose> before;
  std::vector<scene::QueryRecord> log;
  const std::int64_t first = p.done;
  while (p.done < p.target) {
    const std::int64_t frame = p.done + 1;
    const bool audited = s.audit_every > 0 && frame % s.audit_every == 0;
    if (audited) audit.before_step(w);
    const bool logged = s.queries_every > 0 && frame % s.queries_every == 0;
    if (logged) {
      before.clear();
      for (const scene::RigidBody& b : w.bodies())
        before.push_back(b.pose);
      log.clear();
      w.record_queries(&log);
    }
    const scene::StepStats st = w.step();
    w.record_queries(nullptr);
    p.done = frame;
    if (audited) audit.after_step(w, frame, r.audit);
    if (logged) record_queries(before, log, frame, r.queries);
    record_frame(w, st, s.body_size, r.frames);
    if (s.compare_broad_phases) compare.run(w, r.frames);
    if (frame % s.pose_every == 0) record_poses(w, frame, r.poses);
    if (frame % s.contacts_every == 0) record_contacts(w, frame, r.contacts);
    if (!w.finite()) return Outcome::not_finite;
    if (p.done == p.target) break;
    if (stop_requested() || (p.stop_after > 0 && p.done - first >= p.stop_after))
      return Outcome::stopped;
    if (p.checkpoint > 0 && p.done % p.checkpoint == 0) checkpoint();
  }
  return Outcome::finished;
}

void write_frames(const H5& h, hid_t file, const FrameRows& f, bool compared) {
  Closer g = make_group(h, file, "frames");
  write_column(h, g.id, "time", f.time);
  write_column(h, g.id, "kinetic_energy", f.kinetic_energy);
  write_column(h, g.id, "potential_energy", f.potential_energy);
  write_column(h, g.id, "max_penetration", f.max_penetration);
  write_column(h, g.id, "contacts", f.contacts);
  write_column(h, g.id, "candidate_pairs", f.candidate_pairs);
  write_column(h, g.id, "narrow_queries", f.narrow_queries);
  write_column(h, g.id, "epa_queries", f.epa_queries);
  write_column(h, g.id, "failed_queries", f.failed_queries);
  write_column(h, g.id, "broadphase_ns", f.broadphase_ns);
  write_column(h, g.id, "narrowphase_ns", f.narrowphase_ns);
  write_column(h, g.id, "solver_ns", f.solver_ns);
  write_column(h, g.id, "iterations_mean", f.iterations_mean);
  write_column(h, g.id, "iterations_cold_mean", f.iterations_cold_mean);
  if (compared) {
    write_column(h, g.id, "all_pairs_ns", f.all_pairs_ns);
    write_column(h, g.id, "grid_ns", f.grid_ns);
    write_column(h, g.id, "sap_ns", f.sap_ns);
    if (!f.dbvt_ns.empty()) write_column(h, g.id, "dbvt_ns", f.dbvt_ns);
    write_column(h, g.id, "broad_phases_agree", f.broad_phases_agree);
  }
}

void write_bodies(const H5& h, hid_t file, const SceneSetup& s, const PoseRows& p) {
  Closer g = make_group(h, file, "bodies");
  std::vector<double> mass, size;
  std::vector<std::uint8_t> is_static;
  for (const auto& b : s.world->bodies()) {
    mass.push_back(b.mass);
    size.push_back(b.shape->size);
    is_static.push_back(b.is_static() ? 1 : 0);
  }
  write_strings(h, g.id, "shape", s.shape_names);
  write_column(h, g.id, "mass", mass);
  write_column(h, g.id, "size", size);
  write_column(h, g.id, "is_static", is_static);
  write_column(h, g.id, "pose_frame", p.frame);
  write_column(h, g.id, "pose_body", p.body);
  write_column(h, g.id, "position", p.position, 3);
  write_column(h, g.id, "orientation", p.orientation, 4);
  write_column(h, g.id, "velocity", p.velocity, 3);
  write_column(h, g.id, "touching", p.touching);
}

void write_contacts(const H5& h, hid_t file, const ContactRows& c) {
  Closer g = make_group(h, file, "contacts");
  write_column(h, g.id, "frame", c.frame);
  write_column(h, g.id, "body_a", c.a);
  write_column(h, g.id, "body_b", c.b);
  write_column(h, g.id, "point", c.point, 3);
  write_column(h, g.id, "normal", c.normal, 3);
  write_column(h, g.id, "depth", c.depth);
  write_column(h, g.id, "normal_impulse", c.normal_impulse);
}

void write_audit(const H5& h, hid_t file, const AuditRows& a) {
  Closer g = make_group(h, file, "audit");
  write_column(h, g.id, "frame", a.frame);
  write_column(h, g.id, "body_a", a.a);
  write_column(h, g.id, "body_b", a.b);
  write_column(h, g.id, "intersect", a.intersect);
  write_column(h, g.id, "certified", a.certified);
  write_column(h, g.id, "distance", a.distance);
  write_column(h, g.id, "depth", a.depth);
  write_column(h, g.id, "narrow_depth", a.narrow_depth);
}

void write_queries(const H5& h, hid_t file, const SceneSetup& s, const QueryRows& q) {
  Closer g = make_group(h, file, "queries");
  write_column(h, g.id, "frame", q.frame);
  write_column(h, g.id, "body_a", q.a);
  write_column(h, g.id, "body_b", q.b);
  write_column(h, g.id, "pose_a", q.pose_a, 12);
  write_column(h, g.id, "pose_b", q.pose_b, 12);
  write_column(h, g.id, "warm_size", q.warm_size);
  write_column(h, g.id, "warm_index_a", q.warm_index_a, 4);
  write_column(h, g.id, "warm_index_b", q.warm_index_b, 4);
  write_column(h, g.id, "iterations", q.iterations);
  write_column(h, g.id, "intersect", q.intersect);
  write_column(h, g.id, "distance", q.distance);
  // The shapes' body-frame vertices, each distinct shape once (in the order bodies first use
  // them): shape k is vertices[offset[k], offset[k+1]), body i has shape body_shape[i].
  Closer sg = make_group(h, file, "shapes");
  std::vector<const scene::ConvexShape*> seen;
  std::vector<std::uint32_t> body_shape;
  std::vector<std::int64_t> offset{0};
  std::vector<double> vertices;
  std::vector<double> radius;  // swept radius per shape (length units; 0: the polytope)
  for (const scene::RigidBody& b : s.world->bodies()) {
    auto it = std::find(seen.begin(), seen.end(), b.shape.get());
    if (it == seen.end()) {
      seen.push_back(b.shape.get());
      radius.push_back(b.shape->swept_radius);
      for (const Vec3& v : b.shape->polytope.vertices())
        vertices.insert(vertices.end(), v.data(), v.data() + 3);
      offset.push_back(static_cast<std::int64_t>(vertices.size() / 3));
      it = seen.end() - 1;
    }
    body_shape.push_back(static_cast<std::uint32_t>(it - seen.begin()));
  }
  write_column(h, sg.id, "vertices", vertices, 3);
  write_column(h, sg.id, "offset", offset);
  write_column(h, sg.id, "body_shape", body_shape);
  write_column(h, sg.id, "radius", radius);
}

void write_root(const H5& h, hid_t file, const SceneSetup& s, const std::string& scene_path,
                std::int64_t frames_done) {
  string_attribute(h, file, "format", "gjklab-scene");
  number_attribute<std::int64_t>(h, file, "schema_version", kSceneSchemaVersion);
  for (const auto& [key, value] : experiment::build_provenance())
    string_attribute(h, file, key, value);
  string_attribute(h, file, "scene_name", s.name);
  string_attribute(h, file, "scene_file", scene_path);
  string_attribute(h, file, "scene_toml", s.text);
  number_attribute<std::int64_t>(h, file, "seed", static_cast<std::int64_t>(s.seed));
  number_attribute<std::int64_t>(h, file, "frames", frames_done);
  number_attribute<std::int64_t>(h, file, "pose_every", s.pose_every);
  number_attribute<std::int64_t>(h, file, "contacts_every", s.contacts_every);
  number_attribute<std::int64_t>(h, file, "audit_every", s.audit_every);
  number_attribute<std::uint8_t>(h, file, "audit_depth", s.audit_depth ? 1 : 0);
  number_attribute<std::int64_t>(h, file, "queries_every", s.queries_every);
  number_attribute<double>(h, file, "body_size", s.body_size);
  const auto& st = s.world->settings();
  number_attribute<double>(h, file, "dt", st.dt);
  number_attribute<double>(h, file, "contact_margin", st.contact_margin);
  string_attribute(h, file, "broad_phase", std::string(scene::to_string(st.broad_phase)));
  string_attribute(h, file, "narrow_algorithm",
                   st.query ? st.query->name : std::string(scene::to_string(st.algorithm)));
  string_attribute(h, file, "depth_algorithm", st.depth ? st.depth->name : std::string("epa"));
  number_attribute<std::uint8_t>(h, file, "warm_start", st.warm_start ? 1 : 0);
}

// ---- checkpoints: the world's state, and the recording read back ----

/// The state a resumed run needs beyond the recording: every body's pose and velocities and
/// the world's carried state (pairs' simplices and impulses, clock), in state/.
void write_state(const H5& h, hid_t file, const scene::World& w, std::int64_t target) {
  Closer g = make_group(h, file, "state");
  std::vector<double> position, orientation, velocity, angular_velocity;  // 3, 4 (x y z w), 3, 3
  std::vector<std::uint8_t> touching;
  for (const scene::RigidBody& b : w.bodies()) {
    position.insert(position.end(), b.pose.translation.data(), b.pose.translation.data() + 3);
    orientation.insert(orientation.end(), b.orientation.coeffs().data(),
                       b.orientation.coeffs().data() + 4);
    velocity.insert(velocity.end(), b.velocity.data(), b.velocity.data() + 3);
    angular_velocity.insert(angular_velocity.end(), b.angular_velocity.data(),
                            b.angular_velocity.data() + 3);
    touching.push_back(b.touching ? 1 : 0);
  }
  write_column(h, g.id, "position", position, 3);
  write_column(h, g.id, "orientation_xyzw", orientation, 4);
  write_column(h, g.id, "velocity", velocity, 3);
  write_column(h, g.id, "angular_velocity", angular_velocity, 3);
  write_column(h, g.id, "touching", touching);
  const scene::CarriedState c = w.carried_state();
  number_attribute<double>(h, g.id, "time", c.time);
  number_attribute<std::int64_t>(h, g.id, "steps", static_cast<std::int64_t>(c.steps));
  number_attribute<std::int64_t>(h, g.id, "frames_target", target);
  std::vector<std::uint32_t> pair_a, pair_b, simplex_size, point_count;
  std::vector<double> w_, a_, b_, local, impulse;  // 3 per row
  std::vector<std::int32_t> index_a, index_b;
  for (const scene::PairState& ps : c.pairs) {
    pair_a.push_back(ps.a);
    pair_b.push_back(ps.b);
    simplex_size.push_back(static_cast<std::uint32_t>(ps.simplex.size()));
    point_count.push_back(static_cast<std::uint32_t>(ps.local_a.size()));
    for (const SimplexVertex& v : ps.simplex) {
      w_.insert(w_.end(), v.w.data(), v.w.data() + 3);
      a_.insert(a_.end(), v.a.data(), v.a.data() + 3);
      b_.insert(b_.end(), v.b.data(), v.b.data() + 3);
      index_a.push_back(v.index_a);
      index_b.push_back(v.index_b);
    }
    for (std::size_t k = 0; k < ps.local_a.size(); ++k) {
      local.insert(local.end(), ps.local_a[k].data(), ps.local_a[k].data() + 3);
      impulse.insert(impulse.end(), ps.impulses[k].begin(), ps.impulses[k].end());
    }
  }
  write_column(h, g.id, "pair_a", pair_a);
  write_column(h, g.id, "pair_b", pair_b);
  write_column(h, g.id, "simplex_size", simplex_size);
  write_column(h, g.id, "point_count", point_count);
  write_column(h, g.id, "simplex_w", w_, 3);
  write_column(h, g.id, "simplex_a", a_, 3);
  write_column(h, g.id, "simplex_b", b_, 3);
  write_column(h, g.id, "simplex_index_a", index_a);
  write_column(h, g.id, "simplex_index_b", index_b);
  write_column(h, g.id, "point_local_a", local, 3);
  write_column(h, g.id, "point_impulse", impulse, 3);
}

Vec3 vec3_at(const std::vector<double>& v, std::size_t row) {
  return Vec3(v.at(3 * row), v.at(3 * row + 1), v.at(3 * row + 2));
}

/// Restores what write_state wrote into a world built from the same scene; returns the run's
/// target frame count.
std::int64_t read_state(const H5& h, hid_t file, scene::World& w) {
  auto col = [&](const char* name) {
    return read_column<double>(h, file, "state/" + std::string(name));
  };
  const auto position = col("position"), orientation = col("orientation_xyzw"),
             velocity = col("velocity"), angular_velocity = col("angular_velocity");
  const auto touching = read_column<std::uint8_t>(h, file, "state/touching");
  auto& bodies = w.bodies();
  if (touching.size() != bodies.size() || orientation.size() != 4 * bodies.size())
    h.fail("state/ does not match the scene's " + std::to_string(bodies.size()) + " bodies");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    scene::RigidBody& b = bodies[i];
    b.pose.translation = vec3_at(position, i);
    // Quat(w, x, y, z): the integrator's own quaternion, so the rotation is recomputed as it was.
    b.orientation = Quat(orientation[4 * i + 3], orientation[4 * i], orientation[4 * i + 1],
                         orientation[4 * i + 2]);
    b.pose.rotation = b.orientation.toRotationMatrix();
    b.velocity = vec3_at(velocity, i);
    b.angular_velocity = vec3_at(angular_velocity, i);
    b.touching = touching[i] != 0;
  }
  Closer g{h.check(H5Gopen2(file, "state", H5P_DEFAULT), "no group state"), H5Gclose};
  scene::CarriedState c;
  c.time = read_number_attribute<double>(h, g.id, "time");
  c.steps = static_cast<std::uint64_t>(read_number_attribute<std::int64_t>(h, g.id, "steps"));
  const auto pair_a = read_column<std::uint32_t>(h, file, "state/pair_a");
  const auto pair_b = read_column<std::uint32_t>(h, file, "state/pair_b");
  const auto simplex_size = read_column<std::uint32_t>(h, file, "state/simplex_size");
  const auto point_count = read_column<std::uint32_t>(h, file, "state/point_count");
  const auto sw = col("simplex_w"), sa = col("simplex_a"), sb = col("simplex_b");
  const auto index_a = read_column<std::int32_t>(h, file, "state/simplex_index_a");
  const auto index_b = read_column<std::int32_t>(h, file, "state/simplex_index_b");
  const auto local = col("point_local_a"), impulse = col("point_impulse");
  std::size_t v = 0, q = 0;
  try {
    for (std::size_t k = 0; k < pair_a.size(); ++k) {
      scene::PairState ps;
      ps.a = pair_a.at(k);
      ps.b = pair_b.at(k);
      for (std::uint32_t j = 0; j < simplex_size.at(k); ++j, ++v)
        ps.simplex.push_back(
            {vec3_at(sw, v), vec3_at(sa, v), vec3_at(sb, v), index_a.at(v), index_b.at(v)});
      for (std::uint32_t j = 0; j < point_count.at(k); ++j, ++q) {
        ps.local_a.push_back(vec3_at(local, q));
        ps.impulses.push_back({impulse.at(3 * q), impulse.at(3 * q + 1), impulse.at(3 * q + 2)});
      }
      c.pairs.push_back(std::move(ps));
    }
    w.restore(c);
  } catch (const std::exception& e) {
    h.fail(std::string("state/ is inconsistent: ") + e.what());
  }
  return read_number_attribute<std::int64_t>(h, g.id, "frames_target");
}

/// The recording so far, as write_archive wrote it.
Recording read_recording(const H5& h, hid_t file, const SceneSetup& s) {
  Recording r;
  auto d = [&](const std::string& n) { return read_column<double>(h, file, n); };
  auto i64 = [&](const std::string& n) { return read_column<std::int64_t>(h, file, n); };
  auto u32 = [&](const std::string& n) { return read_column<std::uint32_t>(h, file, n); };
  auto u8 = [&](const std::string& n) { return read_column<std::uint8_t>(h, file, n); };
  FrameRows& f = r.frames;
  f.time = d("frames/time");
  f.kinetic_energy = d("frames/kinetic_energy");
  f.potential_energy = d("frames/potential_energy");
  f.max_penetration = d("frames/max_penetration");
  f.contacts = i64("frames/contacts");
  f.candidate_pairs = i64("frames/candidate_pairs");
  f.narrow_queries = i64("frames/narrow_queries");
  f.epa_queries = i64("frames/epa_queries");
  f.failed_queries = i64("frames/failed_queries");
  f.broadphase_ns = i64("frames/broadphase_ns");
  f.narrowphase_ns = i64("frames/narrowphase_ns");
  f.solver_ns = i64("frames/solver_ns");
  f.iterations_mean = d("frames/iterations_mean");
  f.iterations_cold_mean = d("frames/iterations_cold_mean");
  if (s.compare_broad_phases) {
    f.all_pairs_ns = i64("frames/all_pairs_ns");
    f.grid_ns = i64("frames/grid_ns");
    f.sap_ns = i64("frames/sap_ns");
    if (has_dataset(file, "frames/dbvt_ns")) f.dbvt_ns = i64("frames/dbvt_ns");
    f.broad_phases_agree = u8("frames/broad_phases_agree");
  }
  PoseRows& p = r.poses;
  p.frame = i64("bodies/pose_frame");
  p.body = u32("bodies/pose_body");
  p.position = d("bodies/position");
  p.orientation = d("bodies/orientation");
  p.velocity = d("bodies/velocity");
  p.touching = u8("bodies/touching");
  ContactRows& c = r.contacts;
  c.frame = i64("contacts/frame");
  c.a = u32("contacts/body_a");
  c.b = u32("contacts/body_b");
  c.point = d("contacts/point");
  c.normal = d("contacts/normal");
  c.depth = d("contacts/depth");
  c.normal_impulse = d("contacts/normal_impulse");
  if (s.audit_every > 0) {
    AuditRows& a = r.audit;
    a.frame = i64("audit/frame");
    a.a = u32("audit/body_a");
    a.b = u32("audit/body_b");
    a.intersect = u8("audit/intersect");
    a.certified = u8("audit/certified");
    a.distance = d("audit/distance");
    a.depth = d("audit/depth");
    a.narrow_depth = d("audit/narrow_depth");
  }
  if (s.queries_every > 0) {
    QueryRows& q = r.queries;
    q.frame = i64("queries/frame");
    q.a = u32("queries/body_a");
    q.b = u32("queries/body_b");
    q.pose_a = d("queries/pose_a");
    q.pose_b = d("queries/pose_b");
    q.warm_size = u8("queries/warm_size");
    q.warm_index_a = read_column<std::int32_t>(h, file, "queries/warm_index_a");
    q.warm_index_b = read_column<std::int32_t>(h, file, "queries/warm_index_b");
    q.iterations = read_column<std::int32_t>(h, file, "queries/iterations");
    q.intersect = u8("queries/intersect");
    q.distance = d("queries/distance");
  }
  return r;
}

std::string checkpoint_path(const std::string& path) {
  return path + ".tmp";
}

/// Writes the archive to FILE.tmp.writing, then renames it: to FILE, complete, when the run is
/// over (removing its checkpoint), or to FILE.tmp, with state/ and complete = 0, as a
/// checkpoint. A kill while writing leaves the previous checkpoint intact.
void write_archive(const std::string& path, const SceneSetup& s, const std::string& scene_path,
                   const Recording& r, const Progress& p, bool finite, bool complete) {
  const std::string writing = path + ".tmp.writing";
  const H5 h(path);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  {
    Closer file{h.check(H5Fcreate(writing.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                        "cannot create " + writing),
                H5Fclose};
    write_root(h, file.id, s, scene_path, p.done);
    write_frames(h, file.id, r.frames, s.compare_broad_phases);
    write_bodies(h, file.id, s, r.poses);
    write_contacts(h, file.id, r.contacts);
    if (s.audit_every > 0) write_audit(h, file.id, r.audit);
    if (s.queries_every > 0) write_queries(h, file.id, s, r.queries);
    if (!complete) write_state(h, file.id, *s.world, p.target);
    number_attribute<std::uint8_t>(h, file.id, "finite", finite ? 1 : 0);
    // Written last: a reader that sees complete = 1 sees every dataset.
    number_attribute<std::uint8_t>(h, file.id, "complete", complete ? 1 : 0);
    if (H5Fflush(file.id, H5F_SCOPE_GLOBAL) < 0) h.fail("cannot flush " + writing);
  }
  const std::string target = complete ? path : checkpoint_path(path);
  std::error_code ec;
  fs::rename(writing, target, ec);
  if (ec) h.fail("cannot rename " + writing + ": " + ec.message());
  if (complete) fs::remove(checkpoint_path(path), ec);
}

/// The audit in three numbers: pairs, the share certified, and the narrow phase's largest
/// error on the pairs it made contact with (its depth against the exact signed gap).
void print_audit(const AuditRows& a, std::ostream& out) {
  std::size_t certified = 0, compared = 0;
  double worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    certified += a.certified[k];
    // The exact signed gap: −distance apart, +depth inside (when computed).
    const double exact = a.intersect[k] ? a.depth[k] : -a.distance[k];
    if (std::isnan(a.narrow_depth[k]) || std::isnan(exact)) continue;
    ++compared;
    worst = std::max(worst, std::abs(a.narrow_depth[k] - exact));
  }
  out << "\n  audit: " << a.size() << " pairs exactly, " << certified << " certified; narrow "
      << "phase vs exact on " << compared << " pairs with contacts: largest |error| " << worst;
}

double mean(const std::vector<double>& v, const std::vector<std::int64_t>& weights) {
  double sum = 0, n = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    sum += v[i] * static_cast<double>(weights[i]);
    n += static_cast<double>(weights[i]);
  }
  return n > 0 ? sum / n : 0;
}

/// Prints the end of a run (or where its checkpoint was left); the command's exit status.
int report(const SceneSetup& s, const std::string& path, const Recording& r, const Progress& p,
           Outcome outcome, std::ostream& out, std::ostream& err) {
  if (outcome == Outcome::stopped) {
    err << "gjklab simulate: stopped after frame " << p.done << " of " << p.target << ": "
        << checkpoint_path(path) << " (continue with gjklab simulate --resume "
        << checkpoint_path(path) << ")\n";
    return stop_requested() ? 130 : 0;
  }
  const FrameRows& f = r.frames;
  double max_pen = 0;
  for (double x : f.max_penetration)
    max_pen = std::max(max_pen, x);
  out << "scene " << s.name << ": " << s.world->bodies().size() << " bodies, " << p.done
      << " frames (" << f.time.back() << " s)\n"
      << "  max penetration / body size: " << max_pen << "\n"
      << "  mean GJK iterations: " << mean(f.iterations_mean, f.narrow_queries);
  if (s.world->settings().measure_cold)
    out << " (cold: " << mean(f.iterations_cold_mean, f.narrow_queries) << ")";
  if (s.audit_every > 0) print_audit(r.audit, out);
  out << "\n  archive: " << path << "\n";
  if (outcome == Outcome::not_finite) {
    err << "gjklab simulate: the state stopped being finite at frame " << p.done << "\n";
    return 1;
  }
  return 0;
}

/// Runs from p.done to p.target with checkpoints, and writes the archive or the checkpoint.
int run_and_write(SceneSetup& s, const std::string& path, const std::string& scene_path,
                  Recording& r, Progress& p, std::ostream& out, std::ostream& err) {
  const StopSignals signals;
  const Outcome outcome =
      simulate(s, r, p, [&] { write_archive(path, s, scene_path, r, p, true, false); });
  const bool finite = s.world->finite();
  write_archive(path, s, scene_path, r, p, finite, outcome != Outcome::stopped);
  return report(s, path, r, p, outcome, out, err);
}

/// The archive path a checkpoint belongs to: FILE.h5 for FILE.h5.tmp (or FILE.h5 itself).
std::string final_path_of(const std::string& given) {
  const std::string suffix = ".tmp";
  if (given.size() > suffix.size() &&
      given.compare(given.size() - suffix.size(), suffix.size(), suffix) == 0)
    return given.substr(0, given.size() - suffix.size());
  return given;
}

int resume(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  const std::string path = final_path_of(args.resume);
  const std::string tmp = checkpoint_path(path);
  if (!fs::exists(tmp)) {
    err << "gjklab simulate: no checkpoint " << tmp << " to resume\n";
    return 1;
  }
  const H5 h(tmp);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  std::string scene_path;
  SceneSetup s;
  Recording r;
  Progress p;
  {
    Closer file{h.check(H5Fopen(tmp.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "cannot open " + tmp),
                H5Fclose};
    if (read_string_attribute(h, file.id, "format") != "gjklab-scene")
      h.fail("not a scene archive");
    scene_path = read_string_attribute(h, file.id, "scene_file");
    // The scene as the interrupted run read it (the file may have changed since).
    s = parse_scene(read_string_attribute(h, file.id, "scene_toml"), scene_path);
    r = read_recording(h, file.id, s);
    p.done = read_number_attribute<std::int64_t>(h, file.id, "frames");
    p.target = read_state(h, file.id, *s.world);
  }
  if (args.threads > 0) s.world->set_threads(args.threads);
  p.checkpoint = args.checkpoint;
  p.stop_after = args.stop_after;
  return run_and_write(s, path, scene_path, r, p, out, err);
}

}  // namespace

CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "step a scene of rigid bodies (broad phase, warm-started GJK, contacts) and "
      "write its HDF5 archive");
  cmd->add_option("scene", args.scene, "scene file (TOML)");
  cmd->add_option("--out", args.output, "archive path (default: results/<scene name>.h5)");
  cmd->add_option("--frames", args.frames, "frames to simulate (default: the file's `frames`)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{100'000'000}));
  cmd->add_flag("--force", args.force, "overwrite an existing archive");
  cmd->add_option("--resume", args.resume,
                  "continue an interrupted run (FILE.h5.tmp) from its last checkpoint");
  cmd->add_option(
         "--checkpoint", args.checkpoint,
         "frames between checkpoints (default " + std::to_string(args.checkpoint) + "; 0: none)")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{100'000'000}));
  cmd->add_option("--stop-after", args.stop_after,
                  "stop after N frames, leaving a checkpoint to --resume (runs in parts)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{100'000'000}));
  cmd->add_option("--threads", args.threads,
                  "narrow-phase threads (default: the file's [narrow_phase] threads, else 1; "
                  "the archive is the same for any count)")
      ->check(CLI::Range(1, 1024));
  return cmd;
}

int run_simulate_command(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  stop_requested() = false;
  try {
    if (args.scene.empty() == args.resume.empty()) {
      err << "gjklab simulate: give a scene file, or --resume FILE (not both)\n";
      return 1;
    }
    if (!args.resume.empty()) {
      if (!args.output.empty() || args.frames > 0 || args.force) {
        err << "gjklab simulate: --resume continues the run as it was planned; --out, --frames "
               "and --force do not apply\n";
        return 1;
      }
      return resume(args, out, err);
    }
    SceneSetup s = load_scene(args.scene);
    if (args.threads > 0) s.world->set_threads(args.threads);
    const std::string path = args.output.empty() ? "results/" + s.name + ".h5" : args.output;
    if (fs::exists(path) && !args.force) {
      err << "gjklab simulate: " << path << " exists (use --force to overwrite)\n";
      return 1;
    }
    Recording r;
    Progress p;
    p.target = args.frames > 0 ? args.frames : s.frames;
    p.checkpoint = args.checkpoint;
    p.stop_after = args.stop_after;
    return run_and_write(s, path, args.scene, r, p, out, err);
  } catch (const experiment::ConfigError& e) {
    err << "gjklab simulate: " << e.what() << "\n";
    return 1;
  } catch (const SimulationError& e) {
    err << "gjklab simulate: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gjklab::cli
