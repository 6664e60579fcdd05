#include "gjklab/experiment/config/config.hpp"

#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/cases/real_objects.hpp"
#include "gjklab/experiment/cases/scene_stream.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <system_error>

namespace gjklab::experiment {

namespace {

/// The largest sphere-swept radius (shape units), as the bound of `scale`.
constexpr double kMaxRadius = 1e100;

std::string format_message(const std::string& file, int line, const std::string& key,
                           const std::string& problem) {
  std::string message = file;
  if (line > 0) message += ":" + std::to_string(line);
  message += ": ";
  if (!key.empty()) message += "key '" + key + "': ";
  message += problem;
  return message;
}

}  // namespace

ConfigError::ConfigError(const std::string& file, int line, const std::string& key,
                         const std::string& problem)
    : std::runtime_error(format_message(file, line, key, problem)) {}

namespace {

// ---- limits that are not in the header ----
constexpr std::int64_t kMaxThreads = 1024;
constexpr std::int64_t kMaxCases = std::int64_t{1} << 32;  // case ids index 2^32 seed streams
constexpr std::int64_t kMaxVertices = 10'000'000;
constexpr std::int64_t kMaxRepetitions = 1'000'000;
constexpr double kMinScale = 1e-100;  // keeps squared lengths far from underflow and overflow
constexpr double kMaxScale = 1e100;

constexpr ContactType kContactTypes[] = {
    ContactType::face_face,      ContactType::edge_edge,         ContactType::vertex_face,
    ContactType::edge_face,      ContactType::vertex_edge,       ContactType::vertex_vertex,
    ContactType::parallel_edges, ContactType::crossing_segments, ContactType::needle_point,
    ContactType::needle_segment, ContactType::thin_rods,         ContactType::crossing_wedges,
    ContactType::tilted_plates,
};

template <typename Range>
std::string join(const Range& items) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    out += std::string_view(item);
  }
  return out;
}

std::string shape_names() {
  std::vector<std::string_view> names;
  for (const FamilyShapeInfo& shape : family_shapes())
    names.push_back(shape.name);
  return join(names);
}

/// The algorithms that answer for sphere-swept shapes, for messages.
std::string swept_algorithm_names() {
  std::vector<std::string_view> names;
  for (const AlgorithmInfo& a : algorithms())
    if (a.run_swept) names.push_back(a.name);
  return join(names);
}

std::string contact_names() {
  return join(contact_choices());
}

std::string_view type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

int line_of(const toml::source_region& region) {
  return region.begin.line > 0 ? static_cast<int>(region.begin.line) : 1;
}
int line_of(const toml::node& node) {
  return line_of(node.source());
}

/// One TOML table being read: checks unknown keys up front, then reads typed, range-checked
/// values and reports problems as ConfigError with the dotted key path and the value's line.
class Section {
 public:
  Section(const std::string& file, const toml::table& table, std::string path, int header_line)
      : file_(file), table_(table), path_(std::move(path)), header_line_(header_line) {}

  const toml::table& table() const { return table_; }
  const std::string& path() const { return path_; }
  int header_line() const { return header_line_; }

