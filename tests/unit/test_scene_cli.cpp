// `gjklab simulate`: scene files with errors naming file, line and key; a small scene run to
// its archive; an existing archive kept without --force; the exact audit of a step's pairs;
// determinism whatever the file's comments; stopped and killed runs resumed.
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/scene_errors.hpp"
#include "gjklab/cli.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/simulation/scene_audit.hpp"
#include "gjklab/simulation/scene_file.hpp"

namespace fs = std::filesystem;
using gjklab::simulation::parse_scene;
using gjklab::experiment::ConfigError;

using gjklab::testing::run_cli;
const auto error_of = &gjklab::testing::scene_error_of;  // const: internal linkage

namespace {

const std::string kScene = R"([scene]
name = "tiny"
frames = 30
pose_every = 5
contacts_every = 5
compare_broad_phases = true

[physics]
dt = 0.01

[[static]]
shape = "box"
size = [10, 10, 1]
position = [0, 0, -0.5]

[[bodies]]
shape = "cone"
count = 3
placement = "stack"
position = [0, 0, 0.6]
spacing = 1.1
)";

}  // namespace

TEST_CASE("simulate: scene file errors name file, line and key", "[unit][scene]") {
  CHECK(error_of(kScene + "\n[[bodies]]\nshape = \"cone\"\ncount = -1\n")
            .find("bad.toml:25: key 'bodies[1].count'") == 0);
  CHECK(error_of("[scene]\nframes = 0\n[[bodies]]\nshape = \"box\"\n")
            .find("bad.toml:2: key 'scene.frames'") == 0);
  CHECK(error_of("[physics]\ndt = \"fast\"\n[[bodies]]\nshape = \"box\"\n")
            .find("bad.toml:2: key 'physics.dt': expected a number") == 0);
  CHECK(error_of("[narrow_phase]\nalgorithm = \"gjk-bool\"\n[[bodies]]\nshape = \"box\"\n")
            .find("bad.toml:2: key 'narrow_phase.algorithm'") == 0);
  CHECK(error_of("[broad_phase]\nkind = \"octree\"\n[[bodies]]\nshape = \"box\"\n")
            .find("bad.toml:2: key 'broad_phase.kind'") == 0);
  CHECK(error_of("[[bodies]]\nshape = \"hull\"\npoints = [[0,0,0],[1,0,0],[0,1,0]]\n")
            .find("bad.toml:3: key 'bodies[0].points': the hull has no volume") == 0);
  CHECK(error_of("[[bodies]]\nshape = \"box\"\nplacement = \"random\"\ncount = 50\n"
                 "region = [[0,0,0],[1,1,1]]\n")
            .find("key 'bodies[0].region': cannot place body 2 of 50") != std::string::npos);
  CHECK(error_of("[[bodies]]\nshape = \"teapot\"\n").find("bad.toml:2: key 'bodies[0].shape'") ==
        0);
  CHECK(error_of("[scene]\nspeed = 3\n[[bodies]]\nshape = \"box\"\n")
            .find("bad.toml:2: key 'scene.speed': unknown key") == 0);
  CHECK(error_of("[scene\n").find("bad.toml:1: TOML syntax error") == 0);
  CHECK(error_of("[oracle]\naudit_every = -1\n[[bodies]]\nshape = \"box\"\n")
            .find("bad.toml:2: key 'oracle.audit_every'") == 0);
  CHECK(error_of("[oracle]\nevery = 3\n[[bodies]]\nshape = \"box\"\n")
            .find("bad.toml:2: key 'oracle.every': unknown key") == 0);
  CHECK(error_of("[scene]\nname = \"x\"\n").find("a scene needs at least one [[bodies]]") !=
        std::string::npos);
}

