#include "gjklab/simulation/scene_file.hpp"

#include "scene_meshes.hpp"
#include "scene_settings.hpp"
#include "scene_toml.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/cases/real_objects.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/geometry/shapes.hpp"

namespace gjklab::simulation {

namespace {

using experiment::ConfigError;

constexpr std::int64_t kMaxFrames = 100'000'000;
constexpr std::int64_t kMaxBodies = 100'000;
/// Tries per body of the random placement before the region is declared too full.
constexpr int kPlacementAttempts = 1000;
/// The shapes a [[bodies]] group may name (error messages): the scene's own, then the clouds
/// of the family registry it may draw (experiment::find_body_cloud).
const std::string& body_shapes() {
  static const std::string names = [] {
    std::string out = "box, cone, cylinder, uv_sphere, hull, mesh, real_object, ball, capsule";
    for (const experiment::ShapeGenerator& g : experiment::shape_generators())
      if (g.body_cloud) out += ", " + std::string(to_string(g.kind));
    return out;
  }();
  return names;
}

Quat rotation_of(const SceneTable& t) {
  if (!t.has("rotation")) return Quat::Identity();
  const auto q = t.numbers("rotation", 4);
  const Quat r(q[0], q[1], q[2], q[3]);
  if (!(r.norm() > 1e-12)) t.fail("rotation", "a quaternion (w, x, y, z) must not be zero");
  return r.normalized();
}

/// Scale factors of a unit demo shape: one number (uniform) or three.
Vec3 size_of(const SceneTable& t) {
  if (!t.has("size")) return Vec3::Ones();
  Vec3 s;
  if (t.raw().get("size")->is_array()) {
    s = t.vec3("size", Vec3::Ones());
  } else {
    const double u = t.number("size", 1, 0, 1e12);
    s = Vec3::Constant(u);
  }
  if (!(s.minCoeff() > 0)) t.fail("size", "every size must be positive");
  return s;
}

std::vector<Vec3> scaled(const Polytope& p, const Vec3& s) {
  std::vector<Vec3> out;
  for (const Vec3& v : p.vertices())
    out.push_back(v.cwiseProduct(s));
  return out;
}

std::vector<Vec3> hull_points(const SceneTable& t) {
  const toml::node* n = t.raw().get("points");
  const toml::array* a = n ? n->as_array() : nullptr;
  if (!a || a->empty()) t.fail("points", "expected an array of [x, y, z] points");
  std::vector<Vec3> out;
  for (const toml::node& p : *a) {
    const toml::array* xyz = p.as_array();
    if (!xyz) t.fail("points", "expected an array of [x, y, z] points");
    const auto v = t.numbers_of(*xyz, "points", 3);
    out.emplace_back(v[0], v[1], v[2]);
  }
  return out;
}

/// The cloud of a body or static shape, or a ConfigError naming the shape key.
std::vector<Vec3> cloud_of(const SceneTable& t, const std::string& shape) {
  const Vec3 s = size_of(t);
  if (shape == "box") return scaled(shapes::box(), s);
  if (shape == "hull") return hull_points(t);
  // Sphere-swept cores: a point (ball) and a segment of length `size` along x (capsule).
  if (shape == "ball") return {Vec3::Zero()};
  if (shape == "capsule") return {Vec3(-0.5 * s.x(), 0, 0), Vec3(0.5 * s.x(), 0, 0)};
  const auto v = static_cast<int>(t.integer("vertices",
                                            shape == "cone"       ? shapes::kDefaultConeVertices
                                            : shape == "cylinder" ? shapes::kDefaultCylinderVertices
                                                                  : shapes::kDefaultSphereVertices,
                                            4, 100000));
  try {
    if (shape == "cone") return scaled(shapes::cone(v), s);
    if (shape == "cylinder") return scaled(shapes::cylinder(v), s);
    if (shape == "uv_sphere") return scaled(shapes::uv_sphere(v), s);
  } catch (const std::invalid_argument& e) {
    t.fail("vertices", e.what());
  }
  t.fail("shape", "unknown shape '" + shape + "'; valid: " + body_shapes());
}

// ---- bodies from the experiment families ----

/// A generated cloud of the family shape: the experiments' unit cloud (within [-1, 1] of its
/// centre), halved so that `size` is its extent as for the demo shapes, and scaled by size.
std::vector<Vec3> family_cloud_points(const SceneTable& t, const experiment::ShapeGenerator& f,
                                      experiment::RandomStream& stream) {
  const int n = static_cast<int>(t.integer("vertices", 32, 1, 100000));
  const double aspect = t.number("aspect", 10, 1, 1e12);
  std::vector<Vec3> cloud = experiment::generate_shape(f.kind, n, stream, aspect);
  const Vec3 s = 0.5 * size_of(t);
  for (Vec3& v : cloud)
    v = v.cwiseProduct(s);
  return cloud;
}

/// The vertices of the files a `mesh` group or static names (mesh_paths), scaled by `size`.
std::vector<std::vector<Vec3>> read_meshes(const SceneTable& t) {
  std::vector<std::vector<Vec3>> meshes;
  const Vec3 s = size_of(t);
  for (const auto& file : mesh_paths(t)) {
    try {
      meshes.push_back(exact::read_mesh_vertices(file));
    } catch (const std::runtime_error& e) {
      t.fail("path", e.what());
    }
    for (Vec3& v : meshes.back())
      v = v.cwiseProduct(s);
  }
  return meshes;
}

/// The compounds of a `mesh` group or static with `decomposition` (none without it: the mesh
/// is then the hull of its vertices). The keys that only compounds take are refused elsewhere.
std::vector<std::shared_ptr<const scene::CompoundShape>> compounds_of(const SceneTable& t,
                                                                      const std::string& shape) {
  if (!t.has("decomposition")) {
    if (t.has("decomposition_options"))
      t.fail("decomposition_options", "needs a `decomposition` (hull, exact or approximate)");
    return {};
  }
  if (shape != "mesh")
    t.fail("decomposition", "only a shape = \"mesh\" of closed meshes has a decomposition");
  if (t.has("radius")) t.fail("radius", "a mesh made of pieces cannot be swept by a radius");
  return mesh_compounds(t, size_of(t));
}

/// The hulls of a `real_object` group (`objects`: "all" or a list of names, as in experiments;
/// body i takes object i mod count). A real object has unit radius: halved and scaled by
/// `size`, its extent is `size` as for the demo shapes.
std::vector<std::vector<Vec3>> read_real_objects(const SceneTable& t) {
  const toml::node* node = t.raw().get("objects");
  if (!node)
    t.fail("objects", "missing (shape = \"real_object\" needs \"all\" or a list of names)");
  std::vector<std::string> names;
  if (node->value<std::string>() == std::optional<std::string>("all")) {
    names = experiment::real_object_names();
  } else if (const toml::array* list = node->as_array()) {
    for (const toml::node& name : *list) {
      if (!name.is_string()) t.fail("objects", "expected \"all\" or an array of object names");
      names.push_back(*name.value<std::string>());
    }
  } else {
    t.fail("objects", "expected \"all\" or an array of object names");
  }
  if (names.empty()) t.fail("objects", "names no object");
  std::vector<std::vector<Vec3>> hulls;
  const Vec3 s = 0.5 * size_of(t);
  for (const std::string& name : names) {
    try {
      hulls.push_back(experiment::real_object(name));
    } catch (const experiment::RealObjectError& e) {
      t.fail("objects", e.what());
    }
    for (Vec3& v : hulls.back())
      v = v.cwiseProduct(s);
  }
  return hulls;
}

/// The swept radius of a group (length units): `radius`, by default 0.5 for a ball and 0.25
/// for a capsule (the demo shapes' half size and quarter size), 0 otherwise (no sweep).
double swept_radius_of(const SceneTable& t, const std::string& shape) {
  const double fallback = shape == "ball" ? 0.5 : shape == "capsule" ? 0.25 : 0.0;
  const double r = t.number("radius", fallback, 0, 1e12);
  if ((shape == "ball" || shape == "capsule") && !(r > 0))
    t.fail("radius", "a " + shape + " needs a radius > 0");
  return r;
}

/// Shapes by their points and swept radius, so that bodies of one cloud share one hull.
class ShapeCache {
 public:
  std::shared_ptr<const scene::ConvexShape> get(const SceneTable& t, std::string_view key,
                                                std::vector<Vec3> cloud, double radius = 0) {
    std::ostringstream k;
    k.precision(17);
    k << radius << ':';
    for (const Vec3& v : cloud)
      k << v.x() << ' ' << v.y() << ' ' << v.z() << ';';
    auto& slot = cache_[k.str()];
    if (!slot) {
      try {
        slot = radius > 0 ? scene::make_swept_shape(std::move(cloud), radius)
                          : scene::make_convex_shape(std::move(cloud));
      } catch (const std::invalid_argument& e) {
        t.fail(radius > 0 ? "radius" : key, e.what());
      }
    }
    return slot;
  }