  std::string key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }

  [[noreturn]] void fail(int line, std::string_view key, const std::string& problem) const {
    throw ConfigError(file_, line, key_path(key), problem);
  }
  [[noreturn]] void fail(const toml::node& node, std::string_view key,
                         const std::string& problem) const {
    fail_at(node.source(), key, problem);
  }
  /// A value (or key) inherited from a base experiment names the base file.
  [[noreturn]] void fail_at(const toml::source_region& where, std::string_view key,
                            const std::string& problem) const {
    throw ConfigError(where.path ? *where.path : file_, line_of(where), key_path(key), problem);
  }
  [[noreturn]] void missing(std::string_view key, const std::string& what = {}) const {
    fail(header_line_, key, what.empty() ? "missing (required)" : what);
  }

  /// Rejects every key not in `allowed` (the first one in file order). `explain` may turn an
  /// unknown key into a more specific message (e.g. a key that belongs to another algorithm).
  template <typename Explain>
  void allow_only(const std::vector<std::string_view>& allowed, Explain explain) const {
    const toml::key* first = nullptr;
    for (auto&& [key, value] : table_) {
      (void)value;
      if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
      if (!first || key.source().begin.line < first->source().begin.line) first = &key;
    }
    if (!first) return;
    std::string problem = explain(first->str());
    if (problem.empty()) problem = "unknown key; valid: " + join(allowed);
    fail_at(first->source(), first->str(), problem);
  }
  void allow_only(const std::vector<std::string_view>& allowed) const {
    allow_only(allowed, [](std::string_view) { return std::string(); });
  }

  const toml::node* find(std::string_view key) const { return table_.get(key); }

  /// The section of a nested table, named `path` (a dotted key path) in messages.
  Section child(const toml::table& table, std::string path) const {
    return Section(file_, table, std::move(path), line_of(table));
  }

  std::optional<std::string> string(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_string())
      fail(*node, key, "expected a string, got " + std::string(type_name(*node)));
    return node->as_string()->get();
  }

  std::optional<bool> boolean(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_boolean())
      fail(*node, key, "expected a boolean (true or false), got " + std::string(type_name(*node)));
    return node->as_boolean()->get();
  }

  /// An integer in [lo, hi].
  std::optional<std::int64_t> integer(std::string_view key, std::int64_t lo,
                                      std::int64_t hi) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    return integer_value(*node, key, lo, hi);
  }

  std::int64_t integer_value(const toml::node& node, std::string_view key, std::int64_t lo,
                             std::int64_t hi) const {
    if (!node.is_integer())
      fail(node, key, "expected an integer, got " + std::string(type_name(node)));
    const std::int64_t v = node.as_integer()->get();
    if (v < lo || v > hi) {
      if (hi == std::numeric_limits<std::int64_t>::max())
        fail(node, key, "must be at least " + std::to_string(lo) + ", got " + std::to_string(v));
      fail(node, key,
           "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " +
               std::to_string(v));
    }
    return v;
  }

  /// A finite number (an integer is accepted and converted).
  double number_value(const toml::node& node, std::string_view key) const {
    double v = 0;
    if (node.is_floating_point())
      v = node.as_floating_point()->get();
    else if (node.is_integer())
      v = static_cast<double>(node.as_integer()->get());
    else
      fail(node, key, "expected a number, got " + std::string(type_name(node)));
    if (!std::isfinite(v)) fail(node, key, "must be finite, got " + round_trip(v));
    return v;
  }

  std::optional<double> positive(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const double v = number_value(*node, key);
    if (!(v > 0)) fail(*node, key, "must be > 0, got " + round_trip(v));
    return v;
  }

  std::optional<double> non_negative(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const double v = number_value(*node, key);
    if (!(v >= 0)) fail(*node, key, "must be >= 0, got " + round_trip(v));
    return v;
  }

  std::optional<double> fraction(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const double v = number_value(*node, key);
    if (!(v >= 0 && v <= 1)) fail(*node, key, "must be between 0 and 1, got " + round_trip(v));
    return v;
  }

  /// A number >= 0 (fixed) or a [lo, hi] pair with 0 < lo <= hi (a log-uniform range).
  /// A radius: a number >= 0 or a positive [lo, hi], at most kMaxRadius (shape units, as
  /// `scale`'s bound: a radius of 1e308 overflowed the placement's coordinates).
  std::optional<Interval> radius_interval(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    Interval r;
    if (node->is_number()) {
      const double v = number_value(*node, key);
      if (!(v >= 0)) fail(*node, key, "must be >= 0, got " + round_trip(v));
      r = Interval{v, v};
    } else {
      r = *positive_interval(key);
    }
    if (!(r.hi <= kMaxRadius))
      fail(*node, key, "must be at most " + round_trip(kMaxRadius) + ", got " + round_trip(r.hi));
    return r;
  }

  /// A positive number or a [lo, hi] pair with 0 < lo <= hi.
  std::optional<Interval> positive_interval(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    Interval interval;
    if (const toml::array* array = node->as_array()) {
      if (array->size() != 2)
        fail(*node, key,
             "expected [lo, hi] (two numbers), got " + std::to_string(array->size()) + " elements");
      interval.lo = number_value(*array->get(0), key);
      interval.hi = number_value(*array->get(1), key);
    } else if (node->is_number()) {
      interval.lo = interval.hi = number_value(*node, key);
    } else {
      fail(*node, key, "expected a number or [lo, hi], got " + std::string(type_name(*node)));
    }
    if (!(interval.lo > 0))
      fail(*node, key, "lower bound must be > 0, got " + round_trip(interval.lo));
    if (!(interval.lo <= interval.hi))
      fail(*node, key,
           "lower bound " + round_trip(interval.lo) + " exceeds upper bound " +
               round_trip(interval.hi));
    return interval;
  }

  /// An integer count or a [lo, hi] pair of counts with 1 <= lo <= hi <= kMaxVertices.
  std::optional<Interval> count_interval(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    Interval interval;
    if (const toml::array* array = node->as_array()) {
      if (array->size() != 2)
        fail(
            *node, key,
            "expected [lo, hi] (two integers), got " + std::to_string(array->size()) + " elements");
      interval.lo = static_cast<double>(integer_value(*array->get(0), key, 1, kMaxVertices));
      interval.hi = static_cast<double>(integer_value(*array->get(1), key, 1, kMaxVertices));
      if (interval.lo > interval.hi)
        fail(*node, key,
             "lower bound " + std::to_string(static_cast<std::int64_t>(interval.lo)) +
                 " exceeds upper bound " + std::to_string(static_cast<std::int64_t>(interval.hi)));
    } else if (node->is_integer()) {
      interval.lo = interval.hi = static_cast<double>(integer_value(*node, key, 1, kMaxVertices));
    } else {
      fail(*node, key, "expected an integer or [lo, hi], got " + std::string(type_name(*node)));
    }
    return interval;
  }

  /// A sub-table (either [a.b] or an inline table), or nullptr if absent.
  const toml::table* subtable(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return nullptr;
    if (!node->is_table())
      fail(*node, key, "expected a table, got " + std::string(type_name(*node)));
    return node->as_table();
  }

  /// An array of tables ([[key]]); its elements must all be tables.
  const toml::array* table_array(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return nullptr;
    const toml::array* array = node->as_array();
    if (!array)
      fail(*node, key,
           "expected an array of tables ([[" + std::string(key) + "]]), got " +
               std::string(type_name(*node)));
    for (std::size_t i = 0; i < array->size(); ++i)
      if (!array->get(i)->is_table())
        fail(*array->get(i), std::string(key) + "[" + std::to_string(i) + "]",
             "expected a table, got " + std::string(type_name(*array->get(i))));
    return array;
  }

 private:
  const std::string& file_;
  const toml::table& table_;
  std::string path_;
  int header_line_;
};

ShapeKind read_shape(const Section& s, std::string_view key) {
  const std::string name = *s.string(key);
  if (const ShapeGenerator* generator = find_shape_generator(name)) return generator->kind;
  s.fail(*s.find(key), key, "unknown shape '" + name + "'; valid: " + shape_names());
}

/// The vertex count a shape gets when the family does not say (the generator's default; 32
/// for shapes read from files, whose clouds are read whole).
Interval default_vertices(ShapeKind kind) {
  const ShapeGenerator* generator = find_shape_generator(kind);
  const double n = generator ? generator->default_vertices : 32;
  return {n, n};
}

