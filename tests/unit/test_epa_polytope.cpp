// The EPA polytope on its own (epa_polytope.hpp): the starting tetrahedron's orientation and
// adjacency, the closest face, the faces a point sees and their horizon, and the cone.
#include <catch2/catch.hpp>

#include <array>
#include <set>
#include <utility>

#include "gjklab/gjk/epa_polytope.hpp"

using namespace gjklab;

namespace {

SimplexVertex point(double x, double y, double z) {
  SimplexVertex v;
  v.w = Vec3(x, y, z);
  v.a = v.w;
  return v;
}

/// A tetrahedron around the origin with its face (0, 1, 2) nearest, in the plane z = −1.
std::array<SimplexVertex, 4> tetrahedron() {
  return {point(6, 0, -1), point(-4, 4, -1), point(-4, -4, -1), point(0, 0, 20)};
}

/// Every live face's neighbour across each edge has that edge reversed and points back; every
/// face's plane has the other vertices behind it; Euler's formula holds.
void check_closed_convex(const EpaPolytope& p) {
  std::set<int> vertices;
  int faces = 0;
  for (int f = 0; f < static_cast<int>(p.faces.size()); ++f) {
    const auto& face = p.faces[f];
    if (!face.alive) continue;
    ++faces;
    for (int e = 0; e < 3; ++e) {
      vertices.insert(face.v[e]);
      const auto& other = p.faces[face.adj[e]];
      REQUIRE(other.alive);
      const int back = face.adj_edge[e];
      CHECK(other.adj[back] == f);
      CHECK(other.v[back] == face.v[(e + 1) % 3]);
      CHECK(other.v[(back + 1) % 3] == face.v[e]);
    }
    for (const SimplexVertex& v : p.vertices)
      CHECK(face.normal.dot(v.w) - face.distance <= 1e-12);
    CHECK(face.distance > 0);  // the origin is inside
  }
  CHECK(faces == p.alive());
  const int edges = 3 * faces / 2;
  CHECK(static_cast<int>(vertices.size()) - edges + faces == 2);
}

}  // namespace

TEST_CASE("EPA polytope: the starting tetrahedron, outward and closed", "[unit][epa]") {
  EpaPolytope p;
  p.prepare(8, 20);
  REQUIRE(p.start_tetrahedron(tetrahedron()));
  CHECK(p.alive() == 4);
  check_closed_convex(p);
  const int closest = p.closest_face();
  CHECK(p.faces[closest].distance == Approx(1));
  CHECK(p.faces[closest].normal.isApprox(Vec3(0, 0, -1)));
  CHECK(p.has_vertex(Vec3(0, 0, 20)));
  CHECK_FALSE(p.has_vertex(Vec3(0, 0, 4)));

  // Four points in a plane have no volume.
  EpaPolytope flat;
  flat.prepare(8, 20);
  CHECK_FALSE(flat.start_tetrahedron(
      {point(1, 0, 0), point(0, 1, 0), point(-1, -1, 0), point(0.5, 0.5, 0)}));
}

TEST_CASE("EPA polytope: horizon and cone of a point beyond one face, then beyond two",
          "[unit][epa]") {
  EpaPolytope p;
  p.prepare(8, 20);
  REQUIRE(p.start_tetrahedron(tetrahedron()));
  // Below the base: sees the base only; the horizon is its three edges.
  int closest = p.closest_face();
  const SimplexVertex below = point(0, 0, -3);
  int visible = p.mark_visible(closest, below.w, 1e-12, 0);
  CHECK(visible == 1);
  CHECK(p.horizon().size() == 3);
  REQUIRE(p.cone_fits(visible, 20));
  REQUIRE(p.link_horizon());
  REQUIRE(p.add_cone(below, 0, p.faces[closest].distance, 1e-12));
  CHECK(p.alive() == 6);
  CHECK(p.vertices.size() == 5);
  check_closed_convex(p);

  // Far out to the side: sees two faces; the horizon is a loop of four edges.
  const SimplexVertex side = point(12, 0, 2);
  std::pair<int, double> seed{-1, 0};
  for (int f = 0; f < static_cast<int>(p.faces.size()); ++f)
    if (p.faces[f].alive) {
      const double h = p.faces[f].normal.dot(side.w) - p.faces[f].distance;
      if (h > seed.second) seed = {f, h};
    }
  REQUIRE(seed.first >= 0);
  visible = p.mark_visible(seed.first, side.w, 1e-12, 1);
  CHECK(visible == 2);
  CHECK(p.horizon().size() == 4);
  REQUIRE(p.link_horizon());
  REQUIRE(p.add_cone(side, 1, 0, 1e-12));
  CHECK(p.alive() == 8);
  check_closed_convex(p);
}

TEST_CASE("EPA polytope: a cone nearer the origin than the bound, or over the budget, is refused",
          "[unit][epa]") {
  EpaPolytope p;
  p.prepare(8, 20);
  REQUIRE(p.start_tetrahedron(tetrahedron()));
  const int closest = p.closest_face();
  const SimplexVertex below = point(0, 0, -3);
  const int visible = p.mark_visible(closest, below.w, 1e-12, 0);
  CHECK_FALSE(p.cone_fits(visible, 5));  // 4 − 1 + 3 = 6 faces > 5
  REQUIRE(p.link_horizon());
  // The new faces' planes are nearer the origin than 3: a lower bound of 3 rejects them, and
  // the polytope is left as it was.
  CHECK_FALSE(p.add_cone(below, 0, 3.0, 1e-12));
  CHECK(p.alive() == 4);
  CHECK(p.vertices.size() == 4);
  check_closed_convex(p);
}