 private:
  std::map<std::string, std::shared_ptr<const scene::ConvexShape>> cache_;
};

/// A funnel of `segments` static slabs: each a convex hull of 8 points between the cone of
/// inner radius bottom_radius (z = 0) … top_radius (z = height) and the same cone moved out by
/// `thickness` (length units), centred on `position`.
std::vector<std::vector<Vec3>> funnel_panels(const SceneTable& t) {
  const double r0 = t.number("bottom_radius", 1, 0, 1e12);
  const double r1 = t.number("top_radius", 3, 0, 1e12);
  const double h = t.number("height", 3, 1e-9, 1e12);
  const double th = t.number("thickness", 0.2, 1e-9, 1e12);
  const int n = static_cast<int>(t.integer("segments", 16, 3, 1024));
  std::vector<std::vector<Vec3>> out;
  for (int k = 0; k < n; ++k) {
    std::vector<Vec3> pts;
    for (int e = 0; e < 2; ++e) {
      const double a = 2 * M_PI * (k + e) / n;
      const Vec3 dir(std::cos(a), std::sin(a), 0);
      for (double r : {r0, r1})
        for (double off : {0.0, th})
          pts.push_back(dir * (r + off) + Vec3(0, 0, r == r0 ? 0 : h));
    }
    out.push_back(std::move(pts));
  }
  return out;
}

/// A body group's `shape`. `sphere` once named the UV-sphere polytope here while experiment
/// files call a sphere-swept point so: it still builds the polytope, with a warning.
std::string body_shape_name(const SceneTable& t, SceneSetup& s) {
  const std::string shape = t.string("shape", "");
  if (shape != "sphere") return shape;
  s.warnings.push_back(
      t.message("shape",
                "\"sphere\" is deprecated in scene files: it builds the UV-sphere polytope, "
                "now \"uv_sphere\"; a true sphere is \"ball\", as in experiment files"));
  return "uv_sphere";
}

/// The clouds of a static shape that is not made of pieces.
std::vector<std::vector<Vec3>> static_clouds(const SceneTable& t, const std::string& shape) {
  if (shape == "funnel") return funnel_panels(t);
  if (shape == "mesh") return read_meshes(t);  // every file of a folder at the same pose
  if (shape == "box" || shape == "hull") return {cloud_of(t, shape)};
  t.fail("shape", "unknown static shape '" + shape + "'; valid: box, hull, mesh, funnel");
}

void add_statics(const SceneTable& root, SceneSetup& s, ShapeCache& shapes) {
  for (const SceneTable& t : root.tables("static")) {
    t.allow_only({"shape", "size", "points", "path", "decomposition", "decomposition_options",
                  "position", "rotation", "friction", "restitution", "bottom_radius", "top_radius",
                  "height", "thickness", "segments"});
    const std::string shape = t.string("shape", "");
    if (shape.empty()) t.fail("shape", "missing (required): box, hull, mesh or funnel");
    const Vec3 position = t.vec3("position", Vec3::Zero());
    const Quat rotation = rotation_of(t);
    const Mat3 r = rotation.toRotationMatrix();
    // The shape's own origin (the cloud's, the mesh file's) goes to `position`: the centre of
    // mass sits where the shape put it relative to that origin.
    std::vector<scene::RigidBody> bodies;
    for (const auto& c : compounds_of(t, shape))  // a folder's files all at the same pose
      bodies.push_back(
          scene::make_static_body(c, rotation, position - r * c->envelope->input_origin));
    for (auto& cloud :
         bodies.empty() ? static_clouds(t, shape) : std::vector<std::vector<Vec3>>{}) {
      auto cs = shapes.get(t,
                           shape == "hull"   ? "points"
                           : shape == "mesh" ? "path"
                                             : "shape",
                           std::move(cloud));
      bodies.push_back(scene::make_static_body(cs, rotation, position - r * cs->input_origin));
    }
    for (scene::RigidBody& b : bodies) {
      b.friction = t.number("friction", 0.5, 0, 100);
      b.restitution = t.number("restitution", 0, 0, 1);
      s.world->add(b);
      s.shape_names.push_back(shape);
    }
  }
}

Quat random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  return Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
}

/// A placed body's bounding ball, for the random placement's overlap test.
struct Placed {
  Vec3 centre;
  double radius;
};

/// The box of a `random` placement: `region` = [[xmin, ymin, zmin], [xmax, ymax, zmax]].
std::pair<Vec3, Vec3> random_region(const SceneTable& t) {
  const toml::node* r = t.raw().get("region");
  const toml::array* a = r ? r->as_array() : nullptr;
  if (!a || a->size() != 2 || !a->get(0)->is_array() || !a->get(1)->is_array())
    t.fail("region", "expected [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
  const auto l = t.numbers_of(*a->get(0)->as_array(), "region", 3);
  const auto h = t.numbers_of(*a->get(1)->as_array(), "region", 3);
  const Vec3 lo(l[0], l[1], l[2]), hi(h[0], h[1], h[2]);
  if (!(lo.array() <= hi.array()).all())
    t.fail("region", "the lower corner must not exceed the upper");
  return {lo, hi};
}

/// A centre in [lo, hi] whose ball of `radius` overlaps no placed body's, drawn uniformly; a
/// ConfigError naming body i of count when kPlacementAttempts draws all overlap.
Vec3 free_centre(const SceneTable& t, const std::pair<Vec3, Vec3>& region, double radius,
                 const std::vector<Placed>& placed, std::mt19937_64& rng, std::int64_t i,
                 std::int64_t count) {
  std::uniform_real_distribution<double> u(0, 1);
  const auto& [lo, hi] = region;
  for (int attempt = 0; attempt < kPlacementAttempts; ++attempt) {
    const Vec3 centre = lo + (hi - lo).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    const bool free = std::none_of(placed.begin(), placed.end(), [&](const Placed& p) {
      return (p.centre - centre).norm() < p.radius + radius;
    });
    if (free) return centre;
  }
  t.fail("region", "cannot place body " + std::to_string(i + 1) + " of " + std::to_string(count) +
                       " without overlap: the region is too small");
}

/// Body i's centre in a `stack` (along z) or a `grid` (row × row layers) from `origin`.
Vec3 ordered_centre(bool stack, const Vec3& origin, double spacing, std::int64_t row,
                    std::int64_t i) {
  if (stack) return origin + Vec3(0, 0, spacing * static_cast<double>(i));
  const std::int64_t layer = i / (row * row), in = i % (row * row);
  return origin + spacing * Vec3(static_cast<double>(in % row), static_cast<double>(in / row),
                                 static_cast<double>(layer));
}

/// What a group's bodies read from files: the clouds of a `mesh` (its vertices' hull) or a
/// `real_object` group, or a `mesh` group's compounds (with `decomposition`); body i takes
/// entry i mod their number.
struct GroupFiles {
  std::vector<std::vector<Vec3>> clouds;
  std::vector<std::shared_ptr<const scene::CompoundShape>> compounds;
  const std::shared_ptr<const scene::CompoundShape>& compound(std::int64_t i) const {
    return compounds[static_cast<std::size_t>(i) % compounds.size()];
  }
};

GroupFiles group_files(const SceneTable& t, const std::string& shape) {
  GroupFiles f;
  f.compounds = compounds_of(t, shape);
  if (!f.compounds.empty()) return f;
  if (shape == "mesh") f.clouds = read_meshes(t);
  if (shape == "real_object") f.clouds = read_real_objects(t);
  return f;
}

void add_bodies(const SceneTable& root, SceneSetup& s, ShapeCache& shapes, std::mt19937_64& rng) {
  std::vector<Placed> placed;
  std::vector<double> sizes;
  std::size_t group = 0;
  for (const SceneTable& t : root.tables("bodies")) {
    t.allow_only({"shape",
                  "size",
                  "vertices",
                  "points",
                  "path",
                  "decomposition",
                  "decomposition_options",
                  "objects",
                  "radius",
                  "aspect",
                  "count",
                  "density",
                  "friction",
                  "restitution",
                  "placement",
                  "position",
                  "spacing",
                  "row",
                  "region",
                  "random_rotation",
                  "velocity"});
    const std::string shape = body_shape_name(t, s);
    if (shape.empty()) t.fail("shape", "missing (required): " + body_shapes());
    const double radius = swept_radius_of(t, shape);
    // Generated clouds: one per body, from the group's own generator; meshes and real
    // objects: body i takes file (object) i mod count; the other shapes: one hull for the group.
    const experiment::ShapeGenerator* generated = experiment::find_body_cloud(shape);
    // The group's own stream (the scene seed and the group's index alone), so adding a group
    // leaves the others' clouds and the placement stream as they were.
    const experiment::OwnedRandomStream rng_of_group =
        generated ? experiment::case_stream(s.seed, group) : nullptr;
    const GroupFiles files = group_files(t, shape);
    const auto& meshes = files.clouds;
    ++group;
    auto shape_of_body = [&](std::int64_t i) {
      if (!files.compounds.empty()) return files.compound(i)->envelope;
      if (generated)
        return shapes.get(t, "shape", family_cloud_points(t, *generated, *rng_of_group), radius);
      if (!meshes.empty())
        return shapes.get(t, shape == "mesh" ? "path" : "objects",
                          meshes[static_cast<std::size_t>(i) % meshes.size()], radius);
      return shapes.get(t, shape == "hull" ? "points" : "shape", cloud_of(t, shape), radius);
    };
    auto cs = shape_of_body(0);
    const auto count = t.integer("count", 1, 1, kMaxBodies);
    const double density = t.number("density", 1000, 1e-12, 1e12);
    const std::string placement = t.string("placement", "stack");
    const Vec3 origin = t.vec3("position", Vec3::Zero());
    const double spacing = t.number("spacing", cs->size, 1e-9, 1e12);
    const auto row = t.integer("row", 10, 1, kMaxBodies);
    const bool spin = t.boolean("random_rotation", false);
    std::pair<Vec3, Vec3> region;
    if (placement == "random")
      region = random_region(t);
    else if (placement != "stack" && placement != "grid")
      t.fail("placement", "unknown placement '" + placement + "'; valid: stack, grid, random");
    for (std::int64_t i = 0; i < count; ++i) {
      if (i > 0 && (generated || meshes.size() > 1 || files.compounds.size() > 1))
        cs = shape_of_body(i);
      const Vec3 centre = placement == "random"
                              ? free_centre(t, region, cs->radius, placed, rng, i, count)
                              : ordered_centre(placement == "stack", origin, spacing, row, i);
      const Quat q = spin ? random_rotation(rng) : Quat::Identity();
      scene::RigidBody b = files.compounds.empty()
                               ? scene::make_dynamic_body(cs, density, q, centre)
                               : scene::make_dynamic_body(files.compound(i), density, q, centre);
      b.friction = t.number("friction", 0.5, 0, 100);
      b.restitution = t.number("restitution", 0, 0, 1);
      b.velocity = t.vec3("velocity", Vec3::Zero());
      s.world->add(b);
      s.shape_names.push_back(shape);
      placed.push_back({centre, cs->radius});
      sizes.push_back(cs->size);
    }
  }
  if (sizes.empty())
    throw ConfigError(root.file(), root.line(), "bodies",
                      "a scene needs at least one [[bodies]] group");
  std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
  s.body_size = sizes[sizes.size() / 2];
}

}  // namespace

SceneSetup parse_scene(const std::string& text, const std::string& source) {
  const toml::table doc = experiment::parse_toml(text, source);
  const SceneTable root(source, doc, "");
  root.allow_only(
      {"scene", "physics", "broad_phase", "narrow_phase", "oracle", "static", "bodies"});
  SceneSetup s;
  s.text = text;
  const SceneTable sc = root.child("scene");
  sc.allow_only({"name", "seed", "frames", "pose_every", "contacts_every", "compare_broad_phases",
                 "queries_every"});
  s.name = sc.string("name", "scene");
  s.seed = static_cast<std::uint64_t>(sc.integer("seed", 1, 0, INT64_MAX));
  s.frames = sc.integer("frames", 600, 1, kMaxFrames);
  s.pose_every = sc.integer("pose_every", 10, 1, kMaxFrames);
  s.contacts_every = sc.integer("contacts_every", 10, 1, kMaxFrames);
  s.compare_broad_phases = sc.boolean("compare_broad_phases", false);
  s.queries_every = sc.integer("queries_every", 0, 0, kMaxFrames);
  const SceneTable oracle = root.child("oracle");
  oracle.allow_only({"audit_every", "depth"});
  s.audit_every = oracle.integer("audit_every", 0, 0, kMaxFrames);
  s.audit_depth = oracle.boolean("depth", false);
  scene::WorldSettings settings;
  read_settings(root, settings);
  s.world = std::make_unique<scene::World>(settings);
  ShapeCache shapes;
  std::mt19937_64 rng(s.seed);
  add_statics(root, s, shapes);
  add_bodies(root, s, shapes, rng);
  const auto& bodies = s.world->bodies();
  if (s.queries_every > 0 && std::any_of(bodies.begin(), bodies.end(),
                                         [](const auto& b) { return b.compound != nullptr; }))
    sc.fail("queries_every",
            "not available in a scene with mesh bodies made of pieces (`decomposition`): their "
            "queries are per piece pair, which queries/ and the stream family cannot name");
  return s;
}

SceneSetup load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path, 0, "", "cannot read the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), path);
}

}  // namespace gjklab::simulation