/// Reads [placement] keys from `s` on top of `base`.
PlacementSpec read_placement(const Section& s, PlacementSpec base) {
  s.allow_only({"mode", "gap", "depth", "overlapping_fraction", "spread"});
  if (const auto mode = s.string("mode")) {
    const auto value = value_named(kPlacementModeNames, *mode);
    if (!value)
      s.fail(*s.find("mode"), "mode",
             "unknown placement mode '" + *mode + "'; valid: " + names_list(kPlacementModeNames));
    base.mode = *value;
  }
  if (const auto gap = s.positive_interval("gap")) base.gap = *gap;
  if (const auto depth = s.positive_interval("depth")) base.depth = *depth;
  if (const auto f = s.fraction("overlapping_fraction")) base.overlapping_fraction = *f;
  if (const auto spread = s.positive("spread")) base.spread = *spread;
  return base;
}

/// `contact = "..."` of a contact family.
void read_contact(const Section& s, FamilySpec& f) {
  const auto name = s.string("contact");
  if (!name)
    s.missing("contact", "missing (shape = \"contact\" needs it); valid: " + contact_names());
  if (*name == "any") {
    f.contact_any = true;
    f.contact = ContactType::face_face;
  } else {
    const auto* found = std::find_if(std::begin(kContactTypes), std::end(kContactTypes),
                                     [&](ContactType c) { return to_string(c) == *name; });
    if (found == std::end(kContactTypes))
      s.fail(*s.find("contact"), "contact",
             "unknown contact type '" + *name + "'; valid: " + contact_names());
    f.contact = *found;
  }
  f.shape_a = ShapeKind::box;
  f.shape_b = ShapeKind::box;
  if (const auto angle = s.positive_interval("angle")) f.angle = *angle;
}

/// `path = "..."` of a file family: reads every pair now, so a bad file is a config error.
/// `shape = "file"` (a cases file) or `shape = "stream"` (a scene archive's recorded queries,
/// scene_stream.hpp): the pairs, read now so that a bad file is a config error.
void read_stored_pairs(const Section& s, const std::string& experiment_file, FamilySpec& f,
                       bool stream) {
  const auto path = s.string("path");
  if (!path)
    s.missing("path", stream ? "missing (shape = \"stream\" needs a scene archive)"
                             : "missing (shape = \"file\" needs the cases file)");
  f.path = *path;
  std::filesystem::path resolved(*path);
  if (resolved.is_relative())
    resolved = std::filesystem::path(experiment_file).parent_path() / resolved;
  if (stream) {
    try {
      f.stored = read_scene_stream(resolved);
    } catch (const InputError& e) {
      s.fail(*s.find("path"), "path", e.what());
    }
    f.shape_a = f.shape_b = ShapeKind::from_file;
    return;
  }
  std::vector<CaseOrError> cases;
  try {
    cases = read_cases_file(resolved);
  } catch (const InputError& e) {
    s.fail(*s.find("path"), "path", e.what());
  }
  for (const CaseOrError& c : cases) {
    if (const auto* e = std::get_if<CaseError>(&c))
      s.fail(*s.find("path"), "path",
             resolved.string() + ":" + std::to_string(e->line) + ": case '" + e->id +
                 "': " + e->problem);
    const auto& p = std::get<PointCase>(c);
    f.stored.push_back({p.id, p.a, p.b, p.radius_a, p.radius_b});
  }
  if (f.stored.empty()) s.fail(*s.find("path"), "path", resolved.string() + " holds no cases");
  f.shape_a = f.shape_b = ShapeKind::from_file;
}

/// `path = "..."` of a mesh family: one mesh file, or a folder of them (.off, .obj, .ply,
/// .stl), read now so that a bad file is a config error.
void read_meshes(const Section& s, const std::string& experiment_file, FamilySpec& f) {
  const auto path = s.string("path");
  if (!path) s.missing("path", "missing (shape = \"mesh\" needs a mesh file or a folder of them)");
  f.path = *path;
  std::filesystem::path resolved(*path);
  if (resolved.is_relative())
    resolved = std::filesystem::path(experiment_file).parent_path() / resolved;
  std::vector<std::filesystem::path> files;
  try {
    files = exact::mesh_files(resolved);
  } catch (const std::runtime_error& e) {
    s.fail(*s.find("path"), "path", e.what());
  }
  for (const auto& file : files) {
    try {
      f.meshes.push_back(exact::read_mesh_vertices(file));
    } catch (const std::runtime_error& e) {
      s.fail(*s.find("path"), "path", e.what());
    }
  }
  f.shape_a = f.shape_b = ShapeKind::mesh;
}

/// `objects = ["elephant", …]` or `"all"` of a real_object family: each object's hull, read
/// now, so that an unknown name or a missing package is a config error.
void read_real_objects(const Section& s, FamilySpec& f) {
  const toml::node* node = s.find("objects");
  if (!node)
    s.missing("objects", "missing (shape = \"real_object\" needs \"all\" or a list of names)");
  const bool all = node->is_string() && node->as_string()->get() == "all";
  const toml::array* names = node->as_array();
  if (!all && (!names || names->empty()))
    s.fail(*node, "objects", "expected \"all\" or a non-empty array of object names");
  if (names) {
    for (const toml::node& entry : *names) {
      if (!entry.is_string()) s.fail(entry, "objects", "expected object names (strings)");
      f.objects.push_back(entry.as_string()->get());
    }
  }
  try {
    if (all) f.objects = real_object_names();
    for (const std::string& name : f.objects)
      f.meshes.push_back(real_object(name));
  } catch (const std::runtime_error& e) {
    // RealObjectError (no package, unknown name: the message lists the valid names), or a
    // mesh of the package that cannot be read (the message names the file).
    s.fail(*node, "objects", e.what());
  }
  f.shape_a = f.shape_b = ShapeKind::mesh;
}

