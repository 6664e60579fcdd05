// The HDF5 results archive: writer and reader. Schema (version 1): results/README.md.

#include "gjklab/experiment/archive.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <iostream>
#include <optional>
#include <set>
#include <string_view>
#include <system_error>
#include <unordered_map>

#include "hdf5_util.hpp"

namespace gjklab::experiment {

namespace fs = std::filesystem;

namespace {

// Root attributes with a fixed meaning; every other root attribute is a provenance pair.
constexpr std::array<std::string_view, 17> kRootAttributes = {"schema_version",
                                                              "experiment_name",
                                                              "experiment_text",
                                                              "seed",
                                                              "cases_planned",
                                                              "start_time",
                                                              "end_time",
                                                              "oracle",
                                                              "touching_band",
                                                              "family_names",
                                                              "algorithm_names",
                                                              "complete",
                                                              "checkpoint_cases",
                                                              "checkpoint_geometry",
                                                              "checkpoint_vertices_a",
                                                              "checkpoint_vertices_b",
                                                              "trace_mode"};

bool is_root_attribute(std::string_view name) {
  return name.starts_with("checkpoint_") ||
         std::find(kRootAttributes.begin(), kRootAttributes.end(), name) != kRootAttributes.end();
}

// Rows per chunk of the per-case columns: 4096, or fewer for a run planned smaller.
hsize_t case_chunk_rows(std::uint64_t planned) {
  if (planned == 0) return 4096;
  return static_cast<hsize_t>(std::clamp<std::uint64_t>(planned, 64, 4096));
}
constexpr hsize_t kVertexChunkRows = 4096;

// Rejects headers the layout cannot hold, before any file is created.
void check_header(const ArchiveHeader& h, const h5::Context& cx) {
  std::set<std::string> seen;
  for (const auto& [key, value] : h.provenance) {
    if (key.empty()) cx.error("a provenance key is empty");
    if (is_root_attribute(key))
      cx.error("provenance key '" + key + "' is the name of a root attribute");
    if (!seen.insert(key).second) cx.error("provenance key '" + key + "' appears twice");
  }
  seen.clear();
  for (const auto& name : h.algorithm_names) {
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
      cx.error("algorithm name '" + name + "' cannot name an HDF5 group");
    if (!seen.insert(name).second) cx.error("algorithm '" + name + "' appears twice");
  }
  if (!h.algorithm_options.empty() && h.algorithm_options.size() != h.algorithm_names.size())
    cx.error("algorithm_options has " + std::to_string(h.algorithm_options.size()) +
             " entries for " + std::to_string(h.algorithm_names.size()) + " algorithms");
  for (std::size_t i = 0; i < h.algorithm_options.size(); ++i) {
    seen.clear();
    for (const auto& [key, value] : h.algorithm_options[i]) {
      if (key.empty() || !seen.insert(key).second)
        cx.error("option '" + key + "' of algorithm '" + h.algorithm_names[i] +
                 "' is empty or appears twice");
    }
  }
}

// Forces the file's bytes to disk before it is renamed (best effort).
void sync_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  (void)::fsync(fd);
  (void)::close(fd);
}

template <class T, class F>
std::vector<T> gather(std::span<const CaseResult> results, F field) {
  std::vector<T> values;
  values.reserve(results.size());
  for (const CaseResult& r : results)
    values.push_back(static_cast<T>(field(r)));
  return values;
}

/// A 3-vector field of every result, row by row (x, y, z).
template <class F>
std::vector<double> gather_vec3(std::span<const CaseResult> results, F field) {
  std::vector<double> values;
  values.reserve(3 * results.size());
  for (const CaseResult& r : results) {
    const Vec3& v = field(r);
    values.insert(values.end(), {v.x(), v.y(), v.z()});
  }
  return values;
}

// The HDF5 types of the archive, shared by the writer and the reader.
struct Types {
  h5::Handle boolean, string, shape, placement, contact, termination, failure, step, method;

  explicit Types(const h5::Context& cx)
      : boolean(h5::bool_type(cx)),
        string(h5::string_type(cx)),
        shape(h5::enum_type<ShapeKind>(cx)),
        placement(h5::enum_type<Placement>(cx)),
        contact(h5::enum_type<ContactClass>(cx)),
        termination(h5::enum_type<Termination>(cx)),
        failure(h5::enum_type<FailureClass>(cx)),
        step(h5::enum_type<GjkStep>(cx)),
        method(h5::enum_type<exact::AnswerMethod>(cx)) {}
};

}  // namespace

// ---- writer ----

struct ArchiveWriter::Impl {
  struct CaseColumns {
    h5::Column case_id, family, shape_a, shape_b, placement, vertices_a, vertices_b, scale, size,
        intended_gap, radius_a, radius_b;
  };
  struct ExactColumns {
    h5::Column intersect, distance, distance2_num, distance2_den, depth, hull_vertices_a,
        hull_vertices_b, contact, method, depth_method;
  };
  struct AlgorithmColumns {
    h5::Column intersect, distance, abs_error, rel_error, boolean_correct, iterations,
        support_calls, termination, time_ns, failure, depth, depth_abs_error, depth_rel_error,
        witness_a, witness_b, witness_error_a, witness_error_b, witness_distance_error,
        rounded_exact_distance, rounded_exact_depth;
  };
  struct GeometryColumns {
    h5::Column case_id, a_offset, a_count, b_offset, b_count, vertices_a, vertices_b;
  };
  /// One row per traced iteration (see GjkIterationTrace); simplex columns hold 4 points.
  struct TraceColumns {
    h5::Column case_id, iteration, step, direction, support, index_a, index_b, v_norm_squared,
        v_dot_w, lower_bound, simplex_size, simplex, simplex_index_a, simplex_index_b, weights;
    std::vector<h5::Column*> all() {
      return {&case_id,         &iteration,       &step,    &direction,   &support,      &index_a,
              &index_b,         &v_norm_squared,  &v_dot_w, &lower_bound, &simplex_size, &simplex,
              &simplex_index_a, &simplex_index_b, &weights};
    }
  };
  struct Columns {
    CaseColumns cases;
    std::optional<ExactColumns> exact;
    std::vector<AlgorithmColumns> algorithms;
    GeometryColumns geometry;
    std::vector<TraceColumns> traces;  ///< per algorithm, when traces are kept

