// Scene bodies from the experiment families: sphere-swept shapes (mass properties against the
// textbook formulas, a ball and a capsule resting on the ground at their radius), hulls of
// generated point clouds (one cloud per body) and mesh files, their scene-file errors, and a
// scene of them whose recorded queries carry the radii into the stream family.
#include <unistd.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/scene_errors.hpp"
#include "gjklab/cli.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/cases/scene_stream.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/scene/body.hpp"
#include "gjklab/scene/world.hpp"
#include "gjklab/simulation/scene_file.hpp"

namespace fs = std::filesystem;
using namespace gjklab;
using gjklab::simulation::parse_scene;
using gjklab::experiment::ConfigError;

using gjklab::testing::run_cli;
const auto error_of = &gjklab::testing::scene_error_of;  // const: internal linkage

namespace {

std::vector<Vec3> cloud_of(const Polytope& p) {
  return {p.vertices().begin(), p.vertices().end()};
}

/// A scene source named as if it lay in tests/data, so that relative mesh paths resolve there.
std::string data_source() {
  return (fs::path(GJKLAB_TEST_DATA_DIR) / "scene.toml").string();
}

}  // namespace

TEST_CASE("scene: sphere-swept shapes' mass properties match the textbook ones", "[unit][scene]") {
  const double r = 0.3;
  // A ball (a swept point): exact volume by construction, I = 2/5 V r².
  const auto ball = scene::make_swept_shape({Vec3(1, 2, 3)}, r);
  CHECK(ball->volume == Approx(4.0 / 3.0 * M_PI * r * r * r).epsilon(1e-12));
  for (int k = 0; k < 3; ++k)
    CHECK(ball->unit_inertia(k, k) == Approx(0.4 * ball->volume * r * r).epsilon(0.02));
  CHECK(ball->polytope.size() == 1);
  CHECK(ball->polytope.vertices()[0].norm() < 1e-12);  // the centre of mass is the point
  CHECK(ball->swept_radius == r);
  CHECK(ball->radius == Approx(r));
  CHECK(ball->faces.empty());

  // A capsule (a swept segment of length L along x): V = π r² L + 4/3 π r³, and about its axis
  // I = π r⁴ L / 2 + 8/15 π r⁵.
  const double L = 1.0;
  const auto capsule = scene::make_swept_shape({Vec3(-L / 2, 0, 0), Vec3(L / 2, 0, 0)}, r);
  const double v_capsule = M_PI * r * r * L + 4.0 / 3.0 * M_PI * r * r * r;
  CHECK(capsule->volume == Approx(v_capsule).epsilon(0.015));
  CHECK(capsule->unit_inertia(0, 0) ==
        Approx(M_PI * std::pow(r, 4) * L / 2 + 8.0 / 15.0 * M_PI * std::pow(r, 5)).epsilon(0.03));
  CHECK(capsule->faces.empty());

  // A rounded cube of side a: V = a³ + 6a²r + 3πar² + 4/3πr³; it keeps the core's six faces.
  const double a = 1.0;
  const auto rounded = scene::make_swept_shape(cloud_of(shapes::box(Vec3(a, a, a))), r);
  CHECK(rounded->volume ==
        Approx(a * a * a + 6 * a * a * r + 3 * M_PI * a * r * r + 4.0 / 3.0 * M_PI * r * r * r)
            .epsilon(0.015));
  CHECK(rounded->faces.size() == 6);
  CHECK(rounded->face_normals.size() == 6);
  CHECK(rounded->size == Approx(std::sqrt(3.0) * (a + 2 * r)));

  CHECK_THROWS_AS(scene::make_swept_shape({Vec3::Zero()}, 0), std::invalid_argument);
  CHECK_THROWS_AS(scene::make_swept_shape({}, r), InvalidGeometry);
}