Rotation read_rotation(const Section& s) {
  const toml::node* node = s.find("rotate");
  if (!node) return Rotation::random;
  if (node->is_boolean()) return node->as_boolean()->get() ? Rotation::random : Rotation::none;
  if (node->is_string()) {
    const std::string& v = node->as_string()->get();
    if (v == "random") return Rotation::random;
    if (v == "none") return Rotation::none;
    if (v == "axes") return Rotation::axes;
  }
  s.fail(*node, "rotate", "expected true, false, \"random\", \"none\" or \"axes\"");
}

/// The radius of a sphere-swept shape of its own kind when the file gives none.
Interval default_radius(ShapeKind kind) {
  if (kind == ShapeKind::sphere) return {1, 1};
  if (kind == ShapeKind::capsule) return {0.5, 0.5};
  return {0, 0};
}

/// `radius` (both shapes), `radius_a`, `radius_b`: sphere-swept shapes. Contact and file
/// families give their pairs exactly, so they take no radius.
void read_radii(const Section& s, bool exact_pairs, FamilySpec& f) {
  for (std::string_view key : {"radius", "radius_a", "radius_b"}) {
    if (!s.find(key)) continue;
    if (exact_pairs)
      s.fail(*s.find(key), key,
             "applies only to generated and mesh families (contact and file pairs are exact)");
    if (key != "radius" && s.find("radius"))
      s.fail(*s.find(key), key, "cannot be combined with 'radius' (which sets both radii)");
  }
  f.radius_a = default_radius(f.shape_a);
  f.radius_b = default_radius(f.shape_b);
  if (const auto r = s.radius_interval("radius")) f.radius_a = f.radius_b = *r;
  if (const auto r = s.radius_interval("radius_a")) f.radius_a = *r;
  if (const auto r = s.radius_interval("radius_b")) f.radius_b = *r;
}

/// What a [[family]] table describes, read from its `shape` key: the kinds of pair source that
/// take keys of their own (contact, file, stream, mesh, real_object), or generated shapes.
struct FamilyForm {
  bool has_shape = false;  // `shape` sets both shapes (or names a pair source)
  bool is_contact = false;
  bool is_stream = false;
  bool is_file = false;  // pairs read from a file: a file family or a query stream
  bool is_mesh = false;
  bool is_real_object = false;
};

FamilyForm family_form(const Section& s) {
  FamilyForm form;
  form.has_shape = s.find("shape") != nullptr;
  const auto pair_shape = form.has_shape && s.find("shape")->is_string()
                              ? std::optional<std::string>(*s.string("shape"))
                              : std::nullopt;
  form.is_contact = pair_shape == "contact";
  form.is_stream = pair_shape == "stream";
  form.is_file = pair_shape == "file" || form.is_stream;
  form.is_mesh = pair_shape == "mesh";
  form.is_real_object = pair_shape == "real_object";
  return form;
}

/// Refuses the keys that belong to another form of family than this one.
void refuse_foreign_keys(const Section& s, const FamilyForm& form) {
  if (!form.is_real_object && s.find("objects"))
    s.fail(*s.find("objects"), "objects", "applies only to shape = \"real_object\"");
  for (std::string_view key : {"contact", "angle"})
    if (!form.is_contact && s.find(key))
      s.fail(*s.find(key), key, "applies only to shape = \"contact\"");
  if (!form.is_file && !form.is_mesh && s.find("path"))
    s.fail(*s.find("path"), "path", "applies only to shape = \"file\", \"stream\" or \"mesh\"");
  for (std::string_view key : {"shape_a", "shape_b"})
    if (form.has_shape && s.find(key))
      s.fail(*s.find(key), key, "cannot be combined with 'shape' (which sets both shapes)");
}

/// The pair's source: a contact configuration, stored pairs, meshes, real objects, or the
/// generated shape (`shape`, or `shape_a` with `shape_b`).
void read_pair_source(const Section& s, const FamilyForm& form, const std::string& experiment_file,
                      FamilySpec& f) {
  if (form.is_contact) {
    read_contact(s, f);
  } else if (form.is_file) {
    read_stored_pairs(s, experiment_file, f, form.is_stream);
  } else if (form.is_mesh) {
    read_meshes(s, experiment_file, f);
  } else if (form.is_real_object) {
    read_real_objects(s, f);
  } else if (form.has_shape) {
    f.shape_a = f.shape_b = read_shape(s, "shape");
  } else if (s.find("shape_a") || s.find("shape_b")) {
    if (!s.find("shape_a")) s.missing("shape_a", "missing (shape_b is given without shape_a)");
    if (!s.find("shape_b")) s.missing("shape_b", "missing (shape_a is given without shape_b)");
    f.shape_a = read_shape(s, "shape_a");
    f.shape_b = read_shape(s, "shape_b");
  } else {
    s.missing("shape", "missing (give 'shape', or both 'shape_a' and 'shape_b'); valid shapes: " +
                           shape_names());
  }
}

/// `vertices` (both shapes), `vertices_a`, `vertices_b`; each shape's default otherwise.
void read_vertex_counts(const Section& s, FamilySpec& f) {
  f.vertices_a = default_vertices(f.shape_a);
  f.vertices_b = default_vertices(f.shape_b);
  for (std::string_view key : {"vertices_a", "vertices_b"})
    if (s.find("vertices") && s.find(key))
      s.fail(*s.find(key), key, "cannot be combined with 'vertices' (which sets both counts)");
  if (const auto v = s.count_interval("vertices")) f.vertices_a = f.vertices_b = *v;
  if (const auto v = s.count_interval("vertices_a")) f.vertices_a = *v;
  if (const auto v = s.count_interval("vertices_b")) f.vertices_b = *v;
}

