// Scene layer: mass properties from the hull's tetrahedra, and the broad phases (and Bullet's
// dbvt, when built in) against the all-pairs reference on random, dense and irregular scenes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "gjklab/geometry/shapes.hpp"
#include "gjklab/peers/bullet_broadphase.hpp"
#include "gjklab/scene/body.hpp"
#include "gjklab/scene/broadphase.hpp"

using namespace gjklab;
using namespace gjklab::scene;

namespace {

std::vector<Vec3> cloud_of(const Polytope& p) {
  return {p.vertices().begin(), p.vertices().end()};
}

}  // namespace

TEST_CASE("scene: a box's mass properties are the textbook ones", "[unit][scene]") {
  const Vec3 e(2, 1, 0.5);
  std::vector<Vec3> cloud = cloud_of(shapes::box(e));
  for (Vec3& v : cloud)
    v += Vec3(3, -1, 7);  // off-centre: the centroid must be found
  const auto shape = make_convex_shape(cloud);
  CHECK(shape->volume == Approx(1.0));
  CHECK((-shape->input_origin - Vec3(3, -1, 7)).norm() < 1e-12);
  // I = V/12 · diag(b² + c², a² + c², a² + b²) for unit density.
  CHECK(shape->unit_inertia(0, 0) == Approx((1 + 0.25) / 12));
  CHECK(shape->unit_inertia(1, 1) == Approx((4 + 0.25) / 12));
  CHECK(shape->unit_inertia(2, 2) == Approx((4 + 1) / 12.0));
  CHECK(std::abs(shape->unit_inertia(0, 1)) < 1e-12);
  CHECK(shape->faces.size() == 6);
  CHECK(shape->polytope.vertex_mean().norm() < 1e-12);
}

TEST_CASE("scene: a cylinder's and a tetrahedron's mass properties", "[unit][scene]") {
  // A 64-gon prism of radius 0.5, height 1: volume n/2 r² sin(2π/n) h, Izz = V r_eff²/2 with
  // the polygon's polar moment; compare with the circle's within the polygon's 0.2 % deficit.
  const auto cyl = make_convex_shape(cloud_of(shapes::cylinder(64)));
  const double n = 32, r = 0.5;
  const double volume = n / 2 * r * r * std::sin(2 * M_PI / n);
  CHECK(cyl->volume == Approx(volume).epsilon(1e-12));
  CHECK(cyl->unit_inertia(2, 2) == Approx(M_PI * r * r * r * r / 2).epsilon(0.02));
  CHECK(cyl->unit_inertia(0, 0) == Approx(cyl->unit_inertia(1, 1)).epsilon(1e-9));
  // The unit right tetrahedron: V = 1/6, centroid (1/4, 1/4, 1/4), Ixx about the centroid 1/80.
  const auto tet = make_convex_shape({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
  CHECK(tet->volume == Approx(1.0 / 6));
  CHECK((tet->input_origin + Vec3(0.25, 0.25, 0.25)).norm() < 1e-12);
  CHECK(tet->unit_inertia(0, 0) == Approx(1.0 / 80));
  CHECK(tet->unit_inertia(0, 1) == Approx(1.0 / 480));  // products of inertia enter with −
}

TEST_CASE("scene: flat and invalid clouds are refused", "[unit][scene]") {
  CHECK_THROWS_AS(make_convex_shape({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}),
                  InvalidGeometry);
  CHECK_THROWS_AS(make_convex_shape({}), InvalidGeometry);
  CHECK_THROWS_AS(make_convex_shape({Vec3(0, 0, NAN), Vec3(1, 0, 0)}), InvalidGeometry);
  const auto shape = make_convex_shape(cloud_of(shapes::box()));
  CHECK_THROWS_AS(make_dynamic_body(shape, 0.0, Quat::Identity(), Vec3::Zero()),
                  std::invalid_argument);
}

TEST_CASE("scene: grid and sweep-and-prune give exactly the all-pairs overlap set",
          "[unit][scene]") {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 1 + trial * 7;
    // Every fourth scene is scattered over 10⁵ m, where the grid hashes its cells.
    const double region = trial % 4 == 3 ? 1e5 : 2 + u(rng) * 20;
    std::vector<Aabb> boxes(n);
    for (Aabb& b : boxes) {
      const Vec3 c(u(rng) * region, u(rng) * region - region / 2, u(rng) * region);
      Vec3 half(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng));
      if (u(rng) < 0.03) half *= 40;      // a few large boxes (grounds, containers)
      if (u(rng) < 0.05) half.setZero();  // and points: touching counts
      b = {c - half, c + half};
    }
    if (n > 3) boxes[1] = boxes[0];  // identical boxes overlap
    if (n > 3) {                     // boxes that only touch along a face
      boxes[3] = boxes[2];
      boxes[3].lower.x() = boxes[2].upper.x();
      boxes[3].upper.x() = boxes[2].upper.x() + 1;
    }
    std::vector<BodyPair> reference, grid, sap, grid_fixed;
    all_pairs(boxes, reference);
    BroadPhase g(BroadPhaseKind::grid), s(BroadPhaseKind::sweep_and_prune),
        gf(BroadPhaseKind::grid, 0.3);
    g.find_pairs(boxes, grid);
    s.find_pairs(boxes, sap);
    gf.find_pairs(boxes, grid_fixed);
    CHECK(grid == reference);
    CHECK(sap == reference);
    CHECK(grid_fixed == reference);
    // Move every box a little and ask again: sweep-and-prune reuses its order.
    for (Aabb& b : boxes) {
      const Vec3 d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
      b.lower += d;
      b.upper += d;
    }
    all_pairs(boxes, reference);
    s.find_pairs(boxes, sap);
    g.find_pairs(boxes, grid);
    CHECK(sap == reference);
    CHECK(grid == reference);
    if (n > 3 && region < 100) CHECK_FALSE(reference.empty());
  }
}