TEST_CASE("scene physics: a ball and a capsule come to rest on the ground at their radius",
          "[unit][scene]") {
  scene::WorldSettings settings;
  settings.dt = 1.0 / 120;
  scene::World world(settings);
  world.add(
      scene::make_static_body(scene::make_convex_shape(cloud_of(shapes::box(Vec3(10, 10, 1)))),
                              Quat::Identity(), Vec3(0, 0, -0.5)));
  const double r = 0.25;
  const auto ball = world.add(scene::make_dynamic_body(scene::make_swept_shape({Vec3::Zero()}, r),
                                                       500, Quat::Identity(), Vec3(-2, 0, 1)));
  const auto capsule = world.add(
      scene::make_dynamic_body(scene::make_swept_shape({Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0)}, r), 500,
                               Quat::Identity(), Vec3(2, 0, 1.5)));
  for (int frame = 0; frame < 360; ++frame)
    world.step();
  REQUIRE(world.finite());
  // Resting within the slop (and the last step's sub-millimetre settling), not sunk or floating.
  CHECK(world.bodies()[ball].pose.translation.z() == Approx(r).margin(3e-3));
  CHECK(world.bodies()[capsule].pose.translation.z() == Approx(r).margin(3e-3));
  // Nothing resists rolling (no rolling friction): only the vertical motion must have died out.
  CHECK(std::abs(world.bodies()[ball].velocity.z()) < 1e-3);
  CHECK(std::abs(world.bodies()[capsule].velocity.z()) < 1e-3);
  CHECK(world.max_penetration() < 0.01 * r);
}

TEST_CASE("scene files: bodies from generated clouds, meshes and sphere-swept shapes",
          "[unit][scene]") {
  const simulation::SceneSetup s = parse_scene(R"([scene]
seed = 3

[[bodies]]
shape = "ball_points"
vertices = 20
size = 0.6
count = 3
placement = "grid"
spacing = 2

[[bodies]]
shape = "mesh"
path = "meshes"
size = 0.5
count = 5
placement = "grid"
position = [0, 0, 4]
spacing = 3

[[bodies]]
shape = "capsule"
size = 0.5
radius = 0.1
count = 2
placement = "grid"
position = [0, 0, 8]

[[bodies]]
shape = "box"
radius = 0.05
placement = "grid"
position = [0, 0, 12]
)",
                                        data_source());
  const auto& bodies = s.world->bodies();
  REQUIRE(bodies.size() == 11);
  // Each body of a generated group has its own cloud of 20 points (its hull's vertices),
  // within half the size of its centre; the same seed gives the same clouds.
  std::set<const scene::ConvexShape*> clouds;
  for (int i = 0; i < 3; ++i) {
    clouds.insert(bodies[i].shape.get());
    CHECK(bodies[i].shape->polytope.size() <= 20);
    CHECK(bodies[i].shape->radius < 0.6);
    CHECK(s.shape_names[i] == "ball_points");
  }
  CHECK(clouds.size() == 3);
  const simulation::SceneSetup again = parse_scene(s.text, data_source());
  CHECK(again.world->bodies()[1].shape->polytope.vertices()[0] ==
        bodies[1].shape->polytope.vertices()[0]);
  // The four test meshes in name order (cube, octahedron, tetrahedron, wedge), then again.
  CHECK(bodies[3].shape->polytope.size() == 8);
  CHECK(bodies[4].shape->polytope.size() == 6);
  CHECK(bodies[5].shape->polytope.size() == 4);
  CHECK(bodies[6].shape->polytope.size() == 6);
  CHECK(bodies[7].shape == bodies[3].shape);
  CHECK(bodies[3].shape->volume == Approx(0.125));  // the unit cube at half size
  // Swept shapes: the capsules share one shape; mass from the swept volume.
  CHECK(bodies[8].shape == bodies[9].shape);
  CHECK(bodies[8].shape->swept_radius == 0.1);
  CHECK(bodies[8].mass ==
        Approx(1000 * (M_PI * 0.01 * 0.5 + 4.0 / 3.0 * M_PI * 0.001)).epsilon(0.015));
  CHECK(bodies[10].shape->swept_radius == 0.05);
  CHECK(bodies[10].shape->faces.size() == 6);
}