/// Size, shape proportions, rotation, offset and weight of the drawn pairs.
void read_pair_draw(const Section& s, FamilySpec& f) {
  if (const auto scale = s.positive("scale")) {
    if (*scale < kMinScale || *scale > kMaxScale)
      s.fail(*s.find("scale"), "scale",
             "must be between " + round_trip(kMinScale) + " and " + round_trip(kMaxScale) +
                 ", got " + round_trip(*scale));
    f.scale = *scale;
  }
  f.rotation = read_rotation(s);
  if (const auto aspect = s.positive_interval("aspect")) f.aspect = *aspect;
  if (const auto ratio = s.positive_interval("scale_b")) f.scale_ratio = *ratio;
  if (const auto offset = s.positive_interval("offset")) f.offset = *offset;
  if (const auto weight = s.positive("weight")) f.weight = *weight;
}

/// The family's own placement (over the experiment's); touching needs exact contacts.
void read_family_placement(const Section& s, const FamilyForm& form, const PlacementSpec& placement,
                           FamilySpec& f) {
  f.placement = placement;
  if (const toml::table* sub = s.subtable("placement"))
    f.placement = read_placement(s.child(*sub, s.key_path("placement")), placement);
  const bool touching = f.placement.mode == PlacementMode::touching;
  if (touching && (!form.is_contact || !exact_contact(f.contact)))
    s.fail(s.header_line(), "placement.mode",
           "\"touching\" needs an exact contact family (shape = \"contact\", not parallel-edges "
           "or the thin contacts)");
}

/// `name`, or one made from what the family draws.
std::string read_family_name(const Section& s, const FamilyForm& form, const FamilySpec& f) {
  if (const auto name = s.string("name")) {
    if (name->empty()) s.fail(*s.find("name"), "name", "must not be empty");
    return *name;
  }
  if (form.is_contact)
    return "contact-" + std::string(f.contact_any ? "any" : to_string(f.contact));
  if (form.is_file) return "file:" + f.path;
  if (form.is_mesh) return "mesh:" + f.path;
  if (form.is_real_object)
    return s.find("objects")->is_string() ? "real_object:all" : "real_object";
  if (f.shape_a == f.shape_b) return std::string(to_string(f.shape_a));
  return std::string(to_string(f.shape_a)) + "/" + std::string(to_string(f.shape_b));
}

FamilySpec read_family(const Section& s, const PlacementSpec& placement,
                       const std::string& experiment_file) {
  s.allow_only({"name",    "shape",  "shape_a", "shape_b",   "vertices", "vertices_a", "vertices_b",
                "scale",   "rotate", "weight",  "placement", "contact",  "angle",      "aspect",
                "scale_b", "offset", "path",    "radius",    "radius_a", "radius_b",   "objects"});
  const FamilyForm form = family_form(s);
  refuse_foreign_keys(s, form);
  FamilySpec f;
  read_pair_source(s, form, experiment_file, f);
  read_vertex_counts(s, f);
  read_pair_draw(s, f);
  read_radii(s, form.is_contact || form.is_file, f);
  read_family_placement(s, form, placement, f);
  f.name = read_family_name(s, form, f);
  return f;
}

toml::table parse_toml(const std::string& text, const std::string& source) {
  try {
    return toml::parse(std::string_view(text), std::string_view(source));
  } catch (const toml::parse_error& e) {
    throw ConfigError(source, line_of(e.source()), "",
                      "TOML syntax error: " + std::string(e.description()));
  }
}

/// `into` with every key of `over` put in: tables merge key by key, anything else (values,
/// arrays, arrays of tables such as [[family]] and [[algorithm]]) is replaced whole.
void merge_over(toml::table& into, const toml::table& over) {
  for (const auto& [key, node] : over) {
    toml::node* existing = into.get(key);
    if (existing && existing->is_table() && node.is_table()) {
      merge_over(*existing->as_table(), *node.as_table());
    } else {
      into.insert_or_assign(key, node);
    }
  }
}

/// `exclude_families = ["NAME", ...]`: drops the named families (typically a base experiment's
/// that do not suit the derived one); every name must exist and at least one family must stay.
void exclude_families(const Section& top, std::vector<FamilySpec>& families) {
  const toml::node* node = top.find("exclude_families");
  if (!node) return;
  const toml::array* names = node->as_array();
  if (!names) top.fail(*node, "exclude_families", "expected an array of family names");
  for (const toml::node& entry : *names) {
    if (!entry.is_string()) top.fail(entry, "exclude_families", "expected family names (strings)");
    const std::string& name = entry.as_string()->get();
    const auto found = std::find_if(families.begin(), families.end(),
                                    [&](const FamilySpec& f) { return f.name == name; });
    if (found == families.end()) {
      std::vector<std::string_view> known;
      for (const FamilySpec& f : families)
        known.push_back(f.name);
      top.fail(entry, "exclude_families", "no family '" + name + "'; families: " + join(known));
    }
    families.erase(found);
  }
  if (families.empty()) top.fail(*node, "exclude_families", "excludes every family");
}

/// Bases may themselves have a base, up to this depth (which also stops a cycle).
constexpr int kMaxBaseDepth = 8;

/// Rewrites each relative `path` of the base's [[family]] tables (relative to the base file's
/// folder) to name the same file relative to the derived file's folder, so that a base used
/// from another folder still finds its meshes and case files.
void rebase_family_paths(toml::table& base, const std::filesystem::path& base_folder,
                         const std::filesystem::path& derived_folder) {
  toml::array* families = base.get_as<toml::array>("family");
  if (!families) return;
  for (toml::node& node : *families) {
    toml::table* family = node.as_table();
    if (!family) continue;
    toml::value<std::string>* path = family->get_as<std::string>("path");
    if (!path || std::filesystem::path(path->get()).is_absolute()) continue;
    const std::filesystem::path target = (base_folder / path->get()).lexically_normal();
    const std::filesystem::path from =
        derived_folder.empty() ? std::filesystem::path(".") : derived_folder.lexically_normal();
    std::filesystem::path moved = target.lexically_relative(from);
    if (moved.empty()) moved = std::filesystem::absolute(target);
    *path = moved.generic_string();
  }
}