TEST_CASE("simulate: a small scene runs to a complete archive", "[unit][scene]") {
  const fs::path dir =
      fs::temp_directory_path() / ("gjklab-scene-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string scene = (dir / "tiny.toml").string();
  const std::string archive = (dir / "tiny.h5").string();
  std::ofstream(scene) << kScene;
  std::string out, err;
  REQUIRE(run_cli({"simulate", scene, "--out", archive}, out, err) == 0);
  CHECK(out.find("scene tiny: 4 bodies, 30 frames") != std::string::npos);
  CHECK(fs::exists(archive));
  CHECK_FALSE(fs::exists(archive + ".tmp"));
  // Kept without --force; replaced with it.
  CHECK(run_cli({"simulate", scene, "--out", archive, "--frames", "5"}, out, err) == 1);
  CHECK(err.find("exists") != std::string::npos);
  CHECK(run_cli({"simulate", scene, "--out", archive, "--frames", "5", "--force"}, out, err) == 0);
  CHECK(out.find("5 frames") != std::string::npos);
  // A missing scene file is an error with its name, not a crash.
  CHECK(run_cli({"simulate", (dir / "none.toml").string()}, out, err) == 1);
  CHECK(err.find("none.toml") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("simulate: the audit answers a step's pairs exactly beside the narrow phase",
          "[unit][scene]") {
  using namespace gjklab;
  // Without gravity: a unit cube 1 cm above the ground and a second one beside it, 1 cm
  // inside the first and 1 cm above the ground too.
  scene::WorldSettings settings;
  settings.gravity = Vec3::Zero();
  scene::World world(settings);
  auto shape_of = [](const Polytope& p) {
    return scene::make_convex_shape({p.vertices().begin(), p.vertices().end()});
  };
  world.add(scene::make_static_body(shape_of(shapes::box(Vec3(40, 40, 1))), Quat::Identity(),
                                    Vec3(0, 0, -0.5)));
  const auto cube = shape_of(shapes::box());
  world.add(scene::make_dynamic_body(cube, 1000, Quat::Identity(), Vec3(0, 0, 0.51)));
  world.add(scene::make_dynamic_body(cube, 1000, Quat::Identity(), Vec3(0.99, 0, 0.51)));
  simulation::SceneAudit audit(true);
  experiment::SceneAuditRows rows;
  audit.before_step(world);
  world.step();
  audit.after_step(world, 1, rows);
  REQUIRE(rows.size() == 3);  // (ground, 1), (ground, 2), (1, 2)
  for (std::size_t k = 0; k < rows.size(); ++k) {
    CHECK(rows.frame[k] == 1);
    INFO("pair " << rows.a[k] << ", " << rows.b[k]);
    if (rows.a[k] == 0) {
      CHECK_FALSE(rows.intersect[k]);
      CHECK(rows.distance[k] == Approx(0.01).margin(1e-12));
      CHECK(std::isnan(rows.depth[k]));
      CHECK(rows.narrow_depth[k] == Approx(-0.01).margin(1e-9));  // a speculative contact
    } else {
      CHECK(rows.intersect[k]);
      CHECK(rows.distance[k] == 0);
      CHECK(rows.depth[k] == Approx(0.01).margin(1e-12));
      CHECK(rows.narrow_depth[k] == Approx(0.01).margin(1e-9));
    }
  }
}

TEST_CASE("simulate: a scene with an audit writes it", "[unit][scene]") {
  const fs::path dir =
      fs::temp_directory_path() / ("gjklab-scene-audit-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string scene = (dir / "audited.toml").string();
  const std::string archive = (dir / "audited.h5").string();
  std::ofstream(scene) << kScene << "\n[oracle]\naudit_every = 10\n";
  std::string out, err;
  REQUIRE(run_cli({"simulate", scene, "--out", archive}, out, err) == 0);
  // Frames 10, 20 and 30 of the cones falling onto the ground and each other: the pairs
  // near contact by then.
  const std::size_t at = out.find("audit: ");
  REQUIRE(at != std::string::npos);
  CHECK(std::stoi(out.substr(at + 7)) > 0);
  CHECK(fs::exists(archive));
  fs::remove_all(dir);
}

namespace {

/// A scene of UV spheres and boxes dropped on the ground: the spheres' hulls have nearly flat
/// quads, split by the hull into triangles whose rounded normals are bitwise equal.
const std::string kSphereScene = R"([scene]
name = "spheres"
seed = 4
frames = 40

[physics]
dt = 0.008333333333333333

[[static]]
shape = "box"
size = [20, 20, 1]
position = [0, 0, -0.5]

[[bodies]]
shape = "uv_sphere"
count = 12
placement = "random"
region = [[-3, -3, 0.8], [3, 3, 4]]
random_rotation = true

[[bodies]]
shape = "box"
count = 12
placement = "random"
region = [[-3, -3, 0.8], [3, 3, 4]]
random_rotation = true
)";

/// The scene built after `blocks` heap allocations of assorted sizes (kept alive meanwhile),
/// stepped `frames` times.
gjklab::simulation::SceneSetup stepped_after_allocations(const std::string& text, int blocks, int frames) {
  std::vector<std::unique_ptr<char[]>> held;
  for (int k = 0; k < blocks; ++k)
    held.emplace_back(std::make_unique<char[]>(16 + (k * 37 * (blocks % 7 + 3)) % 9000));
  gjklab::simulation::SceneSetup s = parse_scene(text, "spheres.toml");
  for (int f = 0; f < frames; ++f)
    s.world->step();
  return s;
}

}  // namespace

TEST_CASE("simulate: a comment in the scene file or the heap's history changes nothing",
          "[unit][scene][regression]") {
  // Adding a comment line to scene_demo.toml changed the simulation from frame 53 on: the
  // text's allocations moved CGAL's hull in memory, the hull listed a UV sphere's faces in
  // another order, and the sphere's centre of mass (a sum over its faces) changed in its last
  // bit. Every pose must be bit for bit the same whatever the file's comments and the heap.
  const auto first = stepped_after_allocations(kSphereScene, 0, 40);
  for (const auto& [text, blocks] :
       std::vector<std::pair<std::string, int>>{{"# a comment\n" + kSphereScene, 0},
                                                {kSphereScene, 150},
                                                {"# another\n# comment\n" + kSphereScene, 333}}) {
    INFO(blocks << " blocks held");
    const auto other = stepped_after_allocations(text, blocks, 40);
    const auto& a = first.world->bodies();
    const auto& b = other.world->bodies();
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      INFO("body " << i);
      CHECK(a[i].shape->input_origin == b[i].shape->input_origin);
      CHECK(a[i].pose.translation == b[i].pose.translation);
      CHECK(a[i].orientation.coeffs() == b[i].orientation.coeffs());
      CHECK(a[i].velocity == b[i].velocity);
      CHECK(a[i].angular_velocity == b[i].angular_velocity);
    }
  }
}

namespace {

/// The bytes of a numeric dataset in its native type (empty vector for an empty dataset).
std::vector<unsigned char> dataset_bytes(hid_t file, const std::string& name) {
  const hid_t ds = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  REQUIRE(ds >= 0);
  const hid_t type = H5Dget_type(ds);
  const hid_t native = H5Tget_native_type(type, H5T_DIR_ASCEND);
  const hid_t space = H5Dget_space(ds);
  std::vector<unsigned char> out(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)) *
                                 H5Tget_size(native));
  if (!out.empty()) REQUIRE(H5Dread(ds, native, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0);
  H5Sclose(space);
  H5Tclose(native);
  H5Tclose(type);
  H5Dclose(ds);
  return out;
}

/// Every dataset of two scene archives but the timings is bit for bit the same, and the second
/// is complete and has no state/ left.
void require_same_scene_archive(const std::string& x, const std::string& y) {
  const hid_t fx = H5Fopen(x.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t fy = H5Fopen(y.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(fx >= 0);
  REQUIRE(fy >= 0);
  const std::vector<std::string> names = {"frames/time",
                                          "frames/kinetic_energy",
                                          "frames/potential_energy",
                                          "frames/max_penetration",
                                          "frames/contacts",
                                          "frames/candidate_pairs",
                                          "frames/narrow_queries",
                                          "frames/epa_queries",
                                          "frames/failed_queries",
                                          "frames/iterations_mean",
                                          "frames/iterations_cold_mean",
                                          "frames/broad_phases_agree",
                                          "bodies/mass",
                                          "bodies/size",
                                          "bodies/is_static",
                                          "bodies/pose_frame",
                                          "bodies/pose_body",
                                          "bodies/position",
                                          "bodies/orientation",
                                          "bodies/velocity",
                                          "bodies/touching",
                                          "contacts/frame",
                                          "contacts/body_a",
                                          "contacts/body_b",
                                          "contacts/point",
                                          "contacts/normal",
                                          "contacts/depth",
                                          "contacts/normal_impulse",
                                          "audit/frame",
                                          "audit/body_a",
                                          "audit/body_b",
                                          "audit/intersect",
                                          "audit/certified",
                                          "audit/distance",
                                          "audit/depth",
                                          "audit/narrow_depth",
                                          "queries/frame",
                                          "queries/body_a",
                                          "queries/body_b",
                                          "queries/pose_a",
                                          "queries/pose_b",
                                          "queries/warm_size",
                                          "queries/warm_index_a",
                                          "queries/warm_index_b",
                                          "queries/iterations",
                                          "queries/intersect",
                                          "queries/distance",
                                          "shapes/vertices",
                                          "shapes/offset",
                                          "shapes/body_shape"};
  for (const std::string& n : names) {
    INFO(n);
    CHECK(dataset_bytes(fx, n) == dataset_bytes(fy, n));
  }
  CHECK(dataset_bytes(fy, "frames/sap_ns").size() == dataset_bytes(fx, "frames/sap_ns").size());
  CHECK(H5Lexists(fy, "state", H5P_DEFAULT) == 0);
  std::uint8_t complete = 0;
  const hid_t a = H5Aopen(fy, "complete", H5P_DEFAULT);
  REQUIRE(a >= 0);
  H5Aread(a, H5T_NATIVE_UINT8, &complete);
  H5Aclose(a);
  CHECK(complete == 1);
  H5Fclose(fx);
  H5Fclose(fy);
}

/// Runs `gjklab simulate` in a child process and stops it with `signal` once its first
/// checkpoint is on disk; returns the child's exit status (-1 if the signal killed it).
int simulate_until_signal(const std::vector<std::string>& args, const std::string& checkpoint,
                          int signal) {
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    std::string out, err;
    ::_exit(run_cli(args, out, err));
  }
  while (!fs::exists(checkpoint))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  ::kill(child, signal);
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("simulate: a stopped or killed run resumes into the uninterrupted run's archive",
          "[unit][scene]") {
  const fs::path dir =
      fs::temp_directory_path() / ("gjklab-scene-resume-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string scene = (dir / "tiny.toml").string();
  std::string text = kScene;
  // The recorded queries too (queries/ and shapes/), every 6th frame.
  text.insert(text.find("compare_broad_phases"), "queries_every = 6\n");
  std::ofstream(scene) << text << "\n[narrow_phase]\nmeasure_cold = true\n"
                       << "\n[oracle]\naudit_every = 7\n";
  const std::string full = (dir / "full.h5").string();
  std::string out, err;
  REQUIRE(run_cli({"simulate", scene, "--out", full}, out, err) == 0);

  SECTION("in parts: --stop-after, then --resume twice") {
    const std::string part = (dir / "part.h5").string();
    REQUIRE(run_cli({"simulate", scene, "--out", part, "--checkpoint", "4", "--stop-after", "11"},
                    out, err) == 0);
    CHECK(err.find("stopped after frame 11 of 30") != std::string::npos);
    CHECK(fs::exists(part + ".tmp"));
    CHECK_FALSE(fs::exists(part));
    REQUIRE(run_cli({"simulate", "--resume", part + ".tmp", "--stop-after", "9"}, out, err) == 0);
    CHECK(err.find("stopped after frame 20 of 30") != std::string::npos);
    REQUIRE(run_cli({"simulate", "--resume", part}, out, err) == 0);
    CHECK(out.find("scene tiny: 4 bodies, 30 frames") != std::string::npos);
    CHECK_FALSE(fs::exists(part + ".tmp"));
    require_same_scene_archive(full, part);
    // Nothing left to resume; --resume takes no other plan.
    CHECK(run_cli({"simulate", "--resume", part}, out, err) == 1);
    CHECK(run_cli({"simulate", scene, "--resume", part}, out, err) == 1);
  }
  SECTION("a checkpoint whose frames/ columns disagree is refused, naming the column") {
    const std::string part = (dir / "cut.h5").string();
    REQUIRE(run_cli({"simulate", scene, "--out", part, "--stop-after", "5"}, out, err) == 0);
    {
      // frames/kinetic_energy replaced by one value: 1 row where the group has 5.
      const hid_t file = H5Fopen((part + ".tmp").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      REQUIRE(file >= 0);
      REQUIRE(H5Ldelete(file, "frames/kinetic_energy", H5P_DEFAULT) >= 0);
      const hsize_t rows = 1;
      const hid_t space = H5Screate_simple(1, &rows, nullptr);
      const hid_t ds = H5Dcreate2(file, "frames/kinetic_energy", H5T_NATIVE_DOUBLE, space,
                                  H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      const double value = 0;
      REQUIRE(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value) >= 0);
      H5Dclose(ds);
      H5Sclose(space);
      H5Fclose(file);
    }
    CHECK(run_cli({"simulate", "--resume", part + ".tmp"}, out, err) == 1);
    CHECK(err.find("/frames/kinetic_energy has 1 rows where the group's other columns have 5") !=
          std::string::npos);
    CHECK_FALSE(fs::exists(part));
  }
  SECTION("SIGINT and SIGKILL on a long run, checkpoint every frame") {
    const std::string long_full = (dir / "long_full.h5").string();
    REQUIRE(run_cli({"simulate", scene, "--out", long_full, "--frames", "3000"}, out, err) == 0);
    for (int signal : {SIGINT, SIGKILL}) {
      INFO("signal " << signal);
      const std::string part = (dir / ("long_" + std::to_string(signal) + ".h5")).string();
      const int status = simulate_until_signal(
          {"simulate", scene, "--out", part, "--frames", "3000", "--checkpoint", "1"},
          part + ".tmp", signal);
      CHECK(status == (signal == SIGINT ? 130 : -1));
      CHECK_FALSE(fs::exists(part));
      REQUIRE(run_cli({"simulate", "--resume", part + ".tmp"}, out, err) == 0);
      require_same_scene_archive(long_full, part);
    }
  }
  fs::remove_all(dir);
}
