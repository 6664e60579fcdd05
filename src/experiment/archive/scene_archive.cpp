// The scene archive's writer and reader: both walk the tables of scene_schema.hpp.
#include "gjklab/experiment/archive/scene_archive.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <filesystem>
#include <system_error>
#include <type_traits>

#include "experiment/archive/hdf5_util.hpp"
#include "experiment/archive/scene_schema.hpp"

namespace gjklab::experiment {

namespace {

constexpr const char* kFormat = "gjklab-scene";

template <class T>
hid_t memory_type() {
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  if constexpr (std::is_same_v<T, std::int64_t>) return H5T_NATIVE_INT64;
  if constexpr (std::is_same_v<T, std::uint32_t>) return H5T_NATIVE_UINT32;
  if constexpr (std::is_same_v<T, std::int32_t>) return H5T_NATIVE_INT32;
  if constexpr (std::is_same_v<T, std::uint8_t>) return H5T_NATIVE_UINT8;
}

/// One open group and its path, for the h5 helpers' messages.
struct Group {
  h5::Handle handle;
  std::string path;
  hid_t get() const { return handle.get(); }
};

Group create_group(const h5::Context& cx, hid_t file, const std::string& name) {
  return {h5::create_group(cx, file, "/", name), "/" + name};
}

// ---- writing ----

/// Chunks of at most this many rows: whole runs are written at once, read back whole.
constexpr hsize_t kChunkRows = 16384;

template <class T>
void write_values(const h5::Context& cx, const Group& g, std::string_view name,
                  const std::vector<T>& values, hsize_t width) {
  const hsize_t rows = values.size() / width;
  const std::string n(name);
  if constexpr (std::is_same_v<T, std::string>) {
    h5::Handle type = h5::string_type(cx);
    h5::Column column(cx, g.get(), g.path, n, type.get(), type.get(), 1,
                      std::min(rows, kChunkRows));
    std::vector<const char*> pointers;
    for (const std::string& s : values)
      pointers.push_back(s.c_str());
    if (rows > 0) column.append(cx, pointers.data(), rows);
    cx.check(column.close(), "cannot close dataset " + g.path + "/" + n);
  } else {
    h5::Column column(cx, g.get(), g.path, n, memory_type<T>(), memory_type<T>(), width,
                      std::min(rows, kChunkRows));
    if (rows > 0) column.append(cx, values.data(), rows);
    cx.check(column.close(), "cannot close dataset " + g.path + "/" + n);
  }
}

template <class R, std::size_t N>
void write_table(const h5::Context& cx, const Group& g, const scene_schema::Table<R, N>& table,
                 const R& rows) {
  for (const auto& column : table.columns)
    std::visit(
        [&](auto member) {
          const auto& values = rows.*member;
          if (column.presence == scene_schema::Presence::when_recorded && values.empty()) return;
          write_values(cx, g, column.name, values, column.width);
        },
        column.field);
}

template <class Owner, class Spec>
void write_attribute(const h5::Context& cx, hid_t obj, const std::string& path, const Owner& owner,
                     const Spec& spec) {
  const std::string name(spec.name);
  std::visit(
      [&](auto member) {
        const auto& value = owner.*member;
        using V = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<V, std::string>)
          h5::write_attr_string(cx, obj, path, name, value);
        else if constexpr (std::is_same_v<V, bool>)
          h5::write_attr_u8(cx, obj, path, name, value ? 1 : 0);
        else if constexpr (std::is_same_v<V, double>)
          h5::write_attr_f64(cx, obj, path, name, value);
        else
          h5::write_attr_u64(cx, obj, path, name, value);
      },
      spec.field);
}

void write_state(const h5::Context& cx, hid_t file, const SceneState& state) {
  const Group g = create_group(cx, file, "state");
  write_table(cx, g, scene_schema::kBodyState, state.bodies);
  write_table(cx, g, scene_schema::kPairState, state.pairs);
  write_table(cx, g, scene_schema::kSimplexState, state.simplex);
  write_table(cx, g, scene_schema::kPointState, state.points);
  for (const auto& spec : scene_schema::kStateAttributes)
    write_attribute(cx, g.get(), g.path, state, spec);
}

void write_groups(const h5::Context& cx, hid_t file, const SceneArchive& a) {
  write_table(cx, create_group(cx, file, "frames"), scene_schema::kFrames, a.frames);
  {
    const Group bodies = create_group(cx, file, "bodies");
    write_table(cx, bodies, scene_schema::kBodies, a.bodies);
    write_table(cx, bodies, scene_schema::kPoses, a.poses);
  }
  write_table(cx, create_group(cx, file, "contacts"), scene_schema::kContacts, a.contacts);
  if (a.header.audit_every > 0)
    write_table(cx, create_group(cx, file, "audit"), scene_schema::kAudit, a.audit);
  if (a.header.queries_every > 0) {
    write_table(cx, create_group(cx, file, "queries"), scene_schema::kQueries, a.queries);
    write_table(cx, create_group(cx, file, "shapes"), scene_schema::kShapes, a.shapes);
  }
  if (a.state) write_state(cx, file, *a.state);
}

void write_file(const h5::Context& cx, const std::string& file_path, const SceneArchive& a) {
  h5::Handle fcpl =
      cx.handle(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "cannot create file properties");
  cx.check(H5Pset_attr_creation_order(fcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
           "cannot track the attribute order of /");
  h5::Handle file = cx.handle(H5Fcreate(file_path.c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT),
                              H5Fclose, "cannot create " + file_path);
  h5::write_attr_string(cx, file.get(), "/", "format", kFormat);
  h5::write_attr_u64(cx, file.get(), "/", "schema_version", kSceneSchemaVersion);
  for (const auto& [key, value] : a.provenance)
    h5::write_attr_string(cx, file.get(), "/", key, value);
  for (const auto& spec : scene_schema::kRoot)
    write_attribute(cx, file.get(), "/", a.header, spec);
  write_groups(cx, file.get(), a);
  // `complete` last: a reader that sees complete = 1 sees every dataset.
  for (const auto& spec : scene_schema::kRootLast)
    write_attribute(cx, file.get(), "/", a.header, spec);
  cx.check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "cannot flush " + file_path);
  cx.check(file.close(), "cannot close " + file_path);
}

// ---- reading ----

bool is_root_attribute(std::string_view name) {
  if (name == "format" || name == "schema_version") return true;
  for (const auto& spec : scene_schema::kRoot)
    if (spec.name == name) return true;
  for (const auto& spec : scene_schema::kRootLast)
    if (spec.name == name) return true;
  return false;
}

template <class Owner, class Spec>
void read_attribute(const h5::Context& cx, hid_t obj, const std::string& path, Owner& owner,
                    const Spec& spec) {
  const std::string name(spec.name);
  std::visit(
      [&](auto member) {
        auto& value = owner.*member;
        using V = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<V, std::string>)
          value = h5::read_attr_string(cx, obj, path, name);
        else if constexpr (std::is_same_v<V, bool>)
          value = h5::read_attr_u8(cx, obj, path, name) != 0;
        else if constexpr (std::is_same_v<V, double>)
          value = h5::read_attr_f64(cx, obj, path, name);
        else
          value = h5::read_attr_u64(cx, obj, path, name);
      },
      spec.field);
}

