#include "gjklab/simulate.hpp"

#include <hdf5.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "gjklab/experiment/config.hpp"
#include "gjklab/experiment/provenance.hpp"
#include "gjklab/peers/bullet_broadphase.hpp"
#include "gjklab/scene_audit.hpp"
#include "gjklab/scene_file.hpp"

namespace gjklab::cli {

namespace fs = std::filesystem;

namespace {

/// Schema of the scene archive (documented in README.md, "Scenes"); bumped on any change.
constexpr int kSceneSchemaVersion = 2;  // 2: frames/dbvt_ns, audit/

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

// ---- the run ----

struct Recording {
  FrameRows frames;
  PoseRows poses;
  ContactRows contacts;
  AuditRows audit;
};

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

/// Steps the scene; stops early (reported) if the state stops being finite.
Recording simulate(SceneSetup& s, std::int64_t frames, std::int64_t& done) {
  Recording r;
  BroadPhaseComparison compare;
  SceneAudit audit(s.audit_depth);
  scene::World& w = *s.world;
  record_poses(w, 0, r.poses);
  for (done = 0; done < frames;) {
    const bool audited = s.audit_every > 0 && (done + 1) % s.audit_every == 0;
    if (audited) audit.before_step(w);
    const scene::StepStats st = w.step();
    ++done;
    if (audited) audit.after_step(w, done, r.audit);
    record_frame(w, st, s.body_size, r.frames);
    if (s.compare_broad_phases) compare.run(w, r.frames);
    if (done % s.pose_every == 0) record_poses(w, done, r.poses);
    if (done % s.contacts_every == 0) record_contacts(w, done, r.contacts);
    if (!w.finite()) break;
  }
  return r;
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
  number_attribute<double>(h, file, "body_size", s.body_size);
  const auto& st = s.world->settings();
  number_attribute<double>(h, file, "dt", st.dt);
  number_attribute<double>(h, file, "contact_margin", st.contact_margin);
  string_attribute(h, file, "broad_phase", std::string(scene::to_string(st.broad_phase)));
  string_attribute(h, file, "narrow_algorithm", std::string(scene::to_string(st.algorithm)));
  number_attribute<std::uint8_t>(h, file, "warm_start", st.warm_start ? 1 : 0);
}

/// Writes FILE.tmp and renames it to FILE once every dataset and the completion flag are in.
void write_archive(const std::string& path, const SceneSetup& s, const std::string& scene_path,
                   const Recording& r, std::int64_t frames_done, bool finite) {
  const std::string temp = path + ".tmp";
  const H5 h(path);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  {
    Closer file{h.check(H5Fcreate(temp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                        "cannot create " + temp),
                H5Fclose};
    write_root(h, file.id, s, scene_path, frames_done);
    write_frames(h, file.id, r.frames, s.compare_broad_phases);
    write_bodies(h, file.id, s, r.poses);
    write_contacts(h, file.id, r.contacts);
    if (s.audit_every > 0) write_audit(h, file.id, r.audit);
    number_attribute<std::uint8_t>(h, file.id, "finite", finite ? 1 : 0);
    // Written last: a reader that sees complete = 1 sees every dataset.
    number_attribute<std::uint8_t>(h, file.id, "complete", 1);
    if (H5Fflush(file.id, H5F_SCOPE_GLOBAL) < 0) h.fail("cannot flush " + temp);
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) h.fail("cannot rename " + temp + ": " + ec.message());
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

}  // namespace

CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "step a scene of rigid bodies (broad phase, warm-started GJK, contacts) and "
      "write its HDF5 archive");
  cmd->add_option("scene", args.scene, "scene file (TOML)")->required();
  cmd->add_option("--out", args.output, "archive path (default: results/<scene name>.h5)");
  cmd->add_option("--frames", args.frames, "frames to simulate (default: the file's `frames`)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{100'000'000}));
  cmd->add_flag("--force", args.force, "overwrite an existing archive");
  return cmd;
}

int run_simulate_command(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  try {
    SceneSetup s = load_scene(args.scene);
    const std::string path = args.output.empty() ? "results/" + s.name + ".h5" : args.output;
    if (fs::exists(path) && !args.force) {
      err << "gjklab simulate: " << path << " exists (use --force to overwrite)\n";
      return 1;
    }
    const std::int64_t frames = args.frames > 0 ? args.frames : s.frames;
    std::int64_t done = 0;
    const Recording r = simulate(s, frames, done);
    const bool finite = s.world->finite();
    write_archive(path, s, args.scene, r, done, finite);
    const FrameRows& f = r.frames;
    double max_pen = 0;
    for (double p : f.max_penetration)
      max_pen = std::max(max_pen, p);
    out << "scene " << s.name << ": " << s.world->bodies().size() << " bodies, " << done
        << " frames (" << f.time.back() << " s)\n"
        << "  max penetration / body size: " << max_pen << "\n"
        << "  mean GJK iterations: " << mean(f.iterations_mean, f.narrow_queries);
    if (s.world->settings().measure_cold)
      out << " (cold: " << mean(f.iterations_cold_mean, f.narrow_queries) << ")";
    if (s.audit_every > 0) print_audit(r.audit, out);
    out << "\n  archive: " << path << "\n";
    if (!finite) {
      err << "gjklab simulate: the state stopped being finite at frame " << done << "\n";
      return 1;
    }
    return 0;
  } catch (const experiment::ConfigError& e) {
    err << "gjklab simulate: " << e.what() << "\n";
    return 1;
  } catch (const SimulationError& e) {
    err << "gjklab simulate: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gjklab::cli