/// The experiment `derived` (read from `source`) over its base file: `base = "FILE"`, relative
/// to `source`'s folder. Keys of `derived` win; tables merge (see merge_over).
toml::table with_base(toml::table derived, const std::string& source, int depth) {
  const toml::node& node = *derived.get("base");
  const Section s(source, derived, "", 1);
  if (!node.is_string()) s.fail(node, "base", "expected a file name (a string)");
  if (depth >= kMaxBaseDepth)
    s.fail(node, "base",
           "bases nest deeper than " + std::to_string(kMaxBaseDepth) + " files (a cycle?)");
  std::filesystem::path path(node.as_string()->get());
  if (path.is_relative()) path = std::filesystem::path(source).parent_path() / path;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path))
    s.fail(node, "base", "cannot read the base experiment " + path.string());
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  toml::table base = parse_toml(text, path.string());
  if (base.contains("base")) base = with_base(std::move(base), path.string(), depth + 1);
  rebase_family_paths(base, path.parent_path(), std::filesystem::path(source).parent_path());
  derived.erase("base");
  merge_over(base, derived);
  return base;
}

/// The option keys of each algorithm beyond `name` and `max_iterations`.
std::vector<std::string_view> own_option_keys(std::string_view algorithm) {
  std::vector<std::string_view> keys = option_keys(algorithm);
  std::erase(keys, std::string_view("max_iterations"));
  return keys;
}

/// The text of one option's TOML value: a number, [x, y, z], a boolean or a string.
std::string option_text(const Section& s, const toml::node& node, std::string_view key) {
  if (node.is_string()) return node.as_string()->get();
  if (node.is_boolean()) return node.as_boolean()->get() ? "true" : "false";
  if (const toml::array* array = node.as_array()) {
    std::string text;
    for (std::size_t i = 0; i < array->size(); ++i)
      text += (i ? " " : "") + round_trip(s.number_value(*array->get(i), key));
    return text;
  }
  return round_trip(s.number_value(node, key));
}

/// The algorithms an experiment may list: the registry without the exact oracle.
std::vector<std::string_view> query_algorithm_names() {
  std::vector<std::string_view> names;
  for (const AlgorithmInfo& info : algorithms())
    if (info.kind != AnswerKind::exact) names.push_back(info.name);
  return names;
}

AlgorithmSpec read_algorithm(const Section& s) {
  const std::vector<std::string_view> valid = query_algorithm_names();
  const auto name = s.string("name");
  if (!name) s.missing("name", "missing (required); valid: " + join(valid));
  const toml::node& name_node = *s.find("name");
  const AlgorithmInfo* info = find_algorithm(*name);
  if (info && info->kind == AnswerKind::exact)
    s.fail(name_node, "name",
           "'" + *name +
               "' is not listed as an algorithm: the exact oracle runs on every case "
               "and is configured by [oracle] (enabled, depth); valid: " +
               join(valid));
  if (!info) s.fail(name_node, "name", "unknown algorithm '" + *name + "'; valid: " + join(valid));

  std::vector<std::string_view> allowed = {"name", "label", "max_iterations"};
  for (std::string_view key : own_option_keys(*name))
    allowed.push_back(key);
  s.allow_only(allowed, [&](std::string_view key) {
    std::vector<std::string_view> owners;
    for (std::string_view other : valid) {
      const auto keys = own_option_keys(other);
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) owners.push_back(other);
    }
    if (owners.empty()) return std::string();
    return "applies to " + join(owners) + ", not to " + *name + "; valid for " + *name + ": " +
           join(allowed);
  });

  AlgorithmSpec spec;
  spec.name = *name;
  spec.label = *name;
  if (const auto label = s.string("label")) {
    // The result group's name: lets one algorithm run twice with different options.
    if (label->empty() || label->find('/') != std::string::npos ||
        label->find('@') != std::string::npos)
      s.fail(*s.find("label"), "label", "must be non-empty and contain neither '/' nor '@'");
    spec.label = *label;
  }
  if (const toml::node* n = s.find("max_iterations"))
    s.integer_value(*n, "max_iterations", 1, std::numeric_limits<int>::max());
  for (std::string_view key : option_keys(*name)) {
    const toml::node* node = s.find(key);
    if (!node) continue;
    try {
      set_option(spec, key, option_text(s, *node, key));
    } catch (const std::invalid_argument& e) {
      s.fail(*node, key, e.what());
    }
  }
  return spec;
}

constexpr std::string_view kGeometrySweeps[] = {"offset", "scale"};

/// The most values a sweep may have (see read_sweep).
constexpr std::size_t kMaxSweepValues = 256;