TEST_CASE("scene files: errors of the family bodies name file, line and key", "[unit][scene]") {
  CHECK(error_of("[[bodies]]\nshape = \"ball\"\nradius = -1\n")
            .find("bad.toml:3: key 'bodies[0].radius'") == 0);
  CHECK(error_of("[[bodies]]\nshape = \"ball\"\nradius = 0\n")
            .find("bad.toml:3: key 'bodies[0].radius': a ball needs a radius > 0") == 0);
  CHECK(error_of("[[bodies]]\nshape = \"mesh\"\n").find("key 'bodies[0].path': missing") !=
        std::string::npos);
  CHECK(error_of("[[bodies]]\nshape = \"mesh\"\npath = \"no/such/folder\"\n")
            .find("bad.toml:3: key 'bodies[0].path'") == 0);
  // A flat cloud needs a radius to have volume; with one it is a rounded disk.
  CHECK(error_of("[[bodies]]\nshape = \"flat_points\"\nvertices = 12\n")
            .find("bad.toml:2: key 'bodies[0].shape': the hull has no volume") == 0);
  CHECK(error_of("[[bodies]]\nshape = \"flat_points\"\nvertices = 12\nradius = 0.1\n").empty());
  CHECK(error_of("[[bodies]]\nshape = \"gaussian\"\nvertices = 0\n")
            .find("bad.toml:3: key 'bodies[0].vertices'") == 0);
  CHECK(error_of("[[bodies]]\nshape = \"teapot\"\n").find("valid: box, cone") != std::string::npos);
}

TEST_CASE("stream family: a scene's sphere-swept queries carry their radii", "[unit][scene]") {
  const fs::path dir =
      fs::temp_directory_path() / ("gjklab-scene-families-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "balls.toml") << R"([scene]
frames = 20
queries_every = 10

[[static]]
shape = "box"
size = [10, 10, 1]
position = [0, 0, -0.5]

[[bodies]]
shape = "ball"
radius = 0.3
count = 2
placement = "stack"
position = [0, 0, 0.3]
spacing = 0.6
)";
  std::string out, err;
  REQUIRE(run_cli({"simulate", (dir / "balls.toml").string(), "--out", (dir / "balls.h5").string()},
                  out, err) == 0);
  const auto pairs = experiment::read_scene_stream(dir / "balls.h5");
  REQUIRE(pairs.size() >= 4);  // ground-ball and ball-ball, in frames 10 and 20
  for (const auto& p : pairs) {
    INFO(p.id);
    CHECK(p.radius_b == 0.3);  // b is the later body: always a ball
    CHECK((p.radius_a == 0 || p.radius_a == 0.3));
    CHECK(p.b.size() == 1);
  }
  // Warm-started from the recorded simplices, on the cores: the scene's own iterations.
  std::ofstream(dir / "stream.toml")
      << "name = \"balls\"\nseed = 1\ncases = " << pairs.size()
      << "\n\n[[family]]\nshape = \"stream\"\npath = \"balls.h5\"\n\n"
      << "[[algorithm]]\nname = \"gjk-johnson\"\n\n"
      << "[[algorithm]]\nname = \"gjk-johnson\"\nlabel = \"warm\"\nwarm_start = true\n";
  REQUIRE(run_cli({"run", (dir / "stream.toml").string(), "--out", (dir / "stream.h5").string()},
                  out, err) == 0);
  const experiment::Archive run = experiment::read_archive(dir / "stream.h5");
  REQUIRE(run.results.size() == pairs.size());
  for (const auto& r : run.results) {
    REQUIRE(r.exact);
    // Two balls resting on each other and on the ground: in contact to within the slop.
    CHECK(std::abs(r.exact->distance) < 0.01);
    CHECK(r.algorithms[1].termination == Termination::converged);
  }
  fs::remove_all(dir);
}

TEST_CASE("scene files: bodies from real objects, body i taking object i mod count",
          "[unit][scene][real_object]") {
  const simulation::SceneSetup s = parse_scene(R"([[bodies]]
shape = "real_object"
objects = ["cow", "fandisk"]
size = 0.8
count = 3
placement = "grid"
spacing = 2
)",
                                        data_source());
  const auto& bodies = s.world->bodies();
  REQUIRE(bodies.size() == 3);
  CHECK(bodies[0].shape != bodies[1].shape);
  CHECK(bodies[2].shape == bodies[0].shape);
  for (const auto& b : bodies) {
    // Unit radius about the box centre, halved and scaled by size: every vertex within 0.4 of
    // that centre, so within 0.8 of the centroid (the body's origin); one vertex at 0.4 makes a
    // side of the box at least 0.8/√3, so some vertex is at least 0.23 from any point.
    CHECK(b.shape->radius <= 0.8);
    CHECK(b.shape->radius >= 0.23);
    CHECK(b.mass > 0);
  }
  CHECK(error_of("[[bodies]]\nshape = \"real_object\"\nobjects = [\"teapot-not-there\"]\n")
            .find("bad.toml:3: key 'bodies[0].objects'") == 0);
  CHECK(
      error_of("[[bodies]]\nshape = \"real_object\"\n").find("key 'bodies[0].objects': missing") !=
      std::string::npos);
  CHECK(error_of("[[bodies]]\nshape = \"real_object\"\nobjects = []\n")
            .find("bad.toml:3: key 'bodies[0].objects': names no object") == 0);
}

