// FCL's BVHModel<OBBRSS> mesh queries (peers/fcl_mesh.hpp) judged against the exact truth for
// two closed meshes (exact::mesh_truth): distances of separated meshes, crossing meshes, a mesh
// inside another (which FCL does not see, pinned here as its documented limitation), triangles
// below FCL's fixed area threshold, and random poses of non-convex stars.
#ifdef GJKLAB_HAVE_FCL

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <utility>

#include "../support/posed_mesh.hpp"
#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/peers/fcl_mesh.hpp"

using namespace gjklab;
using namespace gjklab::peers;

namespace {

using Mesh = TriangleMesh;

/// FCL's distance against the exact one, relative: FCL takes the least triangle–triangle
/// distance in double, off by about 1e-16 absolute on coordinates of size 1 (measured ≤ 4e-14
/// relative on gaps above 1e-3); a wrong triangle pair or triangle case would be far larger.
constexpr double kRelativeTolerance = 1e-12;

/// A star mesh with radii drawn uniformly from [lo, 1] (lo = 1: a UV sphere of radius 1).
Mesh star(int rings, int segments, double lo, std::mt19937& rng) {
  std::uniform_real_distribution<double> radius(lo, 1.0);
  return star_mesh(rings, segments, [&](const Vec3&) { return lo < 1 ? radius(rng) : 1.0; });
}

using gjklab::testing::posed;

/// One face of a mesh as a mesh of one triangle (mesh_truth then answers for that triangle).
Mesh single_face(const Mesh& m, std::int64_t face) {
  const MeshFace& f = m.faces.at(static_cast<std::size_t>(face));
  return {{m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]}, {{0, 1, 2}}};
}

/// Whether the faces FCL names meet, by the exact truth on the two triangles alone.
bool faces_meet(const Mesh& a, std::int64_t face_a, const Mesh& b, std::int64_t face_b) {
  return exact::mesh_truth(single_face(a, face_a), single_face(b, face_b)).contact ==
         exact::MeshContact::triangles_meet;
}

/// Whether p lies on the mesh's face, within tol (length units): off its plane by at most tol
/// and with barycentric coordinates no less than −tol relative to the face's size.
bool on_face(const Mesh& m, std::int64_t face, const Vec3& p, double tol) {
  const MeshFace& f = m.faces.at(static_cast<std::size_t>(face));
  const Vec3 a = m.vertices[f[0]];
  Eigen::Matrix<double, 3, 2> edges;
  edges << m.vertices[f[1]] - a, m.vertices[f[2]] - a;
  const Eigen::Vector2d st = edges.colPivHouseholderQr().solve(p - a);
  const double off_plane = (edges * st - (p - a)).norm();
  return off_plane <= tol && st.minCoeff() >= -tol && st.sum() <= 1 + tol;
}

/// Two unit-radius UV spheres, scaled, the second above the first along z with its south pole
/// `gap` (relative to the scale) above the first's north pole.
std::pair<Mesh, Mesh> spheres_pole_to_pole(double scale, double gap) {
  std::mt19937 unused(0);
  const Mesh a = posed(star(12, 16, 1.0, unused), scale, Vec3::UnitZ(), 0, Vec3::Zero());
  const Mesh b =
      posed(star(10, 13, 1.0, unused), scale, Vec3::UnitZ(), 0.3, Vec3(0, 0, scale * (2 + gap)));
  return {a, b};
}

}  // namespace