template <class T>
std::vector<T> read_values(const h5::Context& cx, const Group& g, const std::string& name,
                           hsize_t width) {
  if constexpr (std::is_same_v<T, std::string>)
    return h5::read_string_column(cx, g.get(), g.path, name, h5::any_rows);
  else
    return h5::read_column<T>(cx, g.get(), g.path, name, memory_type<T>(), h5::any_rows, width);
}

/// Reads the table's columns (a when_recorded column only when present) and checks that a
/// uniform table's columns have one row count.
template <class R, std::size_t N>
void read_table(const h5::Context& cx, const Group& g, const scene_schema::Table<R, N>& table,
                R& rows) {
  std::optional<std::size_t> count;
  for (const auto& column : table.columns) {
    const std::string name(column.name);
    if (column.presence == scene_schema::Presence::when_recorded &&
        !h5::has_link(cx, g.get(), g.path, name))
      continue;
    std::visit(
        [&](auto member) {
          auto& values = rows.*member;
          using T = typename std::decay_t<decltype(values)>::value_type;
          values = read_values<T>(cx, g, name, column.width);
          const std::size_t n = values.size() / column.width;
          if (!table.uniform_rows) return;
          if (count && *count != n)
            cx.error("dataset " + g.path + "/" + name + " has " + std::to_string(n) +
                     " rows where the group's other columns have " + std::to_string(*count));
          count = n;
        },
        column.field);
  }
}

