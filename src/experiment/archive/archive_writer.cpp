// The HDF5 results archive's writer. The columns of every group come from the schema tables
// (archive_schema.hpp); results/README.md documents them.

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <optional>
#include <set>
#include <span>
#include <string_view>
#include <system_error>

#include "archive_schema.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "hdf5_util.hpp"

namespace gjklab::experiment {

namespace fs = std::filesystem;

namespace {

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

/// The datasets of one schema table in one group, created together and appended to row by row.
template <class R>
class ColumnTable {
 public:
  template <std::size_t N>
  ColumnTable(const h5::Context& cx, const schema::Types& t, hid_t group, const std::string& path,
              const std::array<schema::ColumnSpec<R>, N>& specs, hsize_t chunk_rows)
      : specs_(specs) {
    for (const auto& spec : specs_)
      std::visit(
          [&](auto member) {
            using S = schema::Storage<typename schema::MemberType<decltype(member)>::type>;
            columns_.emplace_back(cx, group, path, std::string(spec.name), S::file(t), S::memory(t),
                                  S::width, chunk_rows);
          },
          spec.field);
  }

  /// Appends one row per record to every column.
  void append(const h5::Context& cx, std::span<const R* const> rows) {
    for (std::size_t k = 0; k < specs_.size(); ++k)
      std::visit([&](auto member) { append_field(cx, columns_[k], rows, member); },
                 specs_[k].field);
  }
  void append(const h5::Context& cx, const std::vector<R>& rows) {
    std::vector<const R*> pointers;
    pointers.reserve(rows.size());
    for (const R& row : rows)
      pointers.push_back(&row);
    append(cx, pointers);
  }

  hsize_t rows() const { return columns_.front().rows(); }

  /// Closes every dataset, reporting the first that fails to close.
  void close(const h5::Context& cx) {
    for (h5::Column& c : columns_)
      cx.check(c.close(), "cannot close dataset " + c.path());
  }

 private:
  template <class T>
  static void append_field(const h5::Context& cx, h5::Column& column,
                           std::span<const R* const> rows, T R::*member) {
    using S = schema::Storage<T>;
    std::vector<typename S::Element> values;
    values.reserve(S::width * rows.size());
    for (const R* row : rows)
      S::put(row->*member, values);
    column.append(cx, values);
  }

  std::span<const schema::ColumnSpec<R>> specs_;
  std::vector<h5::Column> columns_;
};

/// /geometry: the index of kept cases and the points of their clouds.
struct GeometryTables {
  ColumnTable<schema::GeometryRow> index;
  ColumnTable<schema::VertexRow> vertices_a, vertices_b;

  void append(const h5::Context& cx, std::span<const CaseResult> results);
  void close(const h5::Context& cx) {
    index.close(cx);
    vertices_a.close(cx);
    vertices_b.close(cx);
  }
};

void GeometryTables::append(const h5::Context& cx, std::span<const CaseResult> results) {
  std::vector<schema::GeometryRow> rows;
  std::vector<schema::VertexRow> a, b;
  for (const CaseResult& r : results) {
    if (!r.geometry) continue;
    rows.push_back({r.record.case_id, vertices_a.rows() + a.size(), r.geometry->a.size(),
                    vertices_b.rows() + b.size(), r.geometry->b.size()});
    for (const Vec3& v : r.geometry->a)
      a.push_back({v});
    for (const Vec3& v : r.geometry->b)
      b.push_back({v});
  }
  index.append(cx, rows);
  vertices_a.append(cx, a);
  vertices_b.append(cx, b);
}

/// /meshes: what non-convex pairs add (archives of nonconvex families only): the truth's and
/// each algorithm's rows beside /exact's and /algorithms', and the faces and pieces of the
/// cases /geometry keeps.
struct MeshTables {
  std::optional<ColumnTable<MeshExactRecord>> exact;
  std::vector<ColumnTable<MeshAlgorithmRecord>> algorithms;
  ColumnTable<schema::MeshGeometryRow> index;
  ColumnTable<schema::FaceRow> faces_a, faces_b;
  ColumnTable<schema::PieceRow> pieces;
  ColumnTable<schema::VertexRow> corners;