namespace {

/// The demo's density: 1000 boxes of 0.5 to 1.7 m in a 24 × 24 × 12 m region above an 80 m
/// ground (box 0).
std::vector<Aabb> dense_scene(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Aabb> boxes(1001);
  boxes[0] = {Vec3(-40, -40, -1), Vec3(40, 40, 0)};
  for (std::size_t i = 1; i < boxes.size(); ++i) {
    const Vec3 c(24 * u(rng) - 12, 24 * u(rng) - 12, 1 + 12 * u(rng));
    const Vec3 half(0.25 + 0.6 * u(rng), 0.25 + 0.6 * u(rng), 0.25 + 0.6 * u(rng));
    boxes[i] = {c - half, c + half};
  }
  return boxes;
}

/// One frame: every box but the ground falls 8 cm and jostles, resting on the ground. At
/// frame 30 the scene is turned on its side instead (the sweep axis changes).
void next_frame(std::vector<Aabb>& boxes, int frame, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  if (frame == 30) {
    for (Aabb& b : boxes) {
      std::swap(b.lower.x(), b.lower.z());
      std::swap(b.upper.x(), b.upper.z());
    }
    return;
  }
  for (std::size_t i = 1; i < boxes.size(); ++i) {
    Vec3 d(0.1 * (u(rng) - 0.5), 0.1 * (u(rng) - 0.5), -0.08);  // m per frame
    d.z() = std::max(d.z(), -boxes[i].lower.z());
    boxes[i].lower += d;
    boxes[i].upper += d;
  }
}

/// NaN (overlaps nothing), inverted (lower above upper: the test may still accept it),
/// infinite (a half-space), and, when `huge`, coordinates near the largest double, among
/// ordinary boxes.
std::vector<Aabb> irregular_scene(std::mt19937_64& rng, bool huge) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Aabb> boxes(60);
  for (Aabb& b : boxes) {
    const Vec3 c(10 * u(rng), 10 * u(rng), 10 * u(rng));
    b = {c - Vec3::Constant(0.5), c + Vec3::Constant(0.5)};
  }
  boxes[3].lower.y() = NAN;
  std::swap(boxes[5].lower.x(), boxes[5].upper.x());
  boxes[6] = {Vec3(2, 3, 4), Vec3(1, 2, 5)};  // inverted on two axes
  boxes[8].lower.z() = -INFINITY;
  boxes[9] = {Vec3::Constant(-INFINITY), Vec3::Constant(INFINITY)};
  if (huge) {
    boxes[10] = {Vec3::Constant(-1.7e308), Vec3::Constant(-1.6e308)};
    boxes[11] = {Vec3::Constant(1.6e308), Vec3::Constant(1.7e308)};
  }
  return boxes;
}