/// [sweep]: parameter = an algorithm option (each value becomes its own algorithm group) or a
/// geometry parameter (each value its own family group, on the same base pairs).
void read_sweep(const Section& s, ExperimentConfig& config) {
  s.allow_only({"parameter", "values"});
  const auto parameter = s.string("parameter");
  if (!parameter) s.missing("parameter");
  const toml::node* values_node = s.find("values");
  if (!values_node) s.missing("values");
  const toml::array* values = values_node->as_array();
  if (!values || values->empty())
    s.fail(*values_node, "values", "expected a non-empty array of values");
  // Each value is a result group (its own columns in the archive, held in memory per batch):
  // a million of them once took 8 GB before failing.
  if (values->size() > kMaxSweepValues)
    s.fail(*values_node, "values",
           "at most " + std::to_string(kMaxSweepValues) + " values (got " +
               std::to_string(values->size()) + ")");

  if (std::find(std::begin(kGeometrySweeps), std::end(kGeometrySweeps), *parameter) !=
      std::end(kGeometrySweeps)) {
    GeometrySweep sweep{*parameter, {}};
    for (std::size_t i = 0; i < values->size(); ++i) {
      const toml::node& v = *values->get(i);
      const double x = v.is_number() ? s.number_value(v, "values") : -1;
      if (!(*parameter == "offset" ? x >= 0 : x > 0))
        s.fail(
            v, "values",
            *parameter == "offset" ? "offsets must be numbers >= 0" : "scales must be numbers > 0");
      if (std::find(sweep.values.begin(), sweep.values.end(), x) != sweep.values.end())
        s.fail(v, "values", "value " + round_trip(x) + " appears twice");
      sweep.values.push_back(x);
    }
    config.geometry_sweep = std::move(sweep);
    return;
  }

  std::vector<std::string_view> sweepable{std::begin(kGeometrySweeps), std::end(kGeometrySweeps)};
  bool taken = false;
  std::vector<AlgorithmSpec> expanded;
  for (const AlgorithmSpec& spec : config.algorithms) {
    const auto keys = option_keys(spec.name);
    for (std::string_view k : keys)
      if (std::find(sweepable.begin(), sweepable.end(), k) == sweepable.end())
        sweepable.push_back(k);
    if (std::find(keys.begin(), keys.end(), *parameter) == keys.end()) {
      expanded.push_back(spec);  // this algorithm does not take the parameter: run it once
      continue;
    }
    taken = true;
    std::set<std::string> seen;  // each value is a result group: a repeat would clash
    for (std::size_t i = 0; i < values->size(); ++i) {
      const std::string text = option_text(s, *values->get(i), "values");
      if (!seen.insert(text).second)
        s.fail(*values->get(i), "values", "value " + text + " appears twice");
      AlgorithmSpec copy = spec;
      try {
        set_option(copy, *parameter, text);
      } catch (const std::invalid_argument& e) {
        s.fail(*values->get(i), "values", e.what());
      }
      std::string shown = text;
      std::replace(shown.begin(), shown.end(), ' ', ',');
      copy.label = spec.name + "@" + *parameter + "=" + shown;
      expanded.push_back(std::move(copy));
    }
  }
  if (!taken)
    s.fail(*s.find("parameter"), "parameter",
           "no listed algorithm takes '" + *parameter + "'; valid: " + join(sweepable));
  config.algorithms = std::move(expanded);
}

bool valid_experiment_name(std::string_view name) {
  if (name.empty() || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
}

/// The top-level scalars: name, seed, cases, threads, output and touching_band.
void read_run_settings(const Section& top, ExperimentConfig& config) {
  const auto name = top.string("name");
  if (!name) top.missing("name");
  if (!valid_experiment_name(*name))
    top.fail(*top.find("name"), "name",
             "must be non-empty and use only letters, digits, '_', '-' and '.' (not leading), "
             "got '" +
                 *name + "'");
  config.name = *name;

  const auto seed = top.integer("seed", 0, std::numeric_limits<std::int64_t>::max());
  if (!seed) top.missing("seed");
  config.seed = static_cast<std::uint64_t>(*seed);

  const auto cases = top.integer("cases", 1, kMaxCases);
  if (!cases) top.missing("cases");
  config.cases = static_cast<std::uint64_t>(*cases);

  if (const auto threads = top.integer("threads", 1, kMaxThreads))
    config.threads = static_cast<int>(*threads);
  config.output = "results/" + config.name + ".h5";
  if (const auto output = top.string("output")) {
    if (output->empty()) top.fail(*top.find("output"), "output", "must not be empty");
    config.output = *output;
  }
  if (const auto band = top.positive("touching_band")) config.touching_band = *band;
}

/// [oracle]: which exact answers are computed, and the switches that depend on each other.
void read_oracle(const Section& oracle, ExperimentConfig& config) {
  oracle.allow_only({"enabled", "depth", "certificates", "verify", "hull_vertices"});
  if (const auto enabled = oracle.boolean("enabled")) config.oracle = *enabled;
  if (const auto depth = oracle.boolean("depth")) config.depth = *depth;
  if (const auto certificates = oracle.boolean("certificates")) config.certificates = *certificates;
  if (const auto verify = oracle.boolean("verify")) config.verify = *verify;
  if (const auto hull_vertices = oracle.boolean("hull_vertices"))
    config.hull_vertices = *hull_vertices;
  if (config.verify && !config.certificates)
    oracle.fail(*oracle.find("verify"), "verify",
                "audits the certificates, which are off (certificates = false)");
  if (config.depth && !config.oracle)
    oracle.fail(*oracle.find("depth"), "depth", "needs the oracle (enabled = true)");
}

/// [timing]: whether queries are timed, and how often each is repeated.
void read_timing(const Section& timing, ExperimentConfig& config) {
  timing.allow_only({"enabled", "repetitions"});
  if (const auto enabled = timing.boolean("enabled")) config.timing = *enabled;
  if (const auto repetitions = timing.integer("repetitions", 1, kMaxRepetitions))
    config.repetitions = static_cast<int>(*repetitions);
}

/// The [[family]] tables (at least one, distinct names), then exclude_families.
void read_families(const Section& top, const PlacementSpec& placement, ExperimentConfig& config) {
  const toml::array* families = top.table_array("family");
  if (!families) top.missing("family", "missing: at least one [[family]] is required");
  if (families->empty())
    top.fail(*top.find("family"), "family", "at least one [[family]] is required");
  for (std::size_t i = 0; i < families->size(); ++i) {
    const toml::table& t = *families->get(i)->as_table();
    const Section s = top.child(t, "family[" + std::to_string(i) + "]");
    FamilySpec family = read_family(s, placement, config.source);
    for (std::size_t j = 0; j < config.families.size(); ++j)
      if (config.families[j].name == family.name)
        s.fail(s.find("name") ? line_of(*s.find("name")) : s.header_line(), "name",
               "family name '" + family.name + "' is already used by family[" + std::to_string(j) +
                   "]; give each family a distinct name");
    config.families.push_back(std::move(family));
  }
  exclude_families(top, config.families);
}

/// The [[algorithm]] tables (at least one, distinct labels); needs the families read first, to
/// refuse a polytope-only algorithm on sphere-swept shapes.
void read_algorithms(const Section& top, ExperimentConfig& config) {
  const toml::array* algorithms = top.table_array("algorithm");
  if (!algorithms) top.missing("algorithm", "missing: at least one [[algorithm]] is required");
  if (algorithms->empty())
    top.fail(*top.find("algorithm"), "algorithm", "at least one [[algorithm]] is required");
  for (std::size_t i = 0; i < algorithms->size(); ++i) {
    const toml::table& t = *algorithms->get(i)->as_table();
    const Section s = top.child(t, "algorithm[" + std::to_string(i) + "]");
    AlgorithmSpec spec = read_algorithm(s);
    spec.options.oracle = config.oracle_options(config.depth);
    if (config.has_swept_shapes() && !find_algorithm(spec.name)->run_swept)
      s.fail(*s.find("name"), "name",
             "'" + spec.name +
                 "' answers for polytopes only, and this experiment has sphere-swept shapes "
                 "(a family with a radius, or shape sphere or capsule); valid here: " +
                 swept_algorithm_names());
    for (std::size_t j = 0; j < config.algorithms.size(); ++j)
      if (config.algorithms[j].label == spec.label)
        s.fail(*s.find(s.find("label") ? "label" : "name"), s.find("label") ? "label" : "name",
               "'" + spec.label + "' is already used by algorithm[" + std::to_string(j) +
                   "]; give the second one its own label = \"...\"");
    config.algorithms.push_back(std::move(spec));
  }
}

/// [trace]: which cases keep a per-iteration trace.
void read_trace(const Section& trace, ExperimentConfig& config) {
  trace.allow_only({"mode"});
  if (const auto mode = trace.string("mode")) {
    const auto value = trace_mode_from_string(*mode);
    if (!value)
      trace.fail(*trace.find("mode"), "mode",
                 "unknown trace mode '" + *mode + "'; valid: " + names_list(kTraceModeNames));
    config.trace = *value;
  }
}

/// The experiment merged with its base, if it names one, and the text the archive keeps: with a
/// base, the merged experiment, which reads back without the base.
std::pair<toml::table, std::string> resolve_base(const std::string& text,
                                                 const std::string& source) {
  toml::table root = parse_toml(text, source);
  if (!root.contains("base")) return {std::move(root), text};
  root = with_base(std::move(root), source, 0);
  std::ostringstream merged;
  merged << "# " << source << " merged with its base experiment\n"
         << toml::toml_formatter(root) << "\n";
  return {std::move(root), merged.str()};
}

}  // namespace