    /// Closes every dataset, reporting the first that fails to close.
    void close(const h5::Context& cx) {
      std::vector<h5::Column*> all{
          &cases.case_id,    &cases.family,        &cases.shape_a,      &cases.shape_b,
          &cases.placement,  &cases.vertices_a,    &cases.vertices_b,   &cases.scale,
          &cases.size,       &cases.intended_gap,  &cases.radius_a,     &cases.radius_b,
          &geometry.case_id, &geometry.a_offset,   &geometry.a_count,   &geometry.b_offset,
          &geometry.b_count, &geometry.vertices_a, &geometry.vertices_b};
      if (exact)
        all.insert(all.end(), {&exact->intersect, &exact->distance, &exact->distance2_num,
                               &exact->distance2_den, &exact->depth, &exact->hull_vertices_a,
                               &exact->hull_vertices_b, &exact->contact, &exact->method,
                               &exact->depth_method});
      for (AlgorithmColumns& a : algorithms)
        all.insert(all.end(), {&a.intersect,
                               &a.distance,
                               &a.abs_error,
                               &a.rel_error,
                               &a.boolean_correct,
                               &a.iterations,
                               &a.support_calls,
                               &a.termination,
                               &a.time_ns,
                               &a.failure,
                               &a.depth,
                               &a.depth_abs_error,
                               &a.depth_rel_error,
                               &a.witness_a,
                               &a.witness_b,
                               &a.witness_error_a,
                               &a.witness_error_b,
                               &a.witness_distance_error,
                               &a.rounded_exact_distance,
                               &a.rounded_exact_depth});
      for (TraceColumns& t : traces)
        for (h5::Column* c : t.all())
          all.push_back(c);
      for (h5::Column* c : all)
        cx.check(c->close(), "cannot close dataset " + c->path());
    }
  };

  fs::path final_path;
  fs::path temp_path;
  bool overwrite = false;
  bool oracle = true;
  std::size_t algorithm_count = 0;
  h5::Context cx;
  // Declaration order matters: the file is closed after everything opened in it.
  h5::Handle file;
  h5::Handle root;
  std::optional<Types> types;
  std::optional<Columns> columns;
  bool finished = false;
  bool broken = false;  // a write failed: the columns may differ in length
  // The files this writer made: only these may it remove when it fails. (A run that failed
  // on another run's lock once deleted that run's FILE.tmp.)
  bool made_file = false;      // FILE.tmp.new, created exclusively
  bool made_temp = false;      // FILE.tmp, linked from it
  bool made_snapshot = false;  // FILE.tmp.checkpoint

  Impl(fs::path final_p, fs::path temp_p, bool overwrite_, const ArchiveHeader& h)
      : final_path(std::move(final_p)),
        temp_path(std::move(temp_p)),
        overwrite(overwrite_),
        oracle(h.oracle),
        algorithm_count(h.algorithm_names.size()),
        cx(temp_path.string()) {}

  h5::Column column(hid_t group, const std::string& group_path, const char* name, hid_t file_type,
                    hid_t mem_type, hsize_t chunk, hsize_t width = 1) const {
    return h5::Column(cx, group, group_path, name, file_type, mem_type, width, chunk);
  }

  void create(const ArchiveHeader& h);
  void write(std::span<const CaseResult> results);
  void append_traces(TraceColumns& c, std::span<const CaseResult> rs, std::size_t algorithm);

  /// Records how many rows every group holds, flushes the file and snapshots it: an
  /// interrupted run can be read back (and resumed) up to the last checkpoint, or from the
  /// snapshot when a kill cut a later write short.
  void checkpoint() {
    const hid_t r = root.get();
    h5::write_attr_u64(cx, r, "/", "checkpoint_cases", columns->cases.case_id.rows());
    h5::write_attr_u64(cx, r, "/", "checkpoint_geometry", columns->geometry.case_id.rows());
    h5::write_attr_u64(cx, r, "/", "checkpoint_vertices_a", columns->geometry.vertices_a.rows());
    h5::write_attr_u64(cx, r, "/", "checkpoint_vertices_b", columns->geometry.vertices_b.rows());
    for (std::size_t k = 0; k < columns->traces.size(); ++k)
      h5::write_attr_u64(cx, r, "/", "checkpoint_traces_" + std::to_string(k),
                         columns->traces[k].case_id.rows());
    cx.check(H5Fflush(root.get(), H5F_SCOPE_GLOBAL), "cannot flush the file");
    snapshot();
  }

  /// A copy of the flushed file (FILE.tmp.checkpoint, replaced atomically). A process killed
  /// in the middle of a write can leave chunks of rows written before the last checkpoint half
  /// rewritten (HDF5 rewrites a partly filled chunk in place), and the file unreadable; the
  /// copy is then what `--resume` reads. A copy is skipped until 20 times the last copy's
  /// duration has passed since it, which keeps copying near 5 % of the run however large the
  /// archive grows.
  void snapshot() {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    if (last_snapshot && start - *last_snapshot < 20 * last_copy) return;
    fs::path fresh = snapshot_path(temp_path);
    fresh += ".new";
    std::error_code ec;
    fs::copy_file(file_path, fresh, fs::copy_options::overwrite_existing, ec);
    if (!ec) sync_file(fresh);
    if (!ec) fs::rename(fresh, snapshot_path(temp_path), ec);
    if (ec) cx.error("cannot write the checkpoint copy " + fresh.string() + ": " + ec.message());
    made_snapshot = true;
    last_snapshot = Clock::now();
    last_copy = *last_snapshot - start;
  }
  /// Where the open file is: "FILE.tmp.new" while it is created, then FILE.tmp.
  fs::path file_path;
  std::optional<std::chrono::steady_clock::time_point> last_snapshot;
  std::chrono::steady_clock::duration last_copy{};
};