TEST_CASE("fcl mesh: UV spheres pole to pole, the distance is the gap between the poles",
          "[unit][peers][fcl-mesh]") {
  for (const double scale : {1e-2, 1.0, 1e3}) {
    const auto [a, b] = spheres_pole_to_pole(scale, 1e-3);
    const exact::MeshTruth truth = exact::mesh_truth(a, b);
    REQUIRE_FALSE(truth.intersect);
    // Both meshes lie in their balls, which meet the axis only at the poles: the gap is theirs.
    CHECK(truth.distance == Approx(b.vertices.back().z() - a.vertices.front().z()).epsilon(1e-15));
    const FclMeshAnswer d = fcl_mesh_distance(FclMesh(a), FclMesh(b));
    INFO("scale " << scale);
    CHECK_FALSE(d.intersect);
    CHECK(*d.distance == Approx(truth.distance).epsilon(kRelativeTolerance));
    REQUIRE(d.witness_a);
    REQUIRE(d.witness_b);
    CHECK((*d.witness_a - a.vertices.front()).norm() <= 1e-12 * scale);
    CHECK((*d.witness_b - b.vertices.back()).norm() <= 1e-12 * scale);
    CHECK_FALSE(fcl_mesh_collide(FclMesh(a), FclMesh(b)).intersect);
  }
}

TEST_CASE("fcl mesh: separated non-convex stars, the exact distance and witnesses on the meshes",
          "[unit][peers][fcl-mesh]") {
  std::mt19937 rng(20261127);
  std::uniform_real_distribution<double> unit(-1, 1);
  int checked = 0;
  for (int attempt = 0; attempt < 40 && checked < 10; ++attempt) {
    const Mesh a = star(8, 11, 0.5, rng);
    const Vec3 direction = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const Mesh b = posed(star(7, 9, 0.5, rng), 0.8, Vec3(unit(rng), unit(rng), 1), 2 * unit(rng),
                         1.9 * direction);
    const exact::MeshTruth truth = exact::mesh_truth(a, b);
    if (truth.intersect || truth.distance <= 1e-3) continue;  // a gap well above rounding
    ++checked;
    const FclMesh fa(a), fb(b);
    const FclMeshAnswer d = fcl_mesh_distance(fa, fb);
    INFO("attempt " << attempt << ": exact " << truth.distance << ", fcl " << *d.distance);
    CHECK_FALSE(d.intersect);
    CHECK(*d.distance == Approx(truth.distance).epsilon(kRelativeTolerance));
    REQUIRE(d.witness_a);
    REQUIRE(d.witness_b);
    CHECK(on_face(a, d.face_a, *d.witness_a, 1e-12));
    CHECK(on_face(b, d.face_b, *d.witness_b, 1e-12));
    CHECK((*d.witness_b - *d.witness_a).norm() == Approx(truth.distance).epsilon(1e-12));
    CHECK_FALSE(fcl_mesh_collide(fa, fb).intersect);
  }
  CHECK(checked == 10);
}

TEST_CASE("fcl mesh: crossing meshes collide, at distance 0, on faces that meet",
          "[unit][peers][fcl-mesh]") {
  std::mt19937 rng(7);
  const Mesh outer = star(10, 12, 0.6, rng);
  const Mesh inner = posed(star(6, 8, 0.6, rng), 0.3, Vec3(1, 1, 0), 0.7, Vec3::Zero());
  const FclMesh fouter(outer);
  for (const double x : {0.55, 0.7, 0.9}) {
    const Mesh crossing = posed(inner, 1, Vec3::UnitZ(), 0, Vec3(x, 0, 0));
    REQUIRE(exact::mesh_truth(outer, crossing).contact == exact::MeshContact::triangles_meet);
    const FclMesh fcrossing(crossing);
    INFO("moved by " << x);
    const FclMeshAnswer c = fcl_mesh_collide(fouter, fcrossing);
    CHECK(c.intersect);
    CHECK(c.contacts == 1);
    CHECK(faces_meet(outer, c.face_a, crossing, c.face_b));
    // With room for more contacts FCL lists every pair that meets (one contact enough above).
    CHECK(fcl_mesh_collide(fouter, fcrossing, {0, 0, 100000}).contacts > 1);
    const FclMeshAnswer d = fcl_mesh_distance(fouter, fcrossing);
    CHECK(d.intersect);
    CHECK(*d.distance == 0);  // never negative
    CHECK_FALSE(d.witness_a);
    CHECK(faces_meet(outer, d.face_a, crossing, d.face_b));
  }
}