  void append(const h5::Context& cx, std::span<const CaseResult> results);
  void append_geometry(const h5::Context& cx, std::span<const CaseResult> results);
  void close(const h5::Context& cx) {
    if (exact) exact->close(cx);
    for (auto& a : algorithms)
      a.close(cx);
    index.close(cx);
    faces_a.close(cx);
    faces_b.close(cx);
    pieces.close(cx);
    corners.close(cx);
  }
};

void MeshTables::append(const h5::Context& cx, std::span<const CaseResult> results) {
  std::vector<const MeshExactRecord*> truth;
  std::vector<std::vector<const MeshAlgorithmRecord*>> answers(algorithms.size());
  for (const CaseResult& r : results) {
    if (exact) truth.push_back(&*r.mesh->exact);
    for (std::size_t k = 0; k < algorithms.size(); ++k)
      answers[k].push_back(&r.mesh->algorithms[k]);
  }
  if (exact) exact->append(cx, truth);
  for (std::size_t k = 0; k < algorithms.size(); ++k)
    algorithms[k].append(cx, answers[k]);
  append_geometry(cx, results);
}

void MeshTables::append_geometry(const h5::Context& cx, std::span<const CaseResult> results) {
  std::vector<schema::MeshGeometryRow> rows;
  std::vector<schema::FaceRow> fa, fb;
  std::vector<schema::PieceRow> ps;
  std::vector<schema::VertexRow> cs;
  for (const CaseResult& r : results) {
    if (!r.geometry) continue;
    const CaseGeometry& g = *r.geometry;
    rows.push_back({r.record.case_id, faces_a.rows() + fa.size(), g.faces_a.size(),
                    faces_b.rows() + fb.size(), g.faces_b.size(), pieces.rows() + ps.size(),
                    g.pieces.size()});
    for (const auto& f : g.faces_a)
      fa.push_back({f});
    for (const auto& f : g.faces_b)
      fb.push_back({f});
    for (const KeptPiece& piece : g.pieces) {
      ps.push_back({piece.decomposition, piece.side, corners.rows() + cs.size(),
                    piece.corners.size()});
      for (const Vec3& c : piece.corners)
        cs.push_back({c});
    }
  }
  index.append(cx, rows);
  faces_a.append(cx, fa);
  faces_b.append(cx, fb);
  pieces.append(cx, ps);
  corners.append(cx, cs);
}

/// The rows of one algorithm's traces in a batch of results.
std::vector<schema::TraceRow> trace_rows(std::span<const CaseResult> results,
                                         std::size_t algorithm) {
  std::vector<schema::TraceRow> rows;
  for (const CaseResult& r : results) {
    if (algorithm >= r.traces.size()) continue;
    for (const GjkIterationTrace& t : r.traces[algorithm])
      rows.push_back(schema::flatten(r.record.case_id, t));
  }
  return rows;
}

/// The records of one group in a batch of results.
template <class R, class F>
std::vector<const R*> records(std::span<const CaseResult> results, F record) {
  std::vector<const R*> rows;
  rows.reserve(results.size());
  for (const CaseResult& r : results)
    rows.push_back(&record(r));
  return rows;
}

}  // namespace

// ---- writer ----

struct ArchiveWriter::Impl {
  struct Columns {
    std::optional<ColumnTable<CaseRecord>> cases;
    std::optional<ColumnTable<ExactRecord>> exact;
    std::vector<ColumnTable<AlgorithmRecord>> algorithms;
    std::optional<GeometryTables> geometry;
    std::vector<ColumnTable<schema::TraceRow>> traces;  ///< per algorithm, when traces are kept
    std::optional<MeshTables> meshes;                    ///< nonconvex families only

    /// Closes every dataset, reporting the first that fails to close.
    void close(const h5::Context& cx) {
      cases->close(cx);
      if (exact) exact->close(cx);
      for (auto& a : algorithms)
        a.close(cx);
      geometry->close(cx);
      for (auto& t : traces)
        t.close(cx);
      if (meshes) meshes->close(cx);
    }
  };