void ArchiveWriter::Impl::create(const ArchiveHeader& h) {
  h5::Handle fcpl =
      cx.handle(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "cannot create file properties");
  cx.check(H5Pset_attr_creation_order(fcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
           "cannot track the attribute order of /");
  h5::Handle fapl =
      cx.handle(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create file properties");
  // Closing the file fails (instead of silently staying open) if anything in it is still open.
  cx.check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_SEMI), "cannot set the file close degree");
  // Created under another name and given FILE.tmp only once its header is flushed and
  // snapshotted: a run killed before then leaves no FILE.tmp to resume, rather than one that
  // cannot be read.
  file_path = temp_path;
  file_path += ".new";
  // Exclusive: a FILE.tmp.new that exists belongs to a run that is starting (or was killed
  // while starting), and is never truncated.
  file = cx.handle(H5Fcreate(file_path.c_str(), H5F_ACC_EXCL, fcpl.get(), fapl.get()), H5Fclose,
                   "cannot create the file " + file_path.string() +
                       " (does another run write the same archive?)");
  made_file = true;
  root = cx.handle(H5Gopen2(file.get(), "/", H5P_DEFAULT), H5Gclose, "cannot open group /");
  const hid_t r = root.get();

  h5::write_attr_i32(cx, r, "/", "schema_version", kArchiveSchemaVersion);
  for (const auto& [key, value] : h.provenance)
    h5::write_attr_string(cx, r, "/", key, value);
  h5::write_attr_string(cx, r, "/", "experiment_name", h.experiment_name);
  h5::write_attr_string(cx, r, "/", "experiment_text", h.experiment_text);
  h5::write_attr_u64(cx, r, "/", "seed", h.seed);
  h5::write_attr_u64(cx, r, "/", "cases_planned", h.cases_planned);
  h5::write_attr_string(cx, r, "/", "start_time", h.start_time);
  h5::write_attr_u8(cx, r, "/", "oracle", h.oracle ? 1 : 0);
  h5::write_attr_f64(cx, r, "/", "touching_band", h.touching_band);
  h5::write_attr_strings(cx, r, "/", "family_names", h.family_names);
  h5::write_attr_strings(cx, r, "/", "algorithm_names", h.algorithm_names);
  h5::write_attr_string(cx, r, "/", "trace_mode", h.trace_mode);

  types.emplace(cx);
  const Types& t = *types;
  const hsize_t chunk = case_chunk_rows(h.cases_planned);
  const hid_t u64f = H5T_STD_U64LE, u64m = H5T_NATIVE_UINT64;
  const hid_t u32f = H5T_STD_U32LE, u32m = H5T_NATIVE_UINT32;
  const hid_t i32f = H5T_STD_I32LE, i32m = H5T_NATIVE_INT32;
  const hid_t f64f = H5T_IEEE_F64LE, f64m = H5T_NATIVE_DOUBLE;
  const hid_t bt = t.boolean.get(), st = t.string.get();

  Columns c;
  {
    const std::string p = "/cases";
    h5::Handle g = h5::create_group(cx, r, "/", "cases");
    const hid_t gi = g.get();
    c.cases = CaseColumns{
        column(gi, p, "case_id", u64f, u64m, chunk),
        column(gi, p, "family", u32f, u32m, chunk),
        column(gi, p, "shape_a", t.shape.get(), t.shape.get(), chunk),
        column(gi, p, "shape_b", t.shape.get(), t.shape.get(), chunk),
        column(gi, p, "placement", t.placement.get(), t.placement.get(), chunk),
        column(gi, p, "vertices_a", i32f, i32m, chunk),
        column(gi, p, "vertices_b", i32f, i32m, chunk),
        column(gi, p, "scale", f64f, f64m, chunk),
        column(gi, p, "size", f64f, f64m, chunk),
        column(gi, p, "intended_gap", f64f, f64m, chunk),
        column(gi, p, "radius_a", f64f, f64m, chunk),
        column(gi, p, "radius_b", f64f, f64m, chunk),
    };
  }
  if (h.oracle) {
    const std::string p = "/exact";
    h5::Handle g = h5::create_group(cx, r, "/", "exact");
    const hid_t gi = g.get();
    c.exact = ExactColumns{
        column(gi, p, "intersect", bt, bt, chunk),
        column(gi, p, "distance", f64f, f64m, chunk),
        column(gi, p, "distance2_num", st, st, chunk),
        column(gi, p, "distance2_den", st, st, chunk),
        column(gi, p, "depth", f64f, f64m, chunk),
        column(gi, p, "hull_vertices_a", i32f, i32m, chunk),
        column(gi, p, "hull_vertices_b", i32f, i32m, chunk),
        column(gi, p, "contact", t.contact.get(), t.contact.get(), chunk),
        column(gi, p, "method", t.method.get(), t.method.get(), chunk),
        column(gi, p, "depth_method", t.method.get(), t.method.get(), chunk),
    };
  }
  {
    h5::Handle all = h5::create_group(cx, r, "/", "algorithms");
    for (std::size_t i = 0; i < h.algorithm_names.size(); ++i) {
      const std::string& name = h.algorithm_names[i];
      const std::string p = "/algorithms/" + name;
      h5::Handle g = h5::create_group(cx, all.get(), "/algorithms", name);
      const hid_t gi = g.get();
      if (i < h.algorithm_options.size())
        for (const auto& [key, value] : h.algorithm_options[i])
          h5::write_attr_string(cx, gi, p, key, value);
      c.algorithms.push_back(AlgorithmColumns{
          column(gi, p, "intersect", bt, bt, chunk),
          column(gi, p, "distance", f64f, f64m, chunk),
          column(gi, p, "abs_error", f64f, f64m, chunk),
          column(gi, p, "rel_error", f64f, f64m, chunk),
          column(gi, p, "boolean_correct", bt, bt, chunk),
          column(gi, p, "iterations", i32f, i32m, chunk),
          column(gi, p, "support_calls", i32f, i32m, chunk),
          column(gi, p, "termination", t.termination.get(), t.termination.get(), chunk),
          column(gi, p, "time_ns", f64f, f64m, chunk),
          column(gi, p, "failure", t.failure.get(), t.failure.get(), chunk),
          column(gi, p, "depth", f64f, f64m, chunk),
          column(gi, p, "depth_abs_error", f64f, f64m, chunk),
          column(gi, p, "depth_rel_error", f64f, f64m, chunk),
          column(gi, p, "witness_a", f64f, f64m, chunk, 3),
          column(gi, p, "witness_b", f64f, f64m, chunk, 3),
          column(gi, p, "witness_error_a", f64f, f64m, chunk),
          column(gi, p, "witness_error_b", f64f, f64m, chunk),
          column(gi, p, "witness_distance_error", f64f, f64m, chunk),
          column(gi, p, "rounded_exact_distance", f64f, f64m, chunk),
          column(gi, p, "rounded_exact_depth", f64f, f64m, chunk),
      });
    }
  }
  {
    const std::string p = "/geometry";
    h5::Handle g = h5::create_group(cx, r, "/", "geometry");
    const hid_t gi = g.get();
    c.geometry = GeometryColumns{
        column(gi, p, "case_id", u64f, u64m, chunk),
        column(gi, p, "a_offset", u64f, u64m, chunk),
        column(gi, p, "a_count", u64f, u64m, chunk),
        column(gi, p, "b_offset", u64f, u64m, chunk),
        column(gi, p, "b_count", u64f, u64m, chunk),
        column(gi, p, "vertices_a", f64f, f64m, kVertexChunkRows, 3),
        column(gi, p, "vertices_b", f64f, f64m, kVertexChunkRows, 3),
    };
  }
  if (h.trace_mode != "none") {
    h5::Handle all = h5::create_group(cx, r, "/", "traces");
    for (const std::string& name : h.algorithm_names) {
      const std::string p = "/traces/" + name;
      h5::Handle g = h5::create_group(cx, all.get(), "/traces", name);
      const hid_t gi = g.get();
      c.traces.push_back(TraceColumns{
          column(gi, p, "case_id", u64f, u64m, kVertexChunkRows),
          column(gi, p, "iteration", i32f, i32m, kVertexChunkRows),
          column(gi, p, "step", t.step.get(), t.step.get(), kVertexChunkRows),
          column(gi, p, "direction", f64f, f64m, kVertexChunkRows, 3),
          column(gi, p, "support", f64f, f64m, kVertexChunkRows, 3),
          column(gi, p, "index_a", i32f, i32m, kVertexChunkRows),
          column(gi, p, "index_b", i32f, i32m, kVertexChunkRows),
          column(gi, p, "v_norm_squared", f64f, f64m, kVertexChunkRows),
          column(gi, p, "v_dot_w", f64f, f64m, kVertexChunkRows),
          column(gi, p, "lower_bound", f64f, f64m, kVertexChunkRows),
          column(gi, p, "simplex_size", i32f, i32m, kVertexChunkRows),
          column(gi, p, "simplex", f64f, f64m, kVertexChunkRows, 12),
          column(gi, p, "simplex_index_a", i32f, i32m, kVertexChunkRows, 4),
          column(gi, p, "simplex_index_b", i32f, i32m, kVertexChunkRows, 4),
          column(gi, p, "weights", f64f, f64m, kVertexChunkRows, 4),
      });
    }
  }
  columns = std::move(c);
}