std::vector<peers::BroadphaseBox> peer_boxes(const std::vector<Aabb>& boxes) {
  std::vector<peers::BroadphaseBox> out;
  for (const Aabb& b : boxes)
    out.push_back({b.lower, b.upper});
  return out;
}

}  // namespace

TEST_CASE("scene: the broad phases give the all-pairs set on 1000 bodies, frame after frame",
          "[unit][scene]") {
  std::mt19937_64 rng(1000);
  std::vector<Aabb> boxes = dense_scene(rng);
  BroadPhase grid(BroadPhaseKind::grid), sap(BroadPhaseKind::sweep_and_prune);
  std::vector<BodyPair> reference, g, s;
  std::size_t fewest = SIZE_MAX;
  for (int frame = 0; frame < 40; ++frame) {
    all_pairs(boxes, reference);
    grid.find_pairs(boxes, g);
    sap.find_pairs(boxes, s);
    CHECK(g == reference);
    CHECK(s == reference);
    fewest = std::min(fewest, reference.size());
    next_frame(boxes, frame, rng);
  }
  CHECK(fewest > 500);  // a dense scene: most boxes meet another
}

TEST_CASE("scene: the broad phases give the all-pairs set on irregular boxes", "[unit][scene]") {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<Aabb> boxes = irregular_scene(rng, trial % 2 == 1);
    std::vector<BodyPair> reference, g, s;
    all_pairs(boxes, reference);
    BroadPhase grid(BroadPhaseKind::grid), sap(BroadPhaseKind::sweep_and_prune);
    grid.find_pairs(boxes, g);
    sap.find_pairs(boxes, s);
    CHECK(g == reference);
    CHECK(s == reference);
  }
}

TEST_CASE("scene: Bullet's dbvt broad phase gives the all-pairs set", "[unit][scene]") {
  if (!peers::bullet_broadphase_available()) {
    CHECK_THROWS(peers::BulletDbvtBroadphase());
    WARN("built without Bullet: its broad phase is not checked");
    return;
  }
  std::mt19937_64 rng(1000);
  std::vector<Aabb> boxes = dense_scene(rng);
  peers::BulletDbvtBroadphase dbvt;
  std::vector<BodyPair> reference, d;
  for (int frame = 0; frame < 40; ++frame) {
    all_pairs(boxes, reference);
    dbvt.find_pairs(peer_boxes(boxes), d);
    CHECK(d == reference);
    next_frame(boxes, frame, rng);
  }
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Aabb> irregular = irregular_scene(rng, trial % 2 == 1);
    all_pairs(irregular, reference);
    dbvt.find_pairs(peer_boxes(irregular), d);  // a new tree: the count changed
    CHECK(d == reference);
    // The same boxes again, then with the NaN box made regular (it joins the tree).
    dbvt.find_pairs(peer_boxes(irregular), d);
    CHECK(d == reference);
    irregular[3].lower.y() = irregular[3].upper.y() - 1;
    all_pairs(irregular, reference);
    dbvt.find_pairs(peer_boxes(irregular), d);
    CHECK(d == reference);
  }
}

TEST_CASE("scene: broad phase names round-trip", "[unit][scene]") {
  for (auto k : values_of(kBroadPhaseKindNames))
    CHECK(broad_phase_from_string(to_string(k)) == k);
  CHECK(to_string(BroadPhaseKind::sweep_and_prune) == "sap");
  CHECK_FALSE(broad_phase_from_string("octree"));
}