std::vector<std::string_view> contact_choices() {
  std::vector<std::string_view> names;
  for (ContactType c : kContactTypes)
    names.push_back(to_string(c));
  names.push_back("any");
  return names;
}

ExperimentConfig parse_experiment(const std::string& text, const std::string& source) {
  auto [root, effective_text] = resolve_base(text, source);
  const Section top(source, root, "", 1);
  top.allow_only({"name", "seed", "cases", "threads", "output", "touching_band", "oracle", "timing",
                  "placement", "family", "exclude_families", "algorithm", "sweep", "trace"});

  ExperimentConfig config;
  config.source = source;
  config.text = std::move(effective_text);
  read_run_settings(top, config);
  if (const toml::table* t = top.subtable("oracle")) read_oracle(top.child(*t, "oracle"), config);
  if (const toml::table* t = top.subtable("timing")) read_timing(top.child(*t, "timing"), config);
  PlacementSpec placement;
  if (const toml::table* t = top.subtable("placement"))
    placement = read_placement(top.child(*t, "placement"), placement);
  read_families(top, placement, config);
  read_algorithms(top, config);
  if (const toml::table* t = top.subtable("sweep")) read_sweep(top.child(*t, "sweep"), config);
  if (const toml::table* t = top.subtable("trace")) read_trace(top.child(*t, "trace"), config);
  return config;
}

ExperimentConfig load_experiment(const std::filesystem::path& path) {
  std::error_code ec;
  std::ifstream in;
  if (!std::filesystem::is_directory(path, ec)) in.open(path, std::ios::binary);
  if (!in.is_open() || !in) throw ConfigError(path.string(), 0, "", "cannot read");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw ConfigError(path.string(), 0, "", "cannot read");
  return parse_experiment(text, path.string());
}

bool ExperimentConfig::has_swept_shapes() const {
  auto swept_pair = [](const StoredPair& p) { return p.radius_a > 0 || p.radius_b > 0; };
  return std::any_of(families.begin(), families.end(), [&](const FamilySpec& f) {
    return f.radius_a.hi > 0 || f.radius_b.hi > 0 ||
           std::any_of(f.stored.begin(), f.stored.end(), swept_pair);
  });
}

std::vector<std::string> ExperimentConfig::result_family_names() const {
  std::vector<std::string> names;
  for (const FamilySpec& f : families) {
    if (!geometry_sweep) {
      names.push_back(f.name);
      continue;
    }
    for (double v : geometry_sweep->values)
      names.push_back(f.name + " " + geometry_sweep->parameter + "=" + round_trip(v));
  }
  return names;
}

}  // namespace gjklab::experiment