void ArchiveWriter::Impl::write(std::span<const CaseResult> rs) {
  using R = const CaseResult&;
  Columns& c = *columns;
  {
    CaseColumns& k = c.cases;
    k.case_id.append(cx, gather<std::uint64_t>(rs, [](R r) { return r.record.case_id; }));
    k.family.append(cx, gather<std::uint32_t>(rs, [](R r) { return r.record.family; }));
    k.shape_a.append(cx, gather<ShapeKind>(rs, [](R r) { return r.record.shape_a; }));
    k.shape_b.append(cx, gather<ShapeKind>(rs, [](R r) { return r.record.shape_b; }));
    k.placement.append(cx, gather<Placement>(rs, [](R r) { return r.record.placement; }));
    k.vertices_a.append(cx, gather<std::int32_t>(rs, [](R r) { return r.record.vertices_a; }));
    k.vertices_b.append(cx, gather<std::int32_t>(rs, [](R r) { return r.record.vertices_b; }));
    k.scale.append(cx, gather<double>(rs, [](R r) { return r.record.scale; }));
    k.size.append(cx, gather<double>(rs, [](R r) { return r.record.size; }));
    k.intended_gap.append(cx, gather<double>(rs, [](R r) { return r.record.intended_gap; }));
    k.radius_a.append(cx, gather<double>(rs, [](R r) { return r.record.radius_a; }));
    k.radius_b.append(cx, gather<double>(rs, [](R r) { return r.record.radius_b; }));
  }
  if (c.exact) {
    ExactColumns& e = *c.exact;
    e.intersect.append(cx, gather<std::int8_t>(rs, [](R r) { return r.exact->intersect; }));
    e.distance.append(cx, gather<double>(rs, [](R r) { return r.exact->distance; }));
    e.distance2_num.append(
        cx, gather<const char*>(rs, [](R r) { return r.exact->distance2_num.c_str(); }));
    e.distance2_den.append(
        cx, gather<const char*>(rs, [](R r) { return r.exact->distance2_den.c_str(); }));
    e.depth.append(cx, gather<double>(rs, [](R r) { return r.exact->depth; }));
    e.hull_vertices_a.append(
        cx, gather<std::int32_t>(rs, [](R r) { return r.exact->hull_vertices_a; }));
    e.hull_vertices_b.append(
        cx, gather<std::int32_t>(rs, [](R r) { return r.exact->hull_vertices_b; }));
    e.contact.append(cx, gather<ContactClass>(rs, [](R r) { return r.exact->contact; }));
    e.method.append(cx, gather<exact::AnswerMethod>(rs, [](R r) { return r.exact->method; }));
    e.depth_method.append(
        cx, gather<exact::AnswerMethod>(rs, [](R r) { return r.exact->depth_method; }));
  }
  for (std::size_t i = 0; i < c.algorithms.size(); ++i) {
    AlgorithmColumns& a = c.algorithms[i];
    const auto alg = [i](R r) -> const AlgorithmRecord& { return r.algorithms[i]; };
    a.intersect.append(cx, gather<std::int8_t>(rs, [&](R r) { return alg(r).intersect; }));
    a.distance.append(cx, gather<double>(rs, [&](R r) { return alg(r).distance; }));
    a.abs_error.append(cx, gather<double>(rs, [&](R r) { return alg(r).abs_error; }));
    a.rel_error.append(cx, gather<double>(rs, [&](R r) { return alg(r).rel_error; }));
    a.boolean_correct.append(cx,
                             gather<std::int8_t>(rs, [&](R r) { return alg(r).boolean_correct; }));
    a.iterations.append(cx, gather<std::int32_t>(rs, [&](R r) { return alg(r).iterations; }));
    a.support_calls.append(cx, gather<std::int32_t>(rs, [&](R r) { return alg(r).support_calls; }));
    a.termination.append(cx, gather<Termination>(rs, [&](R r) { return alg(r).termination; }));
    a.time_ns.append(cx, gather<double>(rs, [&](R r) { return alg(r).time_ns; }));
    a.failure.append(cx, gather<FailureClass>(rs, [&](R r) { return alg(r).failure; }));
    a.depth.append(cx, gather<double>(rs, [&](R r) { return alg(r).depth; }));
    a.depth_abs_error.append(cx, gather<double>(rs, [&](R r) { return alg(r).depth_abs_error; }));
    a.depth_rel_error.append(cx, gather<double>(rs, [&](R r) { return alg(r).depth_rel_error; }));
    a.witness_a.append(cx, gather_vec3(rs, [&](R r) -> const Vec3& { return alg(r).witness_a; }));
    a.witness_b.append(cx, gather_vec3(rs, [&](R r) -> const Vec3& { return alg(r).witness_b; }));
    a.witness_error_a.append(cx, gather<double>(rs, [&](R r) { return alg(r).witness_error_a; }));
    a.witness_error_b.append(cx, gather<double>(rs, [&](R r) { return alg(r).witness_error_b; }));
    a.witness_distance_error.append(
        cx, gather<double>(rs, [&](R r) { return alg(r).witness_distance_error; }));
    a.rounded_exact_distance.append(
        cx, gather<double>(rs, [&](R r) { return alg(r).rounded_exact_distance; }));
    a.rounded_exact_depth.append(
        cx, gather<double>(rs, [&](R r) { return alg(r).rounded_exact_depth; }));
  }
  {
    GeometryColumns& g = c.geometry;
    std::vector<std::uint64_t> case_id, a_offset, a_count, b_offset, b_count;
    std::vector<double> va, vb;
    for (const CaseResult& r : rs) {
      if (!r.geometry) continue;
      case_id.push_back(r.record.case_id);
      a_offset.push_back(g.vertices_a.rows() + va.size() / 3);
      a_count.push_back(r.geometry->a.size());
      b_offset.push_back(g.vertices_b.rows() + vb.size() / 3);
      b_count.push_back(r.geometry->b.size());
      for (const Vec3& v : r.geometry->a)
        va.insert(va.end(), {v.x(), v.y(), v.z()});
      for (const Vec3& v : r.geometry->b)
        vb.insert(vb.end(), {v.x(), v.y(), v.z()});
    }
    g.case_id.append(cx, case_id);
    g.a_offset.append(cx, a_offset);
    g.a_count.append(cx, a_count);
    g.b_offset.append(cx, b_offset);
    g.b_count.append(cx, b_count);
    g.vertices_a.append(cx, va);
    g.vertices_b.append(cx, vb);
  }
  for (std::size_t k = 0; k < c.traces.size(); ++k)
    append_traces(c.traces[k], rs, k);
}