Group open_group(const h5::Context& cx, hid_t file, const std::string& name) {
  return {h5::open_group(cx, file, "/", name), "/" + name};
}

SceneState read_state(const h5::Context& cx, hid_t file) {
  SceneState state;
  const Group g = open_group(cx, file, "state");
  read_table(cx, g, scene_schema::kBodyState, state.bodies);
  read_table(cx, g, scene_schema::kPairState, state.pairs);
  read_table(cx, g, scene_schema::kSimplexState, state.simplex);
  read_table(cx, g, scene_schema::kPointState, state.points);
  for (const auto& spec : scene_schema::kStateAttributes)
    read_attribute(cx, g.get(), g.path, state, spec);
  return state;
}

void read_header(const h5::Context& cx, hid_t file, SceneArchive& a) {
  if (!h5::has_attr(cx, file, "/", "format") ||
      h5::attr_class(cx, file, "/", "format") != H5T_STRING ||
      h5::read_attr_string(cx, file, "/", "format") != kFormat)
    cx.error("not a scene archive (its root attribute format is not \"gjklab-scene\")");
  const std::uint64_t version = h5::read_attr_u64(cx, file, "/", "schema_version");
  if (version != kSceneSchemaVersion)
    cx.error("scene archive schema " + std::to_string(version) + "; this build reads " +
             std::to_string(kSceneSchemaVersion));
  for (const auto& spec : scene_schema::kRoot)
    read_attribute(cx, file, "/", a.header, spec);
  for (const auto& spec : scene_schema::kRootLast)
    read_attribute(cx, file, "/", a.header, spec);
  for (const std::string& name : h5::attr_names(cx, file, "/"))
    if (!is_root_attribute(name))
      a.provenance.emplace_back(name, h5::read_attr_string(cx, file, "/", name));
}

void read_groups(const h5::Context& cx, hid_t file, SceneArchive& a) {
  read_table(cx, open_group(cx, file, "frames"), scene_schema::kFrames, a.frames);
  {
    const Group bodies = open_group(cx, file, "bodies");
    read_table(cx, bodies, scene_schema::kBodies, a.bodies);
    read_table(cx, bodies, scene_schema::kPoses, a.poses);
  }
  read_table(cx, open_group(cx, file, "contacts"), scene_schema::kContacts, a.contacts);
  if (a.header.audit_every > 0)
    read_table(cx, open_group(cx, file, "audit"), scene_schema::kAudit, a.audit);
  if (a.header.queries_every > 0) {
    read_table(cx, open_group(cx, file, "queries"), scene_schema::kQueries, a.queries);
    read_table(cx, open_group(cx, file, "shapes"), scene_schema::kShapes, a.shapes);
  }
  if (h5::has_link(cx, file, "/", "state")) a.state = read_state(cx, file);
}

// ---- the schema's tables, for docs/scenes.md ----

template <class T>
std::string_view type_name() {
  if constexpr (std::is_same_v<T, double>) return "float64";
  if constexpr (std::is_same_v<T, std::int64_t>) return "int64";
  if constexpr (std::is_same_v<T, std::uint32_t>) return "uint32";
  if constexpr (std::is_same_v<T, std::int32_t>) return "int32";
  if constexpr (std::is_same_v<T, std::uint8_t>) return "uint8";
  if constexpr (std::is_same_v<T, std::string>) return "string";
}