TEST_CASE(
    "scene files: any registered distance algorithm as the narrow phase, any depth "
    "algorithm for penetrating pairs",
    "[unit][scene]") {
  // A stack of three boxes on the ground, queried by a peer (cold) with gjklab's EPA from the
  // registry for depths: it stays at rest as with the built-in warm-started GJK and EPA.
  const std::string stack = R"([scene]
seed = 1
[[static]]
shape = "box"
size = [20, 20, 1]
position = [0, 0, -0.5]
[[bodies]]
shape = "box"
count = 3
placement = "stack"
position = [0, 0, 0.5]
)";
  for (const char* narrow :
       {"[narrow_phase]\nalgorithm = \"bullet-gjk\"\ndepth_algorithm = \"epa\"\n",
        "[narrow_phase]\nalgorithm = \"fcl-indep\"\n"}) {
    INFO(narrow);
    const simulation::SceneSetup s = parse_scene(stack + narrow, "peer.toml");
    REQUIRE(s.world->settings().query);
    CHECK_FALSE(s.world->settings().warm_start);
    double worst = 0;
    for (int frame = 0; frame < 240; ++frame) {
      s.world->step();
      worst = std::max(worst, s.world->max_penetration());
    }
    CHECK(worst < 0.01);  // m, boxes of 1 m
    CHECK(s.world->contacts().size() >= 12);
    for (const auto& b : s.world->bodies())
      CHECK(b.velocity.norm() < 0.05);
  }
  CHECK(error_of("[narrow_phase]\nalgorithm = \"gjk-bool\"\n")
            .find("key 'narrow_phase.algorithm': 'gjk-bool' answers no distance") !=
        std::string::npos);
  CHECK(error_of("[narrow_phase]\nalgorithm = \"no-such\"\n").find("unknown algorithm 'no-such'") !=
        std::string::npos);
  CHECK(error_of("[narrow_phase]\ndepth_algorithm = \"gjk-johnson\"\n")
            .find("'gjk-johnson' reports no penetration depth") != std::string::npos);
  CHECK(error_of("[narrow_phase]\nalgorithm = \"bullet-gjk\"\nwarm_start = true\n")
            .find("key 'narrow_phase.warm_start': 'bullet-gjk' cannot run warm-started") !=
        std::string::npos);
}