  fs::path final_path;
  fs::path temp_path;
  bool overwrite = false;
  bool oracle = true;
  bool meshes = false;
  std::size_t algorithm_count = 0;
  h5::Context cx;
  // Declaration order matters: the file is closed after everything opened in it.
  h5::Handle file;
  h5::Handle root;
  std::optional<schema::Types> types;
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
        meshes(h.meshes),
        algorithm_count(h.algorithm_names.size()),
        cx(temp_path.string()) {}

  void create(const ArchiveHeader& h);
  void create_file();
  void write_root_attributes(const ArchiveHeader& h);
  Columns create_columns(const ArchiveHeader& h);
  MeshTables create_mesh_tables(const ArchiveHeader& h, hsize_t chunk);
  void write(std::span<const CaseResult> results);

  /// Records how many rows every group holds, flushes the file and snapshots it: an
  /// interrupted run can be read back (and resumed) up to the last checkpoint, or from the
  /// snapshot when a kill cut a later write short.
  void checkpoint() {
    const hid_t r = root.get();
    const Columns& c = *columns;
    const auto count = [&](std::string_view attribute, hsize_t rows) {
      h5::write_attr_u64(cx, r, "/", std::string(attribute), rows);
    };
    count(schema::checkpoint::cases, c.cases->rows());
    count(schema::checkpoint::geometry, c.geometry->index.rows());
    count(schema::checkpoint::vertices_a, c.geometry->vertices_a.rows());
    count(schema::checkpoint::vertices_b, c.geometry->vertices_b.rows());
    for (std::size_t k = 0; k < c.traces.size(); ++k)
      count(schema::checkpoint::traces(k), c.traces[k].rows());
    if (c.meshes) {
      count(schema::checkpoint::mesh_geometry, c.meshes->index.rows());
      count(schema::checkpoint::mesh_faces_a, c.meshes->faces_a.rows());
      count(schema::checkpoint::mesh_faces_b, c.meshes->faces_b.rows());
      count(schema::checkpoint::mesh_pieces, c.meshes->pieces.rows());
      count(schema::checkpoint::mesh_piece_corners, c.meshes->corners.rows());
    }
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
  create_file();
  write_root_attributes(h);
  types.emplace(cx);
  columns = create_columns(h);
}

void ArchiveWriter::Impl::create_file() {
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
}

void ArchiveWriter::Impl::write_root_attributes(const ArchiveHeader& h) {
  const hid_t r = root.get();
  h5::write_attr_i32(cx, r, "/", std::string(schema::attribute::schema_version),
                     kArchiveSchemaVersion);
  for (const auto& [key, value] : h.provenance)
    h5::write_attr_string(cx, r, "/", key, value);
  schema::write_header_attributes(cx, r, h);
}

ArchiveWriter::Impl::Columns ArchiveWriter::Impl::create_columns(const ArchiveHeader& h) {
  const schema::Types& t = *types;
  const hid_t r = root.get();
  const hsize_t chunk = case_chunk_rows(h.cases_planned);
  Columns c;
  {
    h5::Handle g = h5::create_group(cx, r, "/", "cases");
    c.cases.emplace(cx, t, g.get(), "/cases", schema::kCaseColumns, chunk);
  }
  if (h.oracle) {
    h5::Handle g = h5::create_group(cx, r, "/", "exact");
    c.exact.emplace(cx, t, g.get(), "/exact", schema::kExactColumns, chunk);
  }
  {
    h5::Handle all = h5::create_group(cx, r, "/", "algorithms");
    for (std::size_t i = 0; i < h.algorithm_names.size(); ++i) {
      const std::string& name = h.algorithm_names[i];
      const std::string p = "/algorithms/" + name;
      h5::Handle g = h5::create_group(cx, all.get(), "/algorithms", name);
      if (i < h.algorithm_options.size())
        for (const auto& [key, value] : h.algorithm_options[i])
          h5::write_attr_string(cx, g.get(), p, key, value);
      c.algorithms.emplace_back(cx, t, g.get(), p, schema::kAlgorithmColumns, chunk);
    }
  }
  {
    h5::Handle g = h5::create_group(cx, r, "/", "geometry");
    const std::string p = "/geometry";
    c.geometry.emplace(
        GeometryTables{{cx, t, g.get(), p, schema::kGeometryColumns, chunk},
                       {cx, t, g.get(), p, schema::kVerticesAColumns, kVertexChunkRows},
                       {cx, t, g.get(), p, schema::kVerticesBColumns, kVertexChunkRows}});
  }
  if (h.meshes) c.meshes.emplace(create_mesh_tables(h, chunk));
  if (h.trace_mode != TraceMode::none) {
    h5::Handle all = h5::create_group(cx, r, "/", "traces");
    for (const std::string& name : h.algorithm_names) {
      h5::Handle g = h5::create_group(cx, all.get(), "/traces", name);
      c.traces.emplace_back(cx, t, g.get(), "/traces/" + name, schema::kTraceColumns,
                            kVertexChunkRows);
    }
  }
  return c;
}

MeshTables ArchiveWriter::Impl::create_mesh_tables(const ArchiveHeader& h, hsize_t chunk) {
  const schema::Types& t = *types;
  h5::Handle m = h5::create_group(cx, root.get(), "/", "meshes");
  const std::string p = "/meshes";
  MeshTables tables{
      std::nullopt,
      {},
      {cx, t, m.get(), p, schema::kMeshGeometryColumns, chunk},
      {cx, t, m.get(), p, schema::kFacesAColumns, kVertexChunkRows},
      {cx, t, m.get(), p, schema::kFacesBColumns, kVertexChunkRows},
      {cx, t, m.get(), p, schema::kPieceColumns, kVertexChunkRows},
      {cx, t, m.get(), p, schema::kPieceCornerColumns, kVertexChunkRows},
  };
  if (h.oracle) {
    h5::Handle g = h5::create_group(cx, m.get(), p, "exact");
    tables.exact.emplace(cx, t, g.get(), p + "/exact", schema::kMeshExactColumns, chunk);
  }
  h5::Handle all = h5::create_group(cx, m.get(), p, "algorithms");
  for (const std::string& name : h.algorithm_names) {
    h5::Handle g = h5::create_group(cx, all.get(), p + "/algorithms", name);
    tables.algorithms.emplace_back(cx, t, g.get(), p + "/algorithms/" + name,
                                   schema::kMeshAlgorithmColumns, chunk);
  }
  return tables;
}

void ArchiveWriter::Impl::write(std::span<const CaseResult> rs) {
  using R = const CaseResult&;
  Columns& c = *columns;
  c.cases->append(cx, records<CaseRecord>(
                          rs, [](R r) -> auto& { return r.record; }));
  if (c.exact)
    c.exact->append(cx, records<ExactRecord>(
                            rs, [](R r) -> auto& { return *r.exact; }));
  for (std::size_t i = 0; i < c.algorithms.size(); ++i)
    c.algorithms[i].append(cx, records<AlgorithmRecord>(
                                   rs, [i](R r) -> auto& { return r.algorithms[i]; }));
  c.geometry->append(cx, rs);
  for (std::size_t k = 0; k < c.traces.size(); ++k)
    c.traces[k].append(cx, trace_rows(rs, k));
  if (c.meshes) c.meshes->append(cx, rs);
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
    if (r.mesh.has_value() != w.meshes)
      w.cx.error(id() + (w.meshes ? " is not a non-convex pair, and the archive's are"
                                  : " is a non-convex pair, and the archive's are not"));
    if (r.mesh && (r.mesh->algorithms.size() != w.algorithm_count ||
                   r.mesh->exact.has_value() != w.oracle))
      w.cx.error(id() + "'s non-convex records do not match its algorithms and oracle");
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
  h5::write_attr_string(w.cx, w.root.get(), "/", std::string(schema::attribute::end_time),
                        end_time);
  w.columns->close(w.cx);
  w.columns.reset();
  w.cx.check(H5Fflush(w.root.get(), H5F_SCOPE_GLOBAL), "cannot flush the file");
  // The completion flag comes last, after everything else is in the file.
  h5::write_attr_u8(w.cx, w.root.get(), "/", std::string(schema::attribute::complete),
                    whole ? 1 : 0);
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
}  // namespace gjklab::experiment