using Rows = std::vector<std::array<std::string, 3>>;

std::array<std::string, 3> row(std::string_view a, std::string_view b, std::string_view c) {
  return {"`" + std::string(a) + "`", std::string(b), std::string(c)};
}

template <class R, std::size_t N>
void table_rows(const scene_schema::Table<R, N>& table, Rows& out) {
  for (const auto& column : table.columns)
    std::visit(
        [&](auto member) {
          using T = typename std::decay_t<decltype(std::declval<R>().*member)>::value_type;
          std::string type(type_name<T>());
          if (column.width > 1) type += " × " + std::to_string(column.width);
          std::string meaning(column.meaning);
          if (column.presence == scene_schema::Presence::when_recorded)
            meaning += " (absent when not recorded)";
          out.push_back(row(column.name, type, meaning));
        },
        column.field);
}

template <class V>
std::string_view attribute_type(const V&) {
  using Member = std::decay_t<decltype(std::declval<SceneHeader>().*std::declval<V>())>;
  if constexpr (std::is_same_v<Member, std::string>) return "string";
  if constexpr (std::is_same_v<Member, bool>) return "uint8";
  if constexpr (std::is_same_v<Member, double>) return "float64";
  return "uint64";
}
template <class V>
std::string_view state_attribute_type(const V&) {
  using Member = std::decay_t<decltype(std::declval<SceneState>().*std::declval<V>())>;
  if constexpr (std::is_same_v<Member, double>) return "float64";
  return "uint64";
}

template <class Specs>
void attribute_rows(const Specs& specs, Rows& out) {
  for (const auto& spec : specs)
    std::visit(
        [&](auto member) {
          if constexpr (std::is_same_v<typename Specs::value_type, scene_schema::Attribute>)
            out.push_back(row(spec.name, attribute_type(member), spec.meaning));
          else
            out.push_back(row(spec.name, state_attribute_type(member), spec.meaning));
        },
        spec.field);
}

}  // namespace

void write_scene_archive(const std::string& path, const SceneArchive& archive) {
  h5::quiet_errors();
  const h5::Context cx(path);
  const std::string writing = path + ".writing";
  write_file(cx, writing, archive);
  std::error_code ec;
  std::filesystem::rename(writing, path, ec);
  if (ec) cx.error("cannot rename " + writing + ": " + ec.message());
}

SceneArchive read_scene_archive(const std::string& path) {
  h5::quiet_errors();
  const h5::Context cx(path);
  const h5::Handle file =
      cx.handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "cannot open it");
  SceneArchive a;
  read_header(cx, file.get(), a);
  read_groups(cx, file.get(), a);
  return a;
}

namespace scene_schema {

std::optional<Rows> rows(std::string_view group) {
  Rows out;
  if (group == "root") {
    out.push_back(row("format", "string", "`gjklab-scene`"));
    out.push_back(row("schema_version", "uint64", std::to_string(kSceneSchemaVersion)));
    attribute_rows(kRoot, out);
    attribute_rows(kRootLast, out);
  } else if (group == "frames") {
    table_rows(kFrames, out);
  } else if (group == "bodies") {
    table_rows(kBodies, out);
    table_rows(kPoses, out);
  } else if (group == "contacts") {
    table_rows(kContacts, out);
  } else if (group == "audit") {
    table_rows(kAudit, out);
  } else if (group == "queries") {
    table_rows(kQueries, out);
  } else if (group == "shapes") {
    table_rows(kShapes, out);
  } else if (group == "state") {
    table_rows(kBodyState, out);
    table_rows(kPairState, out);
    table_rows(kSimplexState, out);
    table_rows(kPointState, out);
    attribute_rows(kStateAttributes, out);
  } else {
    return std::nullopt;
  }
  return out;
}

}  // namespace scene_schema

}  // namespace gjklab::experiment