TEST_CASE("fcl mesh: a small star strictly inside a big one meets it, and FCL sees no contact",
          "[unit][peers][fcl-mesh]") {
  std::mt19937 rng(3);
  const Mesh outer = star(10, 12, 0.6, rng);
  const Mesh inner = posed(star(6, 8, 0.6, rng), 0.3, Vec3(1, 1, 0), 0.7, Vec3(0.05, 0, 0));
  REQUIRE(exact::mesh_truth(inner, outer).contact == exact::MeshContact::a_inside_b);
  REQUIRE(exact::mesh_truth(outer, inner).contact == exact::MeshContact::b_inside_a);
  const FclMesh fouter(outer), finner(inner);
  // FCL's documented limitation: it tests triangles, and no triangles meet.
  for (const auto& [a, b] : {std::pair{&finner, &fouter}, std::pair{&fouter, &finner}}) {
    CHECK_FALSE(fcl_mesh_collide(*a, *b).intersect);
    CHECK(fcl_mesh_collide(*a, *b, {0, 0, 100000}).contacts == 0);
    const FclMeshAnswer d = fcl_mesh_distance(*a, *b);
    CHECK_FALSE(d.intersect);
    // The gap between the surfaces: the inner star lies within 0.35 of the origin, the outer
    // surface beyond 0.6·cos 15° (its vertices at radius ≥ 0.6, its faces spanning ≤ 30°).
    CHECK(*d.distance > 0.2);
  }
}

