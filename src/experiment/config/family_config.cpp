// The [[family]] tables of experiment files (and [placement]): shapes, pair sources, contact
// types, vertex counts, radii and placements, read into FamilySpec.
#include "experiment/config/family_config.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <variant>

#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/cases/real_objects.hpp"
#include "gjklab/experiment/cases/scene_stream.hpp"

namespace gjklab::experiment {

namespace {

/// The largest sphere-swept radius (shape units), as the bound of `scale`.
constexpr double kMaxRadius = 1e100;
constexpr std::int64_t kMaxVertices = 10'000'000;
constexpr double kMinScale = 1e-100;  // keeps squared lengths far from underflow and overflow
constexpr double kMaxScale = 1e100;

constexpr ContactType kContactTypes[] = {
    ContactType::face_face,      ContactType::edge_edge,         ContactType::vertex_face,
    ContactType::edge_face,      ContactType::vertex_edge,       ContactType::vertex_vertex,
    ContactType::parallel_edges, ContactType::crossing_segments, ContactType::needle_point,
    ContactType::needle_segment, ContactType::thin_rods,         ContactType::crossing_wedges,
    ContactType::tilted_plates,
};

std::string shape_names() {
  std::vector<std::string_view> names;
  for (const FamilyShapeInfo& shape : family_shapes())
    names.push_back(shape.name);
  return join(names);
}

std::string contact_names() {
  return join(contact_choices());
}

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

}  // namespace

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

namespace {

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

/// The closed meshes of a `pair = "meshes"` family: those under `path`, or the packaged
/// non-convex ones; each at unit size, its file name in `objects`.
void read_closed_meshes(const Section& s, const std::string& experiment_file, FamilySpec& f) {
  const toml::node* node = s.find("path") ? s.find("path") : s.find("pair");
  std::vector<std::filesystem::path> files;
  try {
    if (const auto path = s.string("path")) {
      f.path = *path;
      std::filesystem::path resolved(*path);
      if (resolved.is_relative())
        resolved = std::filesystem::path(experiment_file).parent_path() / resolved;
      files = exact::mesh_files(resolved);
    } else {
      for (std::string_view name : kPackagedNonconvexMeshes)
        files.push_back(real_object_meshes() / name);
    }
    for (const auto& file : files) {
      f.closed_meshes.push_back(unit_size(exact::read_closed_mesh(file)));
      f.objects.push_back(file.filename().string());
    }
  } catch (const std::runtime_error& e) {
    s.fail(*node, s.find("path") ? "path" : "pair", e.what());
  }
}

/// `pair = "NAME"` of a nonconvex family (and `path` for pair = "meshes").
void read_nonconvex(const Section& s, const std::string& experiment_file, FamilySpec& f) {
  const auto pair = s.string("pair");
  if (!pair)
    s.missing("pair", "missing (shape = \"nonconvex\" needs one of: " +
                          names_list(kNonconvexPairNames) + ")");
  f.nonconvex = nonconvex_pair_from_string(*pair);
  if (!f.nonconvex)
    s.fail(*s.find("pair"), "pair",
           "unknown pair '" + *pair + "'; valid: " + names_list(kNonconvexPairNames));
  if (s.find("path") && *f.nonconvex != NonconvexPair::meshes)
    s.fail(*s.find("path"), "path", "applies only to pair = \"meshes\"");
  if (*f.nonconvex == NonconvexPair::meshes) read_closed_meshes(s, experiment_file, f);
  f.shape_a = f.shape_b = ShapeKind::mesh;
}

/// A nonconvex family builds and poses its pairs itself: the keys that draw or place convex
/// shapes do not apply.
void refuse_convex_draw_keys(const Section& s) {
  for (std::string_view key : {"vertices", "vertices_a", "vertices_b", "rotate", "aspect",
                               "scale_b", "offset", "radius", "radius_a", "radius_b", "placement"})
    if (s.find(key))
      s.fail(*s.find(key), key,
             "does not apply to shape = \"nonconvex\" (its pairs are built and posed by their "
             "kind; see docs/experiments.md)");
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
  if (const auto r = s.radius_interval("radius", kMaxRadius)) f.radius_a = f.radius_b = *r;
  if (const auto r = s.radius_interval("radius_a", kMaxRadius)) f.radius_a = *r;
  if (const auto r = s.radius_interval("radius_b", kMaxRadius)) f.radius_b = *r;
}

// ---- the form of a family ----
//
// What a [[family]] table describes, read from its `shape` key: generated shapes, or one of
// the pair sources that take keys of their own. Each form lists the keys that belong to it
// alone (own_keys), from which refuse_foreign_keys refuses those of every other form.

/// Generated shapes, both named by `shape` (or a `shape` that is not a string, which
/// read_shape reports).
struct NamedShape {
  static constexpr std::array<std::string_view, 0> own_keys{};
};
/// Generated shapes named by `shape_a` and `shape_b`: the form of a family without `shape`.
struct NamedShapePair {
  static constexpr std::array<std::string_view, 2> own_keys{"shape_a", "shape_b"};
};
/// `shape = "contact"`.
struct ContactPairs {
  static constexpr std::array<std::string_view, 2> own_keys{"contact", "angle"};
};
/// `shape = "file"` (a cases file) or `shape = "stream"` (a scene archive's queries).
struct StoredPairs {
  static constexpr std::array<std::string_view, 1> own_keys{"path"};
  bool stream = false;
};
/// `shape = "mesh"`.
struct MeshFiles {
  static constexpr std::array<std::string_view, 1> own_keys{"path"};
};
/// `shape = "real_object"`.
struct RealObjects {
  static constexpr std::array<std::string_view, 1> own_keys{"objects"};
};
/// `shape = "nonconvex"`.
struct NonconvexPairs {
  static constexpr std::array<std::string_view, 2> own_keys{"pair", "path"};
};

using FamilyForm = std::variant<NamedShape, NamedShapePair, ContactPairs, StoredPairs, MeshFiles,
                                RealObjects, NonconvexPairs>;

/// The keys some form owns, in the order they are checked, each with its refusal in the other
/// forms (which says where the key belongs).
struct OwnedKey {
  std::string_view key;
  std::string_view refusal;
};
constexpr OwnedKey kOwnedKeys[] = {
    {"objects", "applies only to shape = \"real_object\""},
    {"contact", "applies only to shape = \"contact\""},
    {"angle", "applies only to shape = \"contact\""},
    {"pair", "applies only to shape = \"nonconvex\""},
    {"path", "applies only to shape = \"file\", \"stream\", \"mesh\" or \"nonconvex\""},
    {"shape_a", "cannot be combined with 'shape' (which sets both shapes)"},
    {"shape_b", "cannot be combined with 'shape' (which sets both shapes)"},
};

/// Whether every key a form owns is listed in kOwnedKeys: one missing there would be accepted,
/// and ignored, by the other forms.
template <typename... Forms>
constexpr bool every_owned_key_listed(const std::variant<Forms...>*) {
  const auto listed = [](std::string_view key) {
    return std::ranges::any_of(kOwnedKeys, [&](const OwnedKey& owned) { return owned.key == key; });
  };
  return (std::ranges::all_of(Forms::own_keys, listed) && ...);
}
static_assert(every_owned_key_listed(static_cast<const FamilyForm*>(nullptr)));

/// The visitors of a form: one lambda per alternative.
template <typename... Lambdas>
struct Overloaded : Lambdas... {
  using Lambdas::operator()...;
};
template <typename... Lambdas>
Overloaded(Lambdas...) -> Overloaded<Lambdas...>;

/// The form that the table's `shape` names.
FamilyForm family_form(const Section& s) {
  const toml::node* shape = s.find("shape");
  if (!shape) return NamedShapePair{};
  if (!shape->is_string()) return NamedShape{};
  const std::string name = *s.string("shape");
  if (name == "contact") return ContactPairs{};
  if (name == "file" || name == "stream") return StoredPairs{.stream = name == "stream"};
  if (name == "mesh") return MeshFiles{};
  if (name == "real_object") return RealObjects{};
  if (name == "nonconvex") return NonconvexPairs{};
  return NamedShape{};
}

/// Whether `key` belongs to this form of family.
bool owns(const FamilyForm& form, std::string_view key) {
  return std::visit([&](const auto& f) { return std::ranges::count(f.own_keys, key) > 0; }, form);
}

/// Refuses the keys that belong to another form of family than this one.
void refuse_foreign_keys(const Section& s, const FamilyForm& form) {
  for (const OwnedKey& owned : kOwnedKeys)
    if (s.find(owned.key) && !owns(form, owned.key))
      s.fail(*s.find(owned.key), owned.key, std::string(owned.refusal));
}

/// Contact and file families give their pairs exactly (no radii).
bool exact_pairs(const FamilyForm& form) {
  return std::holds_alternative<ContactPairs>(form) || std::holds_alternative<StoredPairs>(form);
}

/// `shape_a` and `shape_b`: a family without `shape` needs both (with neither, the missing key
/// is `shape`).
void read_shape_pair(const Section& s, FamilySpec& f) {
  if (!s.find("shape_a") && !s.find("shape_b"))
    s.missing("shape", "missing (give 'shape', or both 'shape_a' and 'shape_b'); valid shapes: " +
                           shape_names());
  if (!s.find("shape_a")) s.missing("shape_a", "missing (shape_b is given without shape_a)");
  if (!s.find("shape_b")) s.missing("shape_b", "missing (shape_a is given without shape_b)");
  f.shape_a = read_shape(s, "shape_a");
  f.shape_b = read_shape(s, "shape_b");
}

/// The pair's source: the generated shapes (`shape`, or `shape_a` with `shape_b`), a contact
/// configuration, stored pairs, meshes or real objects.
void read_pair_source(const Section& s, const FamilyForm& form, const std::string& experiment_file,
                      FamilySpec& f) {
  std::visit(Overloaded{
                 [&](const NamedShape&) { f.shape_a = f.shape_b = read_shape(s, "shape"); },
                 [&](const NamedShapePair&) { read_shape_pair(s, f); },
                 [&](const ContactPairs&) { read_contact(s, f); },
                 [&](const StoredPairs& p) { read_stored_pairs(s, experiment_file, f, p.stream); },
                 [&](const MeshFiles&) { read_meshes(s, experiment_file, f); },
                 [&](const RealObjects&) { read_real_objects(s, f); },
                 [&](const NonconvexPairs&) { read_nonconvex(s, experiment_file, f); },
             },
             form);
}

/// `vertices` (both shapes), `vertices_a`, `vertices_b`; each shape's default otherwise.
void read_vertex_counts(const Section& s, FamilySpec& f) {
  f.vertices_a = default_vertices(f.shape_a);
  f.vertices_b = default_vertices(f.shape_b);
  for (std::string_view key : {"vertices_a", "vertices_b"})
    if (s.find("vertices") && s.find(key))
      s.fail(*s.find(key), key, "cannot be combined with 'vertices' (which sets both counts)");
  if (const auto v = s.count_interval("vertices", kMaxVertices)) f.vertices_a = f.vertices_b = *v;
  if (const auto v = s.count_interval("vertices_a", kMaxVertices)) f.vertices_a = *v;
  if (const auto v = s.count_interval("vertices_b", kMaxVertices)) f.vertices_b = *v;
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
  if (touching && (!std::holds_alternative<ContactPairs>(form) || !exact_contact(f.contact)))
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
  const auto generated_name = [&] {
    if (f.shape_a == f.shape_b) return std::string(to_string(f.shape_a));
    return std::string(to_string(f.shape_a)) + "/" + std::string(to_string(f.shape_b));
  };
  return std::visit(
      Overloaded{
          [&](const NamedShape&) { return generated_name(); },
          [&](const NamedShapePair&) { return generated_name(); },
          [&](const ContactPairs&) {
            return "contact-" + std::string(f.contact_any ? "any" : to_string(f.contact));
          },
          [&](const StoredPairs&) { return "file:" + f.path; },
          [&](const MeshFiles&) { return "mesh:" + f.path; },
          [&](const RealObjects&) {
            return std::string(s.find("objects")->is_string() ? "real_object:all" : "real_object");
          },
          [&](const NonconvexPairs&) { return std::string(to_string(*f.nonconvex)); },
      },
      form);
}

}  // namespace

FamilySpec read_family(const Section& s, const PlacementSpec& placement,
                       const std::string& experiment_file) {
  s.allow_only({"name",    "shape",  "shape_a", "shape_b",   "vertices", "vertices_a", "vertices_b",
                "scale",   "rotate", "weight",  "placement", "contact",  "angle",      "aspect",
                "scale_b", "offset", "path",    "radius",    "radius_a", "radius_b",   "objects",
                "pair"});
  const FamilyForm form = family_form(s);
  refuse_foreign_keys(s, form);
  if (std::holds_alternative<NonconvexPairs>(form)) refuse_convex_draw_keys(s);
  FamilySpec f;
  read_pair_source(s, form, experiment_file, f);
  read_vertex_counts(s, f);
  read_pair_draw(s, f);
  read_radii(s, exact_pairs(form), f);
  read_family_placement(s, form, placement, f);
  f.name = read_family_name(s, form, f);
  return f;
}

std::vector<std::string_view> contact_choices() {
  std::vector<std::string_view> names;
  for (ContactType c : kContactTypes)
    names.push_back(to_string(c));
  names.push_back("any");
  return names;
}

}  // namespace gjklab::experiment