void ArchiveWriter::Impl::append_traces(TraceColumns& c, std::span<const CaseResult> rs,
                                        std::size_t algorithm) {
  std::vector<std::uint64_t> case_id;
  std::vector<std::int32_t> iteration, index_a, index_b, simplex_size, sia, sib;
  std::vector<GjkStep> step;
  std::vector<double> direction, support, vv, vw, lb, simplex, weights;
  for (const CaseResult& r : rs) {
    if (algorithm >= r.traces.size()) continue;
    for (const GjkIterationTrace& t : r.traces[algorithm]) {
      case_id.push_back(r.record.case_id);
      iteration.push_back(t.iteration);
      step.push_back(t.step);
      direction.insert(direction.end(), {t.direction.x(), t.direction.y(), t.direction.z()});
      const Vec3& w = t.support.w;
      support.insert(support.end(), {w.x(), w.y(), w.z()});
      index_a.push_back(t.support.index_a);
      index_b.push_back(t.support.index_b);
      vv.push_back(t.v_norm_squared);
      vw.push_back(t.v_dot_w);
      lb.push_back(t.lower_bound);
      simplex_size.push_back(t.simplex.size());
      for (int i = 0; i < 4; ++i) {
        const bool in = i < t.simplex.size();
        const Vec3 p = in ? t.simplex[i].w : Vec3::Zero();
        simplex.insert(simplex.end(), {p.x(), p.y(), p.z()});
        sia.push_back(in ? t.simplex[i].index_a : -1);
        sib.push_back(in ? t.simplex[i].index_b : -1);
        weights.push_back(in ? t.weights[i] : 0.0);
      }
    }
  }
  c.case_id.append(cx, case_id);
  c.iteration.append(cx, iteration);
  c.step.append(cx, step);
  c.direction.append(cx, direction);
  c.support.append(cx, support);
  c.index_a.append(cx, index_a);
  c.index_b.append(cx, index_b);
  c.v_norm_squared.append(cx, vv);
  c.v_dot_w.append(cx, vw);
  c.lower_bound.append(cx, lb);
  c.simplex_size.append(cx, simplex_size);
  c.simplex.append(cx, simplex);
  c.simplex_index_a.append(cx, sia);
  c.simplex_index_b.append(cx, sib);
  c.weights.append(cx, weights);
}

namespace {

/// Before a run creates FILE.tmp.new: the temporary names must be free, or --force given. An
/// existing FILE.tmp is an interrupted run, resumable, and FILE.tmp.new a run that is starting
/// or was killed while starting: neither is replaced silently.
void claim_temporary_names(const fs::path& temp, bool overwrite) {
  fs::path creating = temp;
  creating += ".new";
  std::error_code ec;
  if (overwrite) {
    fs::remove(creating, ec);
    return;
  }
  if (fs::exists(temp, ec))
    throw ArchiveError(temp.string() +
                       " exists: a run of this archive is still going or was interrupted (continue "
                       "an interrupted one with `gjklab run --resume " +
                       temp.string() + "`, or start afresh with --force)");
  if (fs::exists(creating, ec))
    throw ArchiveError(creating.string() +
                       " exists: another run is starting on this archive, or one was killed "
                       "while starting (remove it, or use --force)");
}

/// Gives the created file its FILE.tmp name. Without --force a FILE.tmp that appeared in the
/// meantime (another run) is never replaced: link(2) fails on an existing name, where
/// rename(2) would overwrite it.
void give_temporary_name(const fs::path& created, const fs::path& temp, bool overwrite,
                         const h5::Context& cx) {
  std::error_code ec;
  if (overwrite) {
    fs::rename(created, temp, ec);
    if (ec) cx.error("cannot rename it from " + created.string() + ": " + ec.message());
    return;
  }
  if (::link(created.c_str(), temp.c_str()) == 0) {
    fs::remove(created, ec);
    return;
  }
  const int error = errno;
  if (error == EEXIST)
    cx.error("cannot name it " + temp.string() +
             ": that file appeared meanwhile (does another run write the same archive?)");
  // A file system without hard links: check, then rename (a narrow race, but no worse).
  if (fs::exists(temp, ec))
    cx.error("cannot name it " + temp.string() + ": that file appeared meanwhile");
  fs::rename(created, temp, ec);
  if (ec) cx.error("cannot rename it from " + created.string() + ": " + ec.message());
}

}  // namespace

ArchiveWriter::ArchiveWriter(const fs::path& final_path, const ArchiveHeader& header,
                             bool overwrite) {
  const std::string name = final_path.string();
  if (final_path.empty() || !final_path.has_filename())
    throw ArchiveError("archive path '" + name + "' does not name a file");
  std::error_code ec;
  if (fs::is_directory(final_path, ec)) throw ArchiveError(name + " is a folder");
  if (fs::exists(final_path, ec) && !overwrite)
    throw ArchiveError(name + " exists (use --force to overwrite)");
  const fs::path folder = final_path.has_parent_path() ? final_path.parent_path() : fs::path(".");
  if (!fs::is_directory(folder, ec))
    throw ArchiveError("cannot write " + name + ": folder " + folder.string() + " does not exist");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw ArchiveError("cannot write " + name + ": folder " + folder.string() + " is not writable");

  check_header(header, h5::Context(name));

  fs::path temp = final_path;
  temp += ".tmp";
  claim_temporary_names(temp, overwrite);
  h5::quiet_errors();
  auto impl = std::make_unique<Impl>(final_path, temp, overwrite, header);
  try {
    impl->create(header);
    impl->checkpoint();  // no rows yet: a run killed from now on resumes from this copy
    give_temporary_name(impl->file_path, temp, overwrite, impl->cx);
    impl->made_temp = true;
    impl->file_path = temp;
  } catch (...) {
    const fs::path created = impl->file_path;
    const bool made_file = impl->made_file, made_temp = impl->made_temp,
               made_snapshot = impl->made_snapshot;
    impl.reset();  // closes whatever was opened
    if (made_file && !made_temp) fs::remove(created, ec);
    if (made_temp) fs::remove(temp, ec);
    if (made_snapshot) fs::remove(snapshot_path(temp), ec);
    throw;
  }
  impl_ = std::move(impl);
}

ArchiveWriter::~ArchiveWriter() = default;

void ArchiveWriter::append(std::span<const CaseResult> results) {
  Impl& w = *impl_;
  if (w.finished) w.cx.error("append after finish");
  if (w.broken) w.cx.error("append after a failed write");
  for (const CaseResult& r : results) {
    const auto id = [&r] { return "case " + std::to_string(r.record.case_id); };
    if (r.algorithms.size() != w.algorithm_count)
      w.cx.error(id() + " has " + std::to_string(r.algorithms.size()) +
                 " algorithm records, expected " + std::to_string(w.algorithm_count));
    if (r.exact.has_value() != w.oracle)
      w.cx.error(id() + (w.oracle ? " has no exact record but the oracle is on"
                                  : " has an exact record but the oracle is off"));
  }
  try {
    w.write(results);
    w.checkpoint();
  } catch (...) {
    w.broken = true;
    throw;
  }
}