TEST_CASE("fcl mesh: triangles below FCL's fixed area threshold give distance 0 while apart",
          "[unit][peers][fcl-mesh]") {
  // A square pyramid (apex down) of size h, and a tetrahedron whose lowest vertex faces the
  // pyramid's top face from 0.1·h above: the distance is vertex to face.
  auto pair = [](double h) {
    const Mesh a{{{0, 0, 0}, {h, 0, 0}, {h, h, 0}, {0, h, 0}, {h / 2, h / 2, -h}},
                 {{0, 1, 2}, {0, 2, 3}, {0, 4, 1}, {1, 4, 2}, {2, 4, 3}, {3, 4, 0}}};
    const double g = 0.1 * h, top = g + h;
    const Mesh b{{{0.3 * h, 0.4 * h, g}, {0, 0, top}, {h, 0, top}, {h / 2, h, top}},
                 {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
    return std::pair{a, b};
  };
  for (const double h : {1.0, 1e-2, 1e-4}) {
    const auto [a, b] = pair(h);
    const exact::MeshTruth truth = exact::mesh_truth(a, b);
    REQUIRE_FALSE(truth.intersect);
    CHECK(truth.distance == 0.1 * h);
    const FclMesh fa(a), fb(b);
    const FclMeshAnswer d = fcl_mesh_distance(fa, fb);
    INFO("h = " << h << ": fcl distance " << *d.distance);
    CHECK_FALSE(fcl_mesh_collide(fa, fb).intersect);
    if (h >= 1e-2) {
      CHECK(*d.distance == Approx(truth.distance).epsilon(kRelativeTolerance));
    } else {
      // |(b − a) × (c − a)|² = h⁴ = 1e-16 is below FCL's 1e-15: its vertex–face test is skipped
      // and, no edge pair showing the triangles apart, it answers 0 (documented in the header).
      CHECK(*d.distance == 0);
      CHECK(d.intersect);
    }
  }
}

TEST_CASE("fcl mesh: random poses of non-convex stars agree with the exact truth",
          "[unit][peers][fcl-mesh]") {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> unit(-1, 1), scale(0.15, 1.1), reach(0, 2.4);
  const int pairs = 60;
  int meet = 0, contained = 0, apart = 0, in_band = 0, agree = 0;
  for (int k = 0; k < pairs; ++k) {
    const Mesh a = star(6, 9, 0.5, rng);
    const Vec3 direction = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const Mesh b = posed(star(5, 8, 0.5, rng), scale(rng), Vec3(unit(rng), unit(rng), 1),
                         3 * unit(rng), reach(rng) * direction);
    const exact::MeshTruth truth = exact::mesh_truth(a, b);
    const FclMesh fa(a), fb(b);
    const FclMeshAnswer c = fcl_mesh_collide(fa, fb);
    const FclMeshAnswer d = fcl_mesh_distance(fa, fb);
    INFO("pair " << k << ": exact distance " << truth.distance << ", fcl " << *d.distance);
    agree += c.intersect == truth.intersect;
    if (truth.contact == exact::MeshContact::a_inside_b ||
        truth.contact == exact::MeshContact::b_inside_a) {
      ++contained;  // the limitation: FCL answers apart
      CHECK_FALSE(c.intersect);
      CHECK(*d.distance > 0);
    } else if (truth.contact == exact::MeshContact::triangles_meet) {
      ++meet;
      CHECK(c.intersect);
      CHECK(*d.distance == 0);
    } else if (truth.distance > 1e-6) {
      ++apart;
      CHECK_FALSE(c.intersect);
      CHECK(*d.distance == Approx(truth.distance).epsilon(kRelativeTolerance));
    } else {
      ++in_band;  // touching band: either answer is within rounding
    }
  }
  INFO(meet << " crossing, " << contained << " contained, " << apart << " apart, " << in_band
            << " within 1e-6; collide agrees on " << agree);
  // The family reaches every kind; FCL agrees everywhere but on containment and in the band.
  CHECK(meet > 0);
  CHECK(contained > 0);
  CHECK(apart > 0);
  CHECK(agree >= pairs - contained - in_band);
}

TEST_CASE("fcl mesh: options, inputs and early stop", "[unit][peers][fcl-mesh]") {
  std::mt19937 rng(5);
  const Mesh a = star(5, 7, 0.6, rng);
  const Mesh b = posed(star(5, 7, 0.6, rng), 1, Vec3::UnitZ(), 0.4, Vec3(2.5, 0, 0));
  FclMesh fa(a);
  const FclMesh fb(b);
  CHECK(fa.triangle_count() == a.faces.size());
  CHECK(fa.bounding_volume_count() == 2 * a.faces.size() - 1);
  CHECK_THROWS_AS(fcl_mesh_distance(fa, fb, {-0.1, 0, 1}), std::invalid_argument);
  CHECK_THROWS_AS(fcl_mesh_distance(fa, fb, {0, -1, 1}), std::invalid_argument);
  CHECK_THROWS_AS(fcl_mesh_collide(fa, fb, {0, 0, 0}), std::invalid_argument);
  Mesh bad = a;
  bad.faces[1][2] = 999;
  CHECK_THROWS_AS(FclMesh(bad), std::invalid_argument);
  bad = a;
  bad.vertices[0].x() = std::nan("");
  CHECK_THROWS_AS(FclMesh(bad), std::invalid_argument);
  CHECK_THROWS_AS(FclMesh(Mesh{a.vertices, {}}), std::invalid_argument);
  // Early stop: the answer lies in [d*, (1 + rel_err)·d*] and in [d*, d* + abs_err].
  const double exact_distance = exact::mesh_truth(a, b).distance;
  const double loose = *fcl_mesh_distance(fa, fb, {0.5, 1e9, 1}).distance;
  CHECK(loose >= exact_distance * (1 - kRelativeTolerance));
  CHECK(loose <= 1.5 * exact_distance * (1 + kRelativeTolerance));
  const double absolute = *fcl_mesh_distance(fa, fb, {1, 0.01, 1}).distance;
  CHECK(absolute >= exact_distance * (1 - kRelativeTolerance));
  CHECK(absolute <= exact_distance + 0.01 + 1e-12);
  // A moved mesh answers as before.
  const FclMesh moved = std::move(fa);
  CHECK(*fcl_mesh_distance(moved, fb).distance ==
        Approx(exact_distance).epsilon(kRelativeTolerance));
}

#endif  // GJKLAB_HAVE_FCL
