// The HDF5 results archive's reader. The columns of every group come from the schema tables
// (archive_schema.hpp); results/README.md documents them.

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <span>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <unordered_map>

#include "archive_schema.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "hdf5_util.hpp"

namespace gjklab::experiment {

namespace fs = std::filesystem;

namespace {

/// The open file and what every group reader needs.
struct Reader {
  const h5::Context& cx;
  hid_t root;
  const schema::Types& types;
  bool complete;

  /// Rows of a group up to the last checkpoint: an incomplete run is read up to it, and rows
  /// written after it (a write cut off by a kill) are ignored. any_rows when complete.
  hsize_t committed(std::string_view attribute) const {
    const std::string name(attribute);
    return !complete && h5::has_attr(cx, root, "/", name) ? h5::read_attr_u64(cx, root, "/", name)
                                                          : h5::any_rows;
  }
};

template <class R, class T>
void read_field(const Reader& in, hid_t group, const std::string& path, const std::string& name,
                T R::*member, std::span<R* const> rows) {
  using S = schema::Storage<T>;
  if constexpr (std::is_same_v<T, std::string>) {
    auto values = h5::read_string_column(in.cx, group, path, name, rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      rows[i]->*member = std::move(values[i]);
  } else {
    const auto values = h5::read_column<typename S::Element>(
        in.cx, group, path, name, S::memory(in.types), rows.size(), S::width);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      rows[i]->*member = S::get(values, i);
      // libhdf5 turns a stored value that no member of the file's enum type names into all
      // ones (255), which would index past every table of the enum's values.
      if constexpr (std::is_enum_v<T>)
        if (to_string(rows[i]->*member) == "unknown")
          in.cx.error(path + "/" + name + " row " + std::to_string(i) +
                      " holds a value outside its enum");
    }
  }
}

/// Fills one member of every row per column of the table. An optional column the file lacks
/// leaves the rows' default values.
template <class R, std::size_t N>
void read_columns(const Reader& in, hid_t group, const std::string& path,
                  const std::array<schema::ColumnSpec<R>, N>& specs, std::span<R* const> rows) {
  for (const auto& spec : specs) {
    const std::string name(spec.name);
    if (spec.presence == schema::Presence::optional && !h5::has_link(in.cx, group, path, name))
      continue;
    std::visit([&](auto member) { read_field(in, group, path, name, member, rows); }, spec.field);
  }
}

/// The rows the table's first column holds, up to `committed`: the table's length.
template <class R, std::size_t N>
std::size_t count_rows(const Reader& in, hid_t group, const std::string& path,
                       const std::array<schema::ColumnSpec<R>, N>& specs, hsize_t committed) {
  return std::visit(
      [&](auto member) {
        using S = schema::Storage<typename schema::MemberType<decltype(member)>::type>;
        return static_cast<std::size_t>(h5::open_dataset(in.cx, group, path,
                                                         std::string(specs.front().name),
                                                         S::memory(in.types), S::width, committed)
                                            .rows);
      },
      specs.front().field);
}

/// A whole table read into rows of its own type (the geometry and trace groups).
template <class R, std::size_t N>
std::vector<R> read_table(const Reader& in, hid_t group, const std::string& path,
                          const std::array<schema::ColumnSpec<R>, N>& specs, hsize_t committed) {
  std::vector<R> rows(count_rows(in, group, path, specs, committed));
  std::vector<R*> pointers;
  pointers.reserve(rows.size());
  for (R& row : rows)
    pointers.push_back(&row);
  read_columns(in, group, path, specs, std::span<R* const>(pointers));
  return rows;
}

/// Pointers to one record of every result (the rows of a group whose records the results hold).
template <class R, class F>
std::vector<R*> records(std::vector<CaseResult>& results, F record) {
  std::vector<R*> rows;
  rows.reserve(results.size());
  for (CaseResult& r : results)
    rows.push_back(&record(r));
  return rows;
}

/// Case ids to positions in a.results.
std::unordered_map<std::uint64_t, std::size_t> case_index(const Archive& a) {
  std::unordered_map<std::uint64_t, std::size_t> index;
  index.reserve(a.results.size());
  for (std::size_t i = 0; i < a.results.size(); ++i)
    index.emplace(a.results[i].record.case_id, i);
  return index;
}

/// The position of a row's case in a.results; an error naming the column when it is not there.
std::size_t find_case(const Reader& in, const std::unordered_map<std::uint64_t, std::size_t>& index,
                      const std::string& path, std::uint64_t case_id) {
  const auto it = index.find(case_id);
  if (it == index.end())
    in.cx.error(path + "/case_id " + std::to_string(case_id) + " is not in /cases/case_id");
  return it->second;
}

void read_header(const Reader& in, Archive& a) {
  const h5::Context& cx = in.cx;
  const hid_t r = in.root;
  ArchiveHeader& h = a.header;
  schema::read_header_attributes(cx, r, h);
  // A run that stopped before finish() has neither: it is incomplete.
  const std::string end_time(schema::attribute::end_time);
  const std::string complete(schema::attribute::complete);
  if (h5::has_attr(cx, r, "/", end_time)) a.end_time = h5::read_attr_string(cx, r, "/", end_time);
  if (h5::has_attr(cx, r, "/", complete)) a.complete = h5::read_attr_u8(cx, r, "/", complete) != 0;
  for (const std::string& key : h5::attr_names(cx, r, "/")) {
    if (is_root_attribute(key)) continue;
    if (h5::attr_class(cx, r, "/", key) != H5T_STRING)
      cx.error("attribute '" + key + "' of / is not a string");
    h.provenance.emplace_back(key, h5::read_attr_string(cx, r, "/", key));
  }
}

/// /cases: sizes a.results.
void read_cases(const Reader& in, Archive& a) {
  const h5::Handle g = h5::open_group(in.cx, in.root, "/", "cases");
  const auto& specs = schema::kCaseColumns;
  a.results.resize(
      count_rows(in, g.get(), "/cases", specs, in.committed(schema::checkpoint::cases)));
  const auto rows = records<CaseRecord>(
      a.results, [](CaseResult & r) -> auto& { return r.record; });
  read_columns(in, g.get(), "/cases", specs, std::span<CaseRecord* const>(rows));
}

void read_exact(const Reader& in, Archive& a) {
  const h5::Handle g = h5::open_group(in.cx, in.root, "/", "exact");
  const auto rows = records<ExactRecord>(
      a.results, [](CaseResult & r) -> auto& { return r.exact.emplace(); });
  read_columns(in, g.get(), "/exact", schema::kExactColumns, std::span<ExactRecord* const>(rows));
}

/// /algorithms/<name>: each algorithm's options (its group's attributes) and records.
void read_algorithms(const Reader& in, Archive& a) {
  const h5::Context& cx = in.cx;
  ArchiveHeader& h = a.header;
  const h5::Handle all = h5::open_group(cx, in.root, "/", "algorithms");
  for (CaseResult& res : a.results)
    res.algorithms.resize(h.algorithm_names.size());
  for (std::size_t k = 0; k < h.algorithm_names.size(); ++k) {
    const std::string& name = h.algorithm_names[k];
    const std::string p = "/algorithms/" + name;
    const h5::Handle g = h5::open_group(cx, all.get(), "/algorithms", name);
    auto& options = h.algorithm_options.emplace_back();
    for (const std::string& key : h5::attr_names(cx, g.get(), p)) {
      if (h5::attr_class(cx, g.get(), p, key) != H5T_STRING)
        cx.error("attribute '" + key + "' of " + p + " is not a string");
      options.emplace_back(key, h5::read_attr_string(cx, g.get(), p, key));
    }
    const auto rows = records<AlgorithmRecord>(
        a.results, [k](CaseResult & r) -> auto& { return r.algorithms[k]; });
    read_columns(in, g.get(), p, schema::kAlgorithmColumns,
                 std::span<AlgorithmRecord* const>(rows));
  }
}

/// Rows [offset, offset + count) of a vertex dataset, checked against its length.
std::vector<Vec3> slice(const Reader& in, const std::vector<schema::VertexRow>& v,
                        std::uint64_t offset, std::uint64_t count, const std::string& what) {
  const std::uint64_t rows = v.size();
  if (count > rows || offset > rows - count)
    in.cx.error("/geometry/" + what + " rows [" + std::to_string(offset) + ", " +
                std::to_string(offset + count) + ") lie outside its " + std::to_string(rows) +
                " rows");
  std::vector<Vec3> out;
  out.reserve(count);
  for (std::uint64_t j = offset; j < offset + count; ++j)
    out.push_back(v[j].point);
  return out;
}

/// /geometry: the clouds of the cases that kept them.
void read_geometry(const Reader& in, Archive& a) {
  const std::string p = "/geometry";
  const h5::Handle g = h5::open_group(in.cx, in.root, "/", "geometry");
  const auto index_rows = read_table(in, g.get(), p, schema::kGeometryColumns,
                                     in.committed(schema::checkpoint::geometry));
  const auto va = read_table(in, g.get(), p, schema::kVerticesAColumns,
                             in.committed(schema::checkpoint::vertices_a));
  const auto vb = read_table(in, g.get(), p, schema::kVerticesBColumns,
                             in.committed(schema::checkpoint::vertices_b));
  const auto index = case_index(a);
  for (const schema::GeometryRow& row : index_rows) {
    CaseGeometry& geo = a.results[find_case(in, index, p, row.case_id)].geometry.emplace();
    geo.a = slice(in, va, row.a_offset, row.a_count, "vertices_a");
    geo.b = slice(in, vb, row.b_offset, row.b_count, "vertices_b");
  }
}

/// Rows [offset, offset + count) of a /meshes table, checked against its length.
template <class T>
std::span<const T> rows_of(const Reader& in, const std::vector<T>& v, std::uint64_t offset,
                           std::uint64_t count, const std::string& what) {
  if (count > v.size() || offset > v.size() - count)
    in.cx.error("/meshes/" + what + " rows [" + std::to_string(offset) + ", " +
                std::to_string(offset + count) + ") lie outside its " + std::to_string(v.size()) +
                " rows");
  return std::span<const T>(v).subspan(offset, count);
}

/// /meshes/geometry: the faces and pieces of the kept non-convex cases (whose vertices
/// /geometry holds).
void read_mesh_geometry(const Reader& in, hid_t m, Archive& a) {
  const std::string p = "/meshes";
  const auto index_rows = read_table(in, m, p, schema::kMeshGeometryColumns,
                                     in.committed(schema::checkpoint::mesh_geometry));
  const auto fa =
      read_table(in, m, p, schema::kFacesAColumns, in.committed(schema::checkpoint::mesh_faces_a));
  const auto fb =
      read_table(in, m, p, schema::kFacesBColumns, in.committed(schema::checkpoint::mesh_faces_b));
  const auto pieces =
      read_table(in, m, p, schema::kPieceColumns, in.committed(schema::checkpoint::mesh_pieces));
  const auto corners = read_table(in, m, p, schema::kPieceCornerColumns,
                                  in.committed(schema::checkpoint::mesh_piece_corners));
  const auto index = case_index(a);
  for (const schema::MeshGeometryRow& row : index_rows) {
    CaseResult& r = a.results[find_case(in, index, p + "/case_id", row.case_id)];
    if (!r.geometry)
      in.cx.error(p + "/case_id " + std::to_string(row.case_id) + " has no /geometry row");
    for (const schema::FaceRow& f :
         rows_of(in, fa, row.faces_a_offset, row.faces_a_count, "faces_a"))
      r.geometry->faces_a.push_back(f.face);
    for (const schema::FaceRow& f :
         rows_of(in, fb, row.faces_b_offset, row.faces_b_count, "faces_b"))
      r.geometry->faces_b.push_back(f.face);
    for (const schema::PieceRow& piece :
         rows_of(in, pieces, row.pieces_offset, row.pieces_count, "pieces")) {
      KeptPiece& kept = r.geometry->pieces.emplace_back();
      kept.decomposition = piece.decomposition;
      kept.side = piece.side;
      for (const schema::VertexRow& c :
           rows_of(in, corners, piece.corners_offset, piece.corners_count, "piece_corners"))
        kept.corners.push_back(c.point);
    }
  }
}

/// /meshes: the non-convex records beside /exact's and /algorithms', and the kept geometry.
void read_meshes(const Reader& in, Archive& a) {
  if (!h5::has_link(in.cx, in.root, "/", "meshes")) return;
  a.header.meshes = true;
  const h5::Handle m = h5::open_group(in.cx, in.root, "/", "meshes");
  const auto& names = a.header.algorithm_names;
  for (CaseResult& r : a.results)
    r.mesh.emplace().algorithms.resize(names.size());
  if (a.header.oracle) {
    const h5::Handle g = h5::open_group(in.cx, m.get(), "/meshes", "exact");
    const auto rows = records<MeshExactRecord>(
        a.results, [](CaseResult & r) -> auto& { return r.mesh->exact.emplace(); });
    read_columns(in, g.get(), "/meshes/exact", schema::kMeshExactColumns,
                 std::span<MeshExactRecord* const>(rows));
  }
  const h5::Handle all = h5::open_group(in.cx, m.get(), "/meshes", "algorithms");
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string p = "/meshes/algorithms/" + names[k];
    const h5::Handle g = h5::open_group(in.cx, all.get(), "/meshes/algorithms", names[k]);
    const auto rows = records<MeshAlgorithmRecord>(
        a.results, [k](CaseResult & r) -> auto& { return r.mesh->algorithms[k]; });
    read_columns(in, g.get(), p, schema::kMeshAlgorithmColumns,
                 std::span<MeshAlgorithmRecord* const>(rows));
  }
  read_mesh_geometry(in, m.get(), a);
}

/// /traces/<algorithm>: each case's traces.
void read_traces(const Reader& in, Archive& a) {
  const auto& names = a.header.algorithm_names;
  for (CaseResult& r : a.results)
    r.traces.assign(names.size(), {});
  const auto index = case_index(a);
  const h5::Handle all = h5::open_group(in.cx, in.root, "/", "traces");
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string p = "/traces/" + names[k];
    const h5::Handle g = h5::open_group(in.cx, all.get(), "/traces", names[k]);
    const auto rows = read_table(in, g.get(), p, schema::kTraceColumns,
                                 in.committed(schema::checkpoint::traces(k)));
    for (const schema::TraceRow& row : rows) {
      const std::size_t i = find_case(in, index, p, row.case_id);
      if (row.simplex_size < 0 || row.simplex_size > Simplex::kCapacity)
        in.cx.error(p + "/simplex_size " + std::to_string(row.simplex_size) + " is out of range");
      a.results[i].traces[k].push_back(schema::unflatten(row));
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

  Archive a;
  a.schema_version =
      h5::read_attr_i32(cx, root.get(), "/", std::string(schema::attribute::schema_version));
  if (a.schema_version != kArchiveSchemaVersion)
    cx.error("schema_version " + std::to_string(a.schema_version) + " is not supported (expected " +
             std::to_string(kArchiveSchemaVersion) + ")");
  const schema::Types types(cx);
  Reader in{cx, root.get(), types, false};
  read_header(in, a);
  in.complete = a.complete;
  cx.allow_prefix_reads(!a.complete);
  read_cases(in, a);
  if (a.header.oracle) read_exact(in, a);
  read_algorithms(in, a);
  read_geometry(in, a);
  if (a.header.trace_mode != TraceMode::none) read_traces(in, a);
  read_meshes(in, a);
  return a;
}

namespace {

/// How long the isolated read of an archive may take, in seconds: 60, or one per 10 MB of file
/// if that is more (reads run at hundreds of MB/s; libhdf5 loops forever on some corrupt
/// global heaps). GJKLAB_ARCHIVE_READ_SECONDS overrides it (a positive number).
double read_time_limit(const fs::path& path) {
  if (const char* text = std::getenv("GJKLAB_ARCHIVE_READ_SECONDS")) {
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (end != text && *end == '\0' && seconds > 0 && seconds < 1e7) return seconds;
  }
  std::error_code ec;
  const auto bytes = fs::file_size(path, ec);
  return std::max(60.0, ec ? 0.0 : static_cast<double>(bytes) / 1e7);
}

/// The time limit as written in messages: "60", "0.5" (at most 3 significant digits).
std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", seconds);
  return text;
}

/// Reads the child's message until it closes the pipe; false if the time limit passed first.
bool read_until_closed(int fd, double seconds, std::string& message) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  char buffer[4096];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) return true;  // cannot wait: let waitpid decide
    if (ready <= 0) continue;
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n <= 0) return true;  // closed: the child has finished (or is finishing)
    message.append(buffer, static_cast<std::size_t>(n));
  }
}

/// Reads the archive in a forked child; throws ArchiveError if the child failed, crashed or
/// did not finish within the time limit (then it is killed).
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
  const double limit = read_time_limit(path);
  const bool finished = read_until_closed(pipe_fds[0], limit, message);
  ::close(pipe_fds[0]);
  if (!finished) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (!finished)
    throw ArchiveError(path.string() + ": corrupt: reading it did not finish within " +
                       seconds_text(limit) +
                       " s (the HDF5 library loops on it); the file cannot be used "
                       "(GJKLAB_ARCHIVE_READ_SECONDS sets the limit)");
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