void ArchiveWriter::finish(const std::string& end_time, bool complete) {
  Impl& w = *impl_;
  if (w.finished) w.cx.error("finish called twice");
  w.finished = true;
  const bool whole = complete && !w.broken;
  h5::write_attr_string(w.cx, w.root.get(), "/", "end_time", end_time);
  w.columns->close(w.cx);
  w.columns.reset();
  w.cx.check(H5Fflush(w.root.get(), H5F_SCOPE_GLOBAL), "cannot flush the file");
  // The completion flag comes last, after everything else is in the file.
  h5::write_attr_u8(w.cx, w.root.get(), "/", "complete", whole ? 1 : 0);
  w.cx.check(w.root.close(), "cannot close group /");
  w.cx.check(w.file.close(), "cannot close the file");
  // Closed cleanly, the temporary file is whole up to its last checkpoint: no copy is needed.
  std::error_code removed;
  fs::remove(snapshot_path(w.temp_path), removed);
  if (complete && !whole)
    w.cx.error("an earlier write failed; the incomplete archive stays at " + w.temp_path.string());
  if (!whole) return;

  sync_file(w.temp_path);
  std::error_code ec;
  if (!w.overwrite && fs::exists(w.final_path, ec))
    w.cx.error(w.final_path.string() + " exists (use --force to overwrite); the archive stays at " +
               w.temp_path.string());
  fs::rename(w.temp_path, w.final_path, ec);
  if (ec) w.cx.error("cannot rename it to " + w.final_path.string() + ": " + ec.message());
}

const fs::path& ArchiveWriter::temporary_path() const {
  return impl_->temp_path;
}

// ---- reader ----

namespace {

/// Rows of each algorithm's trace group up to the last checkpoint (any_rows when complete).
std::vector<hsize_t> committed_traces_for(const h5::Context& cx, hid_t r, bool complete,
                                          const ArchiveHeader& h) {
  std::vector<hsize_t> rows(h.algorithm_names.size(), h5::any_rows);
  if (complete) return rows;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::string name = "checkpoint_traces_" + std::to_string(k);
    if (h5::has_attr(cx, r, "/", name)) rows[k] = h5::read_attr_u64(cx, r, "/", name);
  }
  return rows;
}

/// Reads /traces/<algorithm> back into each case's traces.
void read_traces(const h5::Context& cx, hid_t r, const Types& t, Archive& a,
                 const std::vector<hsize_t>& committed) {
  const auto& names = a.header.algorithm_names;
  std::unordered_map<std::uint64_t, std::size_t> index;
  for (std::size_t i = 0; i < a.results.size(); ++i) {
    index.emplace(a.results[i].record.case_id, i);
    a.results[i].traces.assign(names.size(), {});
  }
  const hid_t u64m = H5T_NATIVE_UINT64, i32m = H5T_NATIVE_INT32, f64m = H5T_NATIVE_DOUBLE;
  const h5::Handle all = h5::open_group(cx, r, "/", "traces");
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string p = "/traces/" + names[k];
    const h5::Handle g = h5::open_group(cx, all.get(), "/traces", names[k]);
    const hid_t gi = g.get();
    const auto case_id = h5::read_column<std::uint64_t>(cx, gi, p, "case_id", u64m, committed[k]);
    const std::size_t n = case_id.size();
    const auto iteration = h5::read_column<std::int32_t>(cx, gi, p, "iteration", i32m, n);
    const auto step = h5::read_column<GjkStep>(cx, gi, p, "step", t.step.get(), n);
    const auto direction = h5::read_column<double>(cx, gi, p, "direction", f64m, n, 3);
    const auto support = h5::read_column<double>(cx, gi, p, "support", f64m, n, 3);
    const auto index_a = h5::read_column<std::int32_t>(cx, gi, p, "index_a", i32m, n);
    const auto index_b = h5::read_column<std::int32_t>(cx, gi, p, "index_b", i32m, n);
    const auto vv = h5::read_column<double>(cx, gi, p, "v_norm_squared", f64m, n);
    const auto vw = h5::read_column<double>(cx, gi, p, "v_dot_w", f64m, n);
    const auto lb = h5::read_column<double>(cx, gi, p, "lower_bound", f64m, n);
    const auto size = h5::read_column<std::int32_t>(cx, gi, p, "simplex_size", i32m, n);
    const auto simplex = h5::read_column<double>(cx, gi, p, "simplex", f64m, n, 12);
    const auto sia = h5::read_column<std::int32_t>(cx, gi, p, "simplex_index_a", i32m, n, 4);
    const auto sib = h5::read_column<std::int32_t>(cx, gi, p, "simplex_index_b", i32m, n, 4);
    const auto weights = h5::read_column<double>(cx, gi, p, "weights", f64m, n, 4);
    for (std::size_t j = 0; j < n; ++j) {
      const auto it = index.find(case_id[j]);
      if (it == index.end())
        cx.error(p + "/case_id " + std::to_string(case_id[j]) + " is not in /cases/case_id");
      if (size[j] < 0 || size[j] > Simplex::kCapacity)
        cx.error(p + "/simplex_size " + std::to_string(size[j]) + " is out of range");
      GjkIterationTrace tr;
      tr.iteration = iteration[j];
      tr.step = step[j];
      tr.direction = Vec3(direction[3 * j], direction[3 * j + 1], direction[3 * j + 2]);
      tr.support.w = Vec3(support[3 * j], support[3 * j + 1], support[3 * j + 2]);
      tr.support.index_a = index_a[j];
      tr.support.index_b = index_b[j];
      tr.v_norm_squared = vv[j];
      tr.v_dot_w = vw[j];
      tr.lower_bound = lb[j];
      for (int i = 0; i < size[j]; ++i) {
        SimplexVertex v;
        v.w =
            Vec3(simplex[12 * j + 3 * i], simplex[12 * j + 3 * i + 1], simplex[12 * j + 3 * i + 2]);
        v.index_a = sia[4 * j + i];
        v.index_b = sib[4 * j + i];
        tr.simplex.push(v);
        tr.weights[i] = weights[4 * j + i];
      }
      a.results[it->second].traces[k].push_back(tr);
    }
  }
}

}  // namespace

