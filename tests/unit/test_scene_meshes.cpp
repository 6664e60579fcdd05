// Scene bodies made from closed non-convex meshes, simulated as compounds of their convex
// pieces: mass properties of the solid (against closed forms, whatever the pieces), a ball that
// comes to rest in an L's notch where the L's hull would hold it out, the scene-file keys and
// their errors, and a scene run's archive, audit and resume.
#include <unistd.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/experiment/archive/scene_archive.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/scene/compound.hpp"
#include "gjklab/scene/world.hpp"
#include "gjklab/simulation/scene_file.hpp"

namespace fs = std::filesystem;
using namespace gjklab;
using Catch::Matchers::Contains;
using gjklab::testing::run_cli;

namespace {

/// The corners of the axis-aligned box [lo, hi].
std::vector<Vec3> box_corners(const Vec3& lo, const Vec3& hi) {
  std::vector<Vec3> out;
  for (int k = 0; k < 8; ++k)
    out.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  return out;
}

/// Closed-form mass properties of a union of disjoint boxes (unit density): each box's own
/// inertia V(b² + c²)/12 … about its centre, moved to the union's centroid (parallel axes).
struct BoxUnion {
  double volume = 0;
  Vec3 centroid = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
};
BoxUnion box_union(const std::vector<std::pair<Vec3, Vec3>>& boxes) {
  BoxUnion u;
  for (const auto& [lo, hi] : boxes) {
    const Vec3 e = hi - lo;
    const double v = e.prod();
    u.volume += v;
    u.centroid += v * 0.5 * (lo + hi);
  }
  u.centroid /= u.volume;
  for (const auto& [lo, hi] : boxes) {
    const Vec3 e = hi - lo;
    const double v = e.prod();
    const Vec3 d = 0.5 * (lo + hi) - u.centroid;
    const Vec3 own = v / 12 *
                     Vec3(e.y() * e.y() + e.z() * e.z(), e.x() * e.x() + e.z() * e.z(),
                          e.x() * e.x() + e.y() * e.y());
    u.inertia +=
        Mat3(own.asDiagonal()) + v * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  return u;
}

/// The L of examples/l_prism.off: [0,2]×[0,1] and [0,1]×[1,2] in the plane, 0 ≤ z ≤ 1.
TriangleMesh l_prism() {
  const std::vector<PlanePoint> l{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  return prism_mesh(l, 0, 1);
}

void write_off(const TriangleMesh& mesh, const fs::path& file) {
  std::ofstream out(file);
  out.precision(17);
  out << "OFF\n" << mesh.vertices.size() << ' ' << mesh.faces.size() << " 0\n";
  for (const Vec3& v : mesh.vertices)
    out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const MeshFace& f : mesh.faces)
    out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
}

/// A scratch folder for this process's files.
fs::path scratch() {
  const fs::path dir =
      fs::temp_directory_path() / ("gjklab-scene-meshes-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST_CASE("scene meshes: a compound's mass properties are its solid's, not its pieces'",
          "[unit][scene]") {
  SECTION("an L prism, given overlapping pieces") {
    // Two pieces overlapping in [0,1]²: their volumes sum to 4, the solid's is 3.
    const auto c = scene::make_compound_shape(
        l_prism(),
        {box_corners(Vec3(0, 0, 0), Vec3(2, 1, 1)), box_corners(Vec3(0, 0, 0), Vec3(1, 2, 1))});
    const BoxUnion l = box_union({{Vec3(0, 0, 0), Vec3(2, 1, 1)}, {Vec3(0, 1, 0), Vec3(1, 2, 1)}});
    CHECK(c->pieces.size() == 2);
    CHECK(c->pieces[0].volume + c->pieces[1].volume == Approx(4));
    CHECK(c->envelope->volume == Approx(3).epsilon(1e-14));
    CHECK((-c->envelope->input_origin - l.centroid).norm() < 1e-14);
    CHECK((c->envelope->unit_inertia - l.inertia).norm() < 1e-13);
    CHECK(l.inertia(0, 1) != 0);  // the L's product of inertia: a real check of the off-diagonal
    // The pieces are in the body frame: the solid's centroid at the origin.
    CHECK(c->pieces[0].polytope.box_lower().isApprox(-l.centroid, 1e-14));
    CHECK(c->pieces[1].polytope.box_upper().isApprox(Vec3(1, 2, 1) - l.centroid, 1e-14));
    // The envelope is the hull of everything (the notch's inner corner is not on it).
    CHECK(c->envelope->polytope.size() == 10);
  }
  SECTION("a box, against V(b² + c²)/12 …") {
    const std::vector<PlanePoint> rect{{0, 0}, {2, 0}, {2, 3}, {0, 3}};
    const TriangleMesh box = prism_mesh(rect, 1, 1.5);
    const auto c = scene::make_compound_shape(box, {box.vertices});
    const BoxUnion b = box_union({{Vec3(0, 0, 1), Vec3(2, 3, 1.5)}});
    CHECK(c->envelope->volume == Approx(3).epsilon(1e-14));
    CHECK((-c->envelope->input_origin - Vec3(1, 1.5, 1.25)).norm() < 1e-14);
    CHECK(c->envelope->unit_inertia.isApprox(b.inertia, 1e-13));
    CHECK(c->envelope->unit_inertia(0, 0) == Approx(3.0 / 12 * (9 + 0.25)));
    // A dynamic body of density 10 weighs 30 and carries that inertia.
    const scene::RigidBody body = scene::make_dynamic_body(c, 10, Quat::Identity(), Vec3::Zero());
    CHECK(body.mass == Approx(30));
    CHECK(body.compound == c);
    CHECK(body.shape == c->envelope);
    CHECK((body.inverse_inertia_body.inverse() - 10 * b.inertia).norm() < 1e-11);
  }
  SECTION("refusals") {
    CHECK_THROWS_AS(scene::make_compound_shape(l_prism(), {}), std::invalid_argument);
    CHECK_THROWS_WITH(
        scene::make_compound_shape(l_prism(), {box_corners(Vec3(0, 0, 0), Vec3(2, 1, 1)),
                                               {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}}),
        Contains("piece 1 is not a polyhedron or a polygon"));
    // A flat piece (an approximate decomposition's cluster of coplanar triangles) is a polygon
    // of two sides.
    const auto flat = scene::make_compound_shape(
        l_prism(), {box_corners(Vec3(0, 0, 0), Vec3(2, 1, 1)),
                    {Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(1, 2, 0), Vec3(0, 2, 0)}});
    CHECK(flat->pieces[1].faces.size() == 2);
    CHECK(flat->pieces[1].face_normals.size() == 2);
    CHECK(flat->envelope->volume == Approx(3));
    TriangleMesh inverted = l_prism();
    for (MeshFace& f : inverted.faces)
      std::swap(f[1], f[2]);
    CHECK_THROWS_AS(scene::make_compound_shape(inverted, {inverted.vertices}), InvalidGeometry);
  }
}

namespace {

/// Where a ball dropped over the notch of an L standing on the ground comes to rest, with the
/// L made of the pieces of `decomposition`. The L (a 3 × 3 m polygon of 0.5 m thick legs,
/// 1 m deep) stands in the xz plane: its floor along x, its wall at x ∈ [0, 0.5]; the notch is
/// x, z > 0.5, under the hull's slanted face x + z = 3.5. The ball (radius 0.25 m) is dropped
/// at x = 1.2, over the notch. Returns the ball's final centre in the L's mesh frame.
Vec3 ball_in_l(const std::string& decomposition, bool& l_upright, double& ball_speed) {
  const std::vector<PlanePoint> l{{0, 0}, {3, 0}, {3, 0.5}, {0.5, 0.5}, {0.5, 3}, {0, 3}};
  const TriangleMesh mesh = prism_mesh(l, -0.5, 0.5);
  exact::validate_closed_mesh(mesh, "the L");
  const auto& d = experiment::decomposition_named(decomposition);
  const auto compound = scene::make_compound_shape(mesh, d.decompose(mesh, "the L", {}).pieces);
  scene::World world{scene::WorldSettings{}};
  const Polytope ground = shapes::box(Vec3(40, 40, 1));  // top face z = 0
  world.add(scene::make_static_body(
      scene::make_convex_shape({ground.vertices().begin(), ground.vertices().end()}),
      Quat::Identity(), Vec3(0, 0, -0.5)));
  // Mesh y up: a quarter turn about x takes the mesh frame's (x, y, z) to the world's (x, −z, y).
  const Quat up(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
  const std::uint32_t li = world.add(
      scene::make_dynamic_body(compound, 500, up, -(up * compound->envelope->input_origin)));
  const std::uint32_t bi = world.add(scene::make_dynamic_body(
      scene::make_swept_shape({Vec3::Zero()}, 0.25), 500, Quat::Identity(), Vec3(1.2, 0, 4)));
  for (int step = 0; step < 360; ++step)  // 3 s
    world.step();
  const scene::RigidBody& lb = world.bodies()[li];
  const scene::RigidBody& ball = world.bodies()[bi];
  l_upright = lb.orientation.angularDistance(up) < 0.05;
  ball_speed = ball.velocity.norm();
  // World → the L's body frame → its mesh frame.
  return lb.pose.rotation.transpose() * (ball.pose.translation - lb.pose.translation) -
         compound->envelope->input_origin;
}

}  // namespace

TEST_CASE("scene meshes: a ball rests in an L's notch, where the L's hull would not let it",
          "[unit][scene]") {
  bool upright = false;
  double speed = 1;
  // The notch of the mesh frame is x, y > 0.5 (y: the mesh's height) below x + y = 3.5.
  const Vec3 exact = ball_in_l("exact", upright, speed);
  INFO("ball at " << exact.transpose() << " in the L's mesh frame");
  CHECK(upright);
  CHECK(speed < 0.05);
  CHECK(exact.y() == Approx(0.75).margin(0.02));  // on the floor (0.5) at its radius
  CHECK(exact.x() > 0.75 - 0.02);                 // beside the wall, not in it
  CHECK(exact.x() + exact.y() < 3.5 - 0.25);      // inside the hull: only the pieces allow it

  // With the hull as its only piece the L holds the ball out of its notch.
  const Vec3 hull = ball_in_l("hull", upright, speed);
  INFO("with the hull: ball at " << hull.transpose());
  const bool in_hull = hull.x() > 0 && hull.x() < 3 && hull.y() > 0 && hull.x() + hull.y() < 3.5;
  CHECK_FALSE(in_hull);
}

namespace {

/// A scene file of a ground, a static L and a group of dynamic L's, with a ball dropped into
/// each notch, reading the example mesh `path` (relative to the scene file) with `extra` keys
/// in the group.
std::string l_scene(const std::string& path, const std::string& extra = "") {
  return "[scene]\nname = \"ls\"\nframes = 120\npose_every = 5\ncontacts_every = 5\n"
         "[oracle]\naudit_every = 30\ndepth = true\n"
         "[[static]]\nshape = \"box\"\nsize = [20, 20, 1]\nposition = [0, 0, -0.5]\n"
         "[[static]]\nshape = \"mesh\"\npath = \"" +
         path +
         "\"\ndecomposition = \"exact\"\nposition = [-4, 0, 0]\n"
         "[[bodies]]\nshape = \"mesh\"\npath = \"" +
         path + "\"\ndecomposition = \"exact\"\n" + extra +
         "count = 2\ndensity = 500\nplacement = \"grid\"\nposition = [0, 0, 0.6]\nspacing = 3\n"
         "[[bodies]]\nshape = \"ball\"\nradius = 0.2\ncount = 2\nplacement = \"grid\"\n"
         "position = [0.667, 0.667, 2]\nspacing = 3\n";
}

std::string examples_source() {
  return (fs::path(GJKLAB_TESTS_DIR).parent_path() / "examples" / "scene.toml").string();
}

}  // namespace

TEST_CASE("scene meshes: scene files build mesh bodies of pieces", "[unit][scene]") {
  const simulation::SceneSetup s =
      simulation::parse_scene(l_scene("l_prism.off"), examples_source());
  const auto& bodies = s.world->bodies();
  REQUIRE(bodies.size() == 6);
  CHECK(s.shape_names == std::vector<std::string>{"box", "mesh", "mesh", "mesh", "ball", "ball"});
  CHECK(bodies[0].compound == nullptr);
  for (std::size_t i : {1, 2, 3}) {
    REQUIRE(bodies[i].compound != nullptr);
    CHECK(bodies[i].compound->pieces.size() >= 2);  // the L's exact decomposition
  }
  CHECK(bodies[1].is_static());
  // The static L's file origin sits at `position`: its centre of mass at (−4, 0, 0) + centroid.
  CHECK(bodies[1].pose.translation.isApprox(Vec3(-4 + 2.5 / 3, 2.5 / 3, 0.5), 1e-12));
  CHECK(bodies[2].mass == Approx(500 * 3.0));       // the solid's volume, 3 m³
  CHECK(bodies[2].compound == bodies[3].compound);  // one file: one compound for the group
  CHECK(bodies[4].compound == nullptr);

  // `size` scales the mesh before it is decomposed: 8 times the volume at size 2.
  const simulation::SceneSetup big =
      simulation::parse_scene(l_scene("l_prism.off", "size = 2\n"), examples_source());
  CHECK(big.world->bodies()[2].mass == Approx(500 * 24.0));
  // Without `decomposition` a mesh is its vertices' hull, as before: 3.5 m³ for the L.
  std::string hull_text = l_scene("l_prism.off");
  hull_text.erase(hull_text.rfind("decomposition = \"exact\"\n"), 24);
  const simulation::SceneSetup hull = simulation::parse_scene(hull_text, examples_source());
  CHECK(hull.world->bodies()[2].compound == nullptr);
  CHECK(hull.world->bodies()[2].mass == Approx(500 * 3.5));
}

TEST_CASE("scene meshes: bad mesh bodies are ConfigErrors naming the key and the file",
          "[unit][scene]") {
  const fs::path dir = scratch();
  const std::string data = GJKLAB_TEST_DATA_DIR;
  auto error_in = [&](const std::string& text) {
    try {
      simulation::parse_scene(text, (dir / "bad.toml").string());
    } catch (const experiment::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  auto mesh_group = [](const std::string& path, const std::string& keys) {
    return "[[bodies]]\nshape = \"mesh\"\npath = \"" + path + "\"\n" + keys;
  };
  const std::string exact = "decomposition = \"exact\"\n";
  CHECK_THAT(error_in(mesh_group("missing.off", exact)),
             Contains("bad.toml:3: key 'bodies[0].path'") && Contains("missing.off"));
  for (const char* bad : {"open_box.off", "box_inverted.off", "two_tetrahedra.off"}) {
    INFO(bad);
    CHECK_THAT(error_in(mesh_group(data + "/meshes_bad/" + bad, exact)),
               Contains("bad.toml:3: key 'bodies[0].path'") && Contains(bad));
  }
  const std::string box = data + "/meshes_closed/box.off";
  CHECK_THAT(error_in(mesh_group(box, "decomposition = \"magic\"\n")),
             Contains("bad.toml:4: key 'bodies[0].decomposition': unknown decomposition 'magic'"));
  CHECK_THAT(
      error_in(mesh_group(box, exact + "decomposition_options = { concavity = 1 }\n")),
      Contains("key 'bodies[0].decomposition_options.concavity'") && Contains("takes no option"));
  const auto& names = experiment::decomposition_names();
  if (names.find("approximate") != std::string::npos) {
    CHECK_THAT(error_in(mesh_group(box,
                                   "decomposition = \"approximate\"\n"
                                   "decomposition_options = { concavity = -1 }\n")),
               Contains("bad.toml:5: key 'bodies[0].decomposition_options.concavity'"));
    CHECK_THAT(error_in(mesh_group(box,
                                   "decomposition = \"approximate\"\n"
                                   "decomposition_options = { concavity = \"high\" }\n")),
               Contains("key 'bodies[0].decomposition_options.concavity'") &&
                   Contains("expected an integer, a number or true/false"));
  }
  CHECK_THAT(error_in(mesh_group(box, "decomposition_options = { concavity = 1 }\n")),
             Contains("key 'bodies[0].decomposition_options': needs a `decomposition`"));
  CHECK_THAT(error_in("[[bodies]]\nshape = \"box\"\n" + exact),
             Contains("key 'bodies[0].decomposition': only a shape = \"mesh\""));
  CHECK_THAT(error_in(mesh_group(box, exact + "radius = 0.1\n")),
             Contains("key 'bodies[0].radius'"));
  // A decomposition that fails: the exact one takes at most 2 000 faces (this star has 3 120).
  const fs::path star = dir / "star.off";
  write_off(star_mesh(40, 40, [](const Vec3& u) { return 1 + 0.3 * u.z() * u.z(); }), star);
  CHECK_THAT(error_in(mesh_group(star.string(), exact)),
             Contains("bad.toml:4: key 'bodies[0].decomposition'") && Contains(star.string()) &&
                 Contains("more than the 2000 it accepts"));
  // The recorded query stream names bodies, not pieces.
  CHECK_THAT(error_in("[scene]\nqueries_every = 5\n" + mesh_group(box, exact)),
             Contains("bad.toml:2: key 'scene.queries_every': not available in a scene with mesh "
                      "bodies made of pieces"));
  // Static containers take the same keys and give the same errors.
  CHECK_THAT(error_in("[[static]]\nshape = \"mesh\"\npath = \"" + box +
                      "\"\ndecomposition = \"none\"\n[[bodies]]\nshape = \"box\"\n"),
             Contains("bad.toml:4: key 'static[0].decomposition': unknown decomposition 'none'"));
  fs::remove_all(dir);
}

TEST_CASE("scene meshes: a run records mesh bodies, audits their piece pairs and resumes",
          "[unit][scene]") {
  const fs::path dir = scratch();
  const std::string scene = (dir / "ls.toml").string();
  const std::string mesh =
      (fs::path(GJKLAB_TESTS_DIR).parent_path() / "examples" / "l_prism.off").string();
  std::ofstream(scene) << l_scene(mesh);
  const std::string full = (dir / "full.h5").string();
  std::string out, err;
  REQUIRE(run_cli({"simulate", scene, "--out", full}, out, err) == 0);
  const experiment::SceneArchive a = experiment::read_scene_archive(full);
  CHECK(a.bodies.shape == std::vector<std::string>{"box", "mesh", "mesh", "mesh", "ball", "ball"});
  CHECK(a.bodies.mass[2] == Approx(1500));
  // The audit. At frame 60 the first ball is halfway down its L's notch, its centre on the face
  // of the L's hull (x + y = 3 in the mesh frame): the hull would meet it, the pieces do not.
  REQUIRE(!a.audit.frame.empty());
  bool found = false;
  for (std::size_t k = 0; k < a.audit.frame.size(); ++k) {
    CHECK(std::isfinite(a.audit.distance[k]));
    if (a.audit.frame[k] != 60 || a.audit.a[k] != 2 || a.audit.b[k] != 4) continue;
    found = true;
    CHECK(a.audit.intersect[k] == 0);
    CHECK(a.audit.distance[k] > 0.2);  // about 0.3 m: the notch's half width less the radius
    CHECK(a.audit.certified[k] == 1);
  }
  CHECK(found);
  for (std::size_t k = 0; k < a.poses.frame.size(); ++k)
    if (a.poses.frame[k] == 60 && a.poses.body[k] == 4)
      CHECK(a.poses.position[3 * k + 2] < 1.0);  // below the L's top face (z ≈ 1.0)
  // At the end the balls rest on the ground inside the notches.
  const std::size_t n = a.poses.frame.size();
  for (std::size_t k = n - 4; k < n; ++k)
    if (a.poses.body[k] >= 4) CHECK(a.poses.position[3 * k + 2] == Approx(0.2).margin(0.01));

  // Stopped and resumed, the run writes the same poses and contacts (compound pairs carry their
  // contact points and impulses, and no simplex).
  const std::string part = (dir / "part.h5").string();
  REQUIRE(run_cli({"simulate", scene, "--out", part, "--checkpoint", "7", "--stop-after", "31"},
                  out, err) == 0);
  REQUIRE(run_cli({"simulate", "--resume", part + ".tmp"}, out, err) == 0);
  const experiment::SceneArchive b = experiment::read_scene_archive(part);
  CHECK(b.poses.position == a.poses.position);
  CHECK(b.poses.velocity == a.poses.velocity);
  CHECK(b.contacts.point == a.contacts.point);
  CHECK(b.contacts.normal_impulse == a.contacts.normal_impulse);
  CHECK(b.audit.distance == a.audit.distance);
  fs::remove_all(dir);
}