TEST_CASE("scene files: the narrow phase's and the depth algorithm's options", "[unit][scene]") {
  const std::string ball_on_ground = R"([scene]
seed = 1
[[static]]
shape = "box"
size = [20, 20, 1]
position = [0, 0, -0.5]
[[bodies]]
shape = "uv_sphere"
position = [0, 0, 0.45]
[narrow_phase]
algorithm = "gjk-nesterov"
)";
  // One iteration is too few for the accelerated GJK to converge: the step counts the stops.
  const simulation::SceneSetup limited =
      parse_scene(ball_on_ground + "[narrow_phase.options]\nmax_iterations = 1\n", "opt.toml");
  const simulation::SceneSetup plain = parse_scene(ball_on_ground, "opt.toml");
  CHECK(limited.world->step().failed_queries > 0);
  CHECK(plain.world->step().failed_queries == 0);
  CHECK(error_of(ball_on_ground + "[narrow_phase.options]\nno_such_key = 1\n")
            .find("key 'narrow_phase.options.no_such_key'") != std::string::npos);
  CHECK(error_of("[narrow_phase]\nalgorithm = \"gjk-johnson\"\n[narrow_phase.options]\n"
                 "max_iterations = 3\n")
            .find("key 'narrow_phase.options': only for an algorithm other than") !=
        std::string::npos);
  CHECK(error_of("[narrow_phase]\n[narrow_phase.depth_options]\nmax_iterations = 3\n")
            .find("key 'narrow_phase.depth_options': needs depth_algorithm") != std::string::npos);
}

TEST_CASE("scene files: a body group may draw every body cloud of the family registry",
          "[unit][scene]") {
  int body_clouds = 0;
  for (const experiment::ShapeGenerator& g : experiment::shape_generators()) {
    if (!g.body_cloud) continue;
    ++body_clouds;
    INFO(to_string(g.kind));
    CHECK(experiment::find_body_cloud(to_string(g.kind)) == &g);
    // A radius gives the flat and collinear clouds a volume.
    CHECK(error_of("[[bodies]]\nshape = \"" + std::string(to_string(g.kind)) +
                   "\"\nvertices = 12\nradius = 0.1\n")
              .empty());
  }
  CHECK(body_clouds == 9);
  // The scene builds its own demo shapes and swept shapes; the registry's are not bodies.
  for (const char* own : {"box", "cone", "cylinder", "uv_sphere", "sphere", "capsule"})
    CHECK(experiment::find_body_cloud(own) == nullptr);
  CHECK(error_of("[[bodies]]\nshape = \"teapot\"\n")
            .find("valid: box, cone, cylinder, uv_sphere, hull, mesh, real_object, ball, "
                  "capsule, sphere_points, ball_points, cube_points, gaussian, flat_points, "
                  "collinear_points, sliver, prism, pyramid") != std::string::npos);
}

TEST_CASE("scene files: the deprecated shape \"sphere\" builds the UV sphere, with a warning",
          "[unit][scene]") {
  // `sphere` names a sphere-swept point in experiment files; in scene files it meant the
  // UV-sphere polytope, and old files keep building that, told the new names.
  const std::string body = "[[bodies]]\nshape = \"%\"\nposition = [0, 0, 1]\n";
  auto with = [&](const std::string& shape) {
    std::string text = body;
    return text.replace(text.find('%'), 1, shape);
  };
  const simulation::SceneSetup old = simulation::parse_scene(with("sphere"), "old.toml");
  const simulation::SceneSetup now = simulation::parse_scene(with("uv_sphere"), "new.toml");
  REQUIRE(old.warnings.size() == 1);
  CHECK(old.warnings[0].find("old.toml:2: key 'bodies[0].shape': \"sphere\" is deprecated") !=
        std::string::npos);
  CHECK(now.warnings.empty());
  CHECK(old.shape_names == now.shape_names);
  CHECK(old.world->bodies()[0].shape->polytope.vertices().size() ==
        now.world->bodies()[0].shape->polytope.vertices().size());
  // In experiment files `ball` names the sphere-swept point that `sphere` names there.
  CHECK(experiment::find_shape_generator("ball") == experiment::find_shape_generator("sphere"));
  CHECK(experiment::find_shape_generator("ball") != nullptr);
}