Archive read_archive(const fs::path& path) {
  h5::quiet_errors();
  h5::Context cx(path.string());
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) cx.error("no such file");
  if (H5Fis_hdf5(path.c_str()) <= 0) cx.error("not an HDF5 file");
  const h5::Handle file = cx.handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                                    "cannot open the file");
  const h5::Handle root =
      cx.handle(H5Gopen2(file.get(), "/", H5P_DEFAULT), H5Gclose, "cannot open group /");
  const hid_t r = root.get();

  Archive a;
  a.schema_version = h5::read_attr_i32(cx, r, "/", "schema_version");
  if (a.schema_version != kArchiveSchemaVersion)
    cx.error("schema_version " + std::to_string(a.schema_version) + " is not supported (expected " +
             std::to_string(kArchiveSchemaVersion) + ")");
  ArchiveHeader& h = a.header;
  h.experiment_name = h5::read_attr_string(cx, r, "/", "experiment_name");
  h.experiment_text = h5::read_attr_string(cx, r, "/", "experiment_text");
  h.seed = h5::read_attr_u64(cx, r, "/", "seed");
  h.cases_planned = h5::read_attr_u64(cx, r, "/", "cases_planned");
  h.start_time = h5::read_attr_string(cx, r, "/", "start_time");
  h.oracle = h5::read_attr_u8(cx, r, "/", "oracle") != 0;
  h.touching_band = h5::read_attr_f64(cx, r, "/", "touching_band");
  h.family_names = h5::read_attr_strings(cx, r, "/", "family_names");
  h.algorithm_names = h5::read_attr_strings(cx, r, "/", "algorithm_names");
  // A run that stopped before finish() has neither: it is incomplete.
  if (h5::has_attr(cx, r, "/", "end_time"))
    a.end_time = h5::read_attr_string(cx, r, "/", "end_time");
  if (h5::has_attr(cx, r, "/", "complete"))
    a.complete = h5::read_attr_u8(cx, r, "/", "complete") != 0;
  for (const std::string& key : h5::attr_names(cx, r, "/")) {
    if (is_root_attribute(key)) continue;
    if (h5::attr_class(cx, r, "/", key) != H5T_STRING)
      cx.error("attribute '" + key + "' of / is not a string");
    h.provenance.emplace_back(key, h5::read_attr_string(cx, r, "/", key));
  }

  // An incomplete run is read up to its last checkpoint: rows written after it (a write cut
  // off by a kill) are ignored.
  auto checkpoint = [&](const char* name) {
    return !a.complete && h5::has_attr(cx, r, "/", name) ? h5::read_attr_u64(cx, r, "/", name)
                                                         : h5::any_rows;
  };
  const hsize_t committed_cases = checkpoint("checkpoint_cases");
  const hsize_t committed_geometry = checkpoint("checkpoint_geometry");
  const hsize_t committed_a = checkpoint("checkpoint_vertices_a");
  const hsize_t committed_b = checkpoint("checkpoint_vertices_b");
  cx.allow_prefix_reads(!a.complete);

  const Types t(cx);
  const hid_t u64m = H5T_NATIVE_UINT64, u32m = H5T_NATIVE_UINT32, i32m = H5T_NATIVE_INT32,
              f64m = H5T_NATIVE_DOUBLE;
  const hid_t bt = t.boolean.get();

  std::size_t n = 0;
  {
    const std::string p = "/cases";
    const h5::Handle g = h5::open_group(cx, r, "/", "cases");
    const hid_t gi = g.get();
    const auto case_id =
        h5::read_column<std::uint64_t>(cx, gi, p, "case_id", u64m, committed_cases);
    n = case_id.size();
    const auto family = h5::read_column<std::uint32_t>(cx, gi, p, "family", u32m, n);
    const auto shape_a = h5::read_column<ShapeKind>(cx, gi, p, "shape_a", t.shape.get(), n);
    const auto shape_b = h5::read_column<ShapeKind>(cx, gi, p, "shape_b", t.shape.get(), n);
    const auto placement = h5::read_column<Placement>(cx, gi, p, "placement", t.placement.get(), n);
    const auto vertices_a = h5::read_column<std::int32_t>(cx, gi, p, "vertices_a", i32m, n);
    const auto vertices_b = h5::read_column<std::int32_t>(cx, gi, p, "vertices_b", i32m, n);
    const auto scale = h5::read_column<double>(cx, gi, p, "scale", f64m, n);
    const auto size = h5::read_column<double>(cx, gi, p, "size", f64m, n);
    const auto gap = h5::read_column<double>(cx, gi, p, "intended_gap", f64m, n);
    // Archives written before sphere-swept shapes have no radius columns: radius 0.
    auto radius = [&](const char* name) {
      return h5::has_link(cx, gi, p, name) ? h5::read_column<double>(cx, gi, p, name, f64m, n)
                                           : std::vector<double>(n, 0.0);
    };
    const auto radius_a = radius("radius_a");
    const auto radius_b = radius("radius_b");
    a.results.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      CaseRecord& c = a.results[i].record;
      c.case_id = case_id[i];
      c.family = family[i];
      c.shape_a = shape_a[i];
      c.shape_b = shape_b[i];
      c.placement = placement[i];
      c.vertices_a = vertices_a[i];
      c.vertices_b = vertices_b[i];
      c.scale = scale[i];
      c.size = size[i];
      c.intended_gap = gap[i];
      c.radius_a = radius_a[i];
      c.radius_b = radius_b[i];
    }
  }
  if (h.oracle) {
    const std::string p = "/exact";
    const h5::Handle g = h5::open_group(cx, r, "/", "exact");
    const hid_t gi = g.get();
    const auto intersect = h5::read_column<std::int8_t>(cx, gi, p, "intersect", bt, n);
    const auto distance = h5::read_column<double>(cx, gi, p, "distance", f64m, n);
    const auto num = h5::read_string_column(cx, gi, p, "distance2_num", n);
    const auto den = h5::read_string_column(cx, gi, p, "distance2_den", n);
    const auto depth = h5::read_column<double>(cx, gi, p, "depth", f64m, n);
    const auto hull_a = h5::read_column<std::int32_t>(cx, gi, p, "hull_vertices_a", i32m, n);
    const auto hull_b = h5::read_column<std::int32_t>(cx, gi, p, "hull_vertices_b", i32m, n);
    const auto contact = h5::read_column<ContactClass>(cx, gi, p, "contact", t.contact.get(), n);
    const auto method =
        h5::read_column<exact::AnswerMethod>(cx, gi, p, "method", t.method.get(), n);
    const auto depth_method =
        h5::read_column<exact::AnswerMethod>(cx, gi, p, "depth_method", t.method.get(), n);
    for (std::size_t i = 0; i < n; ++i) {
      ExactRecord& e = a.results[i].exact.emplace();
      e.intersect = intersect[i] != 0;
      e.distance = distance[i];
      e.distance2_num = num[i];
      e.distance2_den = den[i];
      e.depth = depth[i];
      e.hull_vertices_a = hull_a[i];
      e.hull_vertices_b = hull_b[i];
      e.contact = contact[i];
      e.method = method[i];
      e.depth_method = depth_method[i];
    }
  }
  {
    const h5::Handle all = h5::open_group(cx, r, "/", "algorithms");
    for (CaseResult& res : a.results)
      res.algorithms.resize(h.algorithm_names.size());
    for (std::size_t k = 0; k < h.algorithm_names.size(); ++k) {
      const std::string& name = h.algorithm_names[k];
      const std::string p = "/algorithms/" + name;
      const h5::Handle g = h5::open_group(cx, all.get(), "/algorithms", name);
      const hid_t gi = g.get();
      auto& options = h.algorithm_options.emplace_back();
      for (const std::string& key : h5::attr_names(cx, gi, p)) {
        if (h5::attr_class(cx, gi, p, key) != H5T_STRING)
          cx.error("attribute '" + key + "' of " + p + " is not a string");
        options.emplace_back(key, h5::read_attr_string(cx, gi, p, key));
      }
      const auto intersect = h5::read_column<std::int8_t>(cx, gi, p, "intersect", bt, n);
      const auto distance = h5::read_column<double>(cx, gi, p, "distance", f64m, n);
      const auto abs_error = h5::read_column<double>(cx, gi, p, "abs_error", f64m, n);
      const auto rel_error = h5::read_column<double>(cx, gi, p, "rel_error", f64m, n);
      const auto correct = h5::read_column<std::int8_t>(cx, gi, p, "boolean_correct", bt, n);
      const auto iterations = h5::read_column<std::int32_t>(cx, gi, p, "iterations", i32m, n);
      const auto support = h5::read_column<std::int32_t>(cx, gi, p, "support_calls", i32m, n);
      const auto termination =
          h5::read_column<Termination>(cx, gi, p, "termination", t.termination.get(), n);
      const auto time_ns = h5::read_column<double>(cx, gi, p, "time_ns", f64m, n);
      const auto failure = h5::read_column<FailureClass>(cx, gi, p, "failure", t.failure.get(), n);
      const auto depth = h5::read_column<double>(cx, gi, p, "depth", f64m, n);
      const auto depth_abs = h5::read_column<double>(cx, gi, p, "depth_abs_error", f64m, n);
      const auto depth_rel = h5::read_column<double>(cx, gi, p, "depth_rel_error", f64m, n);
      const auto witness_a = h5::read_column<double>(cx, gi, p, "witness_a", f64m, n, 3);
      const auto witness_b = h5::read_column<double>(cx, gi, p, "witness_b", f64m, n, 3);
      const auto witness_error_a = h5::read_column<double>(cx, gi, p, "witness_error_a", f64m, n);
      const auto witness_error_b = h5::read_column<double>(cx, gi, p, "witness_error_b", f64m, n);
      const auto witness_distance_error =
          h5::read_column<double>(cx, gi, p, "witness_distance_error", f64m, n);
      // Archives written before the precision option have no such columns: NaN (double).
      auto optional_column = [&](const char* name) {
        return h5::has_link(cx, gi, p, name)
                   ? h5::read_column<double>(cx, gi, p, name, f64m, n)
                   : std::vector<double>(n, std::numeric_limits<double>::quiet_NaN());
      };
      const auto rounded_exact_distance = optional_column("rounded_exact_distance");
      const auto rounded_exact_depth = optional_column("rounded_exact_depth");
      for (std::size_t i = 0; i < n; ++i) {
        AlgorithmRecord& ar = a.results[i].algorithms[k];
        ar.intersect = intersect[i] != 0;
        ar.distance = distance[i];
        ar.abs_error = abs_error[i];
        ar.rel_error = rel_error[i];
        ar.boolean_correct = correct[i] != 0;
        ar.iterations = iterations[i];
        ar.support_calls = support[i];
        ar.termination = termination[i];
        ar.time_ns = time_ns[i];
        ar.failure = failure[i];
        ar.depth = depth[i];
        ar.depth_abs_error = depth_abs[i];
        ar.depth_rel_error = depth_rel[i];
        ar.witness_a = Vec3(witness_a[3 * i], witness_a[3 * i + 1], witness_a[3 * i + 2]);
        ar.witness_b = Vec3(witness_b[3 * i], witness_b[3 * i + 1], witness_b[3 * i + 2]);
        ar.witness_error_a = witness_error_a[i];
        ar.witness_error_b = witness_error_b[i];
        ar.witness_distance_error = witness_distance_error[i];
        ar.rounded_exact_distance = rounded_exact_distance[i];
        ar.rounded_exact_depth = rounded_exact_depth[i];
      }
    }
  }
  {
    const std::string p = "/geometry";
    const h5::Handle g = h5::open_group(cx, r, "/", "geometry");
    const hid_t gi = g.get();
    const auto case_id =
        h5::read_column<std::uint64_t>(cx, gi, p, "case_id", u64m, committed_geometry);
    const std::size_t m = case_id.size();
    const auto a_offset = h5::read_column<std::uint64_t>(cx, gi, p, "a_offset", u64m, m);
    const auto a_count = h5::read_column<std::uint64_t>(cx, gi, p, "a_count", u64m, m);
    const auto b_offset = h5::read_column<std::uint64_t>(cx, gi, p, "b_offset", u64m, m);
    const auto b_count = h5::read_column<std::uint64_t>(cx, gi, p, "b_count", u64m, m);
    const auto va = h5::read_column<double>(cx, gi, p, "vertices_a", f64m, committed_a, 3);
    const auto vb = h5::read_column<double>(cx, gi, p, "vertices_b", f64m, committed_b, 3);
    std::unordered_map<std::uint64_t, std::size_t> index;
    index.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      index.emplace(a.results[i].record.case_id, i);
    const auto slice = [&](const std::vector<double>& v, std::uint64_t offset, std::uint64_t count,
                           const std::string& what) {
      const std::uint64_t rows = v.size() / 3;
      if (count > rows || offset > rows - count)
        cx.error(p + "/" + what + " rows [" + std::to_string(offset) + ", " +
                 std::to_string(offset + count) + ") lie outside its " + std::to_string(rows) +
                 " rows");
      std::vector<Vec3> out;
      out.reserve(count);
      for (std::uint64_t j = offset; j < offset + count; ++j)
        out.emplace_back(v[3 * j], v[3 * j + 1], v[3 * j + 2]);
      return out;
    };
    for (std::size_t j = 0; j < m; ++j) {
      const auto it = index.find(case_id[j]);
      if (it == index.end())
        cx.error(p + "/case_id " + std::to_string(case_id[j]) + " is not in /cases/case_id");
      CaseGeometry& geo = a.results[it->second].geometry.emplace();
      geo.a = slice(va, a_offset[j], a_count[j], "vertices_a");
      geo.b = slice(vb, b_offset[j], b_count[j], "vertices_b");
    }
  }
  if (h5::has_attr(cx, r, "/", "trace_mode"))
    h.trace_mode = h5::read_attr_string(cx, r, "/", "trace_mode");
  if (h.trace_mode != "none") read_traces(cx, r, t, a, committed_traces_for(cx, r, a.complete, h));
  return a;
}

namespace {

/// Reads the archive in a forked child; throws ArchiveError if the child failed or crashed.
void probe_in_child(const fs::path& path) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) return;  // cannot isolate: the caller reads unguarded
  std::cout.flush();
  std::cerr.flush();
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    return;
  }
  if (child == 0) {
    ::close(pipe_fds[0]);
    int status = 0;
    try {
      read_archive(path);
    } catch (const std::exception& e) {
      const std::string message = e.what();
      [[maybe_unused]] const auto written = ::write(pipe_fds[1], message.data(), message.size());
      status = 1;
    }
    ::_exit(status);
  }
  ::close(pipe_fds[1]);
  std::string message;
  char buffer[4096];
  for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0;)
    message.append(buffer, static_cast<std::size_t>(n));
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status))
    throw ArchiveError(path.string() + ": corrupt: reading it made the HDF5 library crash (" +
                       ::strsignal(WTERMSIG(status)) + "); the file cannot be used");
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0) throw ArchiveError(message);
}

}  // namespace

Archive read_archive_isolated(const fs::path& path) {
  probe_in_child(path);
  return read_archive(path);
}

}  // namespace gjklab::experiment
