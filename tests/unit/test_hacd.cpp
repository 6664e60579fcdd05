// Bullet's HACD as the approximate convex decomposition (peers::hacd_decomposition): the pieces
// are made of the mesh's own vertices, the cluster bound and the concavity bound do what they
// say, bad options and meshes are refused, and the same input gives the same pieces. The piece
// counts pinned here are what Bullet's HACD gives (measured); a change of HACD shows up here.
#ifdef GJKLAB_HAVE_HACD

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/peers/hacd.hpp"

using namespace gjklab;
using peers::hacd_decomposition;
using peers::HacdOptions;

namespace {

using Pieces = std::vector<std::vector<Vec3>>;
using Cell = std::array<int, 3>;

/// The closed surface of a union of unit cubes (cells of the integer grid, face-connected and
/// without two cells meeting only at an edge): each cube face not shared by two cells as two
/// triangles, counter-clockwise seen from outside, corners shared.
TriangleMesh voxel_mesh(const std::set<Cell>& cells) {
  TriangleMesh m;
  std::map<Cell, std::uint32_t> index;
  auto vertex = [&](const Cell& c) {
    const auto [at, added] = index.try_emplace(c, static_cast<std::uint32_t>(m.vertices.size()));
    if (added) m.vertices.emplace_back(c[0], c[1], c[2]);
    return at->second;
  };
  for (const Cell& cell : cells)
    for (int d = 0; d < 3; ++d)
      for (int side : {1, -1}) {
        Cell next = cell;
        next[d] += side;
        if (cells.count(next)) continue;
        // The square's corners a, a + e_u, a + e_u + e_v, a + e_v: (e_u × e_v) = e_d.
        const int u = (d + 1) % 3, v = (d + 2) % 3;
        Cell a = cell;
        a[d] += side > 0 ? 1 : 0;
        Cell b = a, c = a, e = a;
        b[u] += 1, c[u] += 1, c[v] += 1, e[v] += 1;
        const std::uint32_t ia = vertex(a), ib = vertex(b), ic = vertex(c), ie = vertex(e);
        if (side > 0)
          m.faces.insert(m.faces.end(), {{ia, ib, ic}, {ia, ic, ie}});
        else
          m.faces.insert(m.faces.end(), {{ia, ic, ib}, {ia, ie, ic}});
      }
  return m;
}

/// A UV sphere of radius 1: 8 rings, 12 segments, 86 vertices, 168 faces.
TriangleMesh convex_star() {
  return star_mesh(8, 12, [](const Vec3&) { return 1.0; });
}

/// The same grid with radius 1 along the six axis directions (grid vertices) falling to 0.3
/// between them (0.3 + 0.7·max|uᵢ|⁸): a jack of six spikes, far from convex.
TriangleMesh jack_star() {
  return star_mesh(8, 12,
                   [](const Vec3& u) { return 0.3 + 0.7 * std::pow(u.cwiseAbs().maxCoeff(), 8); });
}

HacdOptions with_min_clusters(int n) {
  HacdOptions o;
  o.min_clusters = n;
  return o;
}

/// Checks what every decomposition must satisfy: at least one piece, each of at least three
/// vertices, each vertex bit for bit a vertex of the mesh (and so inside its bounding box, with
/// no tolerance at all).
void check_pieces(const Pieces& pieces, const TriangleMesh& mesh) {
  REQUIRE_FALSE(pieces.empty());
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  const std::set<Vec3, decltype(less)> vertices(mesh.vertices.begin(), mesh.vertices.end(), less);
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices)
    lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  for (const std::vector<Vec3>& piece : pieces) {
    CHECK(piece.size() >= 3);
    for (const Vec3& v : piece) {
      CHECK(vertices.count(v) == 1);
      CHECK(((v.array() >= lo.array()).all() && (v.array() <= hi.array()).all()));
    }
  }
}

std::multiset<std::size_t> piece_sizes(const Pieces& pieces) {
  std::multiset<std::size_t> sizes;
  for (const std::vector<Vec3>& p : pieces)
    sizes.insert(p.size());
  return sizes;
}

}  // namespace

TEST_CASE("hacd: a convex mesh's pieces are made of its own vertices", "[unit][hacd]") {
  const TriangleMesh mesh = convex_star();
  SECTION("default options: the bound of two clusters, the second a single triangle") {
    const Pieces pieces = hacd_decomposition(mesh, HacdOptions{});
    check_pieces(pieces, mesh);
    CHECK(piece_sizes(pieces) == std::multiset<std::size_t>{3, 86});
  }
  SECTION("one cluster allowed: one piece, every vertex") {
    const Pieces pieces = hacd_decomposition(mesh, with_min_clusters(1));
    check_pieces(pieces, mesh);
    REQUIRE(pieces.size() == 1);
    CHECK(pieces[0].size() == mesh.vertices.size());
  }
}

TEST_CASE("hacd: non-convex meshes are split even when one cluster is allowed", "[unit][hacd]") {
  SECTION("a jack of six spikes") {
    const TriangleMesh mesh = jack_star();
    const Pieces pieces = hacd_decomposition(mesh, with_min_clusters(1));
    check_pieces(pieces, mesh);
    CHECK(pieces.size() == 4);
  }
  SECTION("a U of five cubes") {
    const TriangleMesh mesh = voxel_mesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}});
    const Pieces pieces = hacd_decomposition(mesh, with_min_clusters(1));
    check_pieces(pieces, mesh);
    CHECK(pieces.size() == 2);
  }
}

TEST_CASE("hacd: an L of three cubes is one piece unless face points are measured or it is taller",
          "[unit][hacd]") {
  // HACD measures concavity along vertex normals (sums of the adjacent faces' normals). The
  // L's reflex edge has both ends on the hull's bottom and top faces, and the normals there
  // lean out through those faces: distance 0, so the L is "convex" to HACD. The centroids of
  // the faces along the notch see it, and so do the vertices half-way up a taller L, whose
  // normals are level.
  const std::set<Cell> floor{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const TriangleMesh mesh = voxel_mesh(floor);
  REQUIRE(mesh.faces.size() == 28);
  HacdOptions o = with_min_clusters(1);
  const Pieces vertices_only = hacd_decomposition(mesh, o);
  check_pieces(vertices_only, mesh);
  CHECK(vertices_only.size() == 1);
  o.add_faces_points = true;
  const Pieces with_faces = hacd_decomposition(mesh, o);
  check_pieces(with_faces, mesh);
  CHECK(with_faces.size() == 2);
  std::set<Cell> tall;
  for (int z = 0; z < 3; ++z)
    for (const Cell& c : floor)
      tall.insert({c[0], c[1], z});
  const TriangleMesh tall_mesh = voxel_mesh(tall);
  const Pieces tall_pieces = hacd_decomposition(tall_mesh, with_min_clusters(1));
  check_pieces(tall_pieces, tall_mesh);
  CHECK(tall_pieces.size() == 4);
}

TEST_CASE("hacd: the piece count respects the cluster bound", "[unit][hacd]") {
  const TriangleMesh mesh = jack_star();
  for (int n : {1, 3, 7, 20}) {
    CAPTURE(n);
    HacdOptions o = with_min_clusters(n);
    // The bound is a minimum: the concavity bound may stop the merging earlier.
    const Pieces bounded = hacd_decomposition(mesh, o);
    check_pieces(bounded, mesh);
    CHECK(bounded.size() >= static_cast<std::size_t>(n));
    // With no concavity bound, merging goes on until exactly the bound is left.
    o.concavity = 1e12;
    CHECK(hacd_decomposition(mesh, o).size() == static_cast<std::size_t>(n));
  }
}

TEST_CASE("hacd: concavity 0 merges nothing on a curved mesh", "[unit][hacd]") {
  const TriangleMesh mesh = convex_star();
  HacdOptions o;
  o.concavity = 0;
  const Pieces pieces = hacd_decomposition(mesh, o);
  check_pieces(pieces, mesh);
  CHECK(pieces.size() == mesh.faces.size());
  CHECK(piece_sizes(pieces).count(3) == pieces.size());
}

TEST_CASE("hacd: the vertex bound of a piece, and full hulls", "[unit][hacd]") {
  const TriangleMesh mesh = convex_star();
  HacdOptions o = with_min_clusters(1);
  o.max_hull_vertices = 4;
  const Pieces tetrahedron = hacd_decomposition(mesh, o);
  check_pieces(tetrahedron, mesh);
  REQUIRE(tetrahedron.size() == 1);
  CHECK(tetrahedron[0].size() == 4);
  o.full_hulls = true;
  const Pieces full = hacd_decomposition(mesh, o);
  REQUIRE(full.size() == 1);
  CHECK(full[0].size() == mesh.vertices.size());
}

TEST_CASE("hacd: the same input gives the same pieces; the volume weight changes nothing",
          "[unit][hacd]") {
  const TriangleMesh mesh = jack_star();
  const Pieces first = hacd_decomposition(mesh, HacdOptions{});
  CHECK(hacd_decomposition(mesh, HacdOptions{}) == first);
  // Bullet's HACD computes the volume term but never adds it to the merge cost.
  HacdOptions o;
  o.volume_weight = 10;
  CHECK(hacd_decomposition(mesh, o) == first);
}

TEST_CASE("hacd: options out of range are refused, naming the option", "[unit][hacd]") {
  using Catch::Matchers::Contains;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK_NOTHROW(peers::validate(HacdOptions{}));
  auto refused = [](auto change, const char* name) {
    HacdOptions o;
    change(o);
    CHECK_THROWS_AS(peers::validate(o), std::invalid_argument);
    CHECK_THROWS_WITH(peers::validate(o), Contains(name));
    CHECK_THROWS_AS(hacd_decomposition(convex_star(), o), std::invalid_argument);
  };
  refused([](HacdOptions& o) { o.min_clusters = 0; }, "min_clusters");
  refused([](HacdOptions& o) { o.min_clusters = -2; }, "min_clusters");
  refused([&](HacdOptions& o) { o.concavity = nan; }, "concavity");
  refused([](HacdOptions& o) { o.concavity = -1; }, "concavity");
  refused([&](HacdOptions& o) { o.concavity = inf; }, "concavity");
  refused([](HacdOptions& o) { o.compacity_weight = -0.1; }, "compacity_weight");
  refused([&](HacdOptions& o) { o.volume_weight = nan; }, "volume_weight");
  refused([](HacdOptions& o) { o.max_hull_vertices = 3; }, "max_hull_vertices");
  refused([&](HacdOptions& o) { o.connect_distance = nan; }, "connect_distance");
  refused([](HacdOptions& o) { o.scale = 0; }, "scale");
  refused([](HacdOptions& o) { o.scale = -1000; }, "scale");
  refused([&](HacdOptions& o) { o.scale = inf; }, "scale");
  // A negative connect distance is HACD's way of linking no components.
  HacdOptions o;
  o.connect_distance = -1;
  CHECK_NOTHROW(peers::validate(o));
}

TEST_CASE("hacd: meshes it cannot decompose are refused", "[unit][hacd]") {
  CHECK_THROWS_AS(hacd_decomposition(TriangleMesh{}, HacdOptions{}), std::runtime_error);
  TriangleMesh no_face = convex_star();
  no_face.faces.clear();
  CHECK_THROWS_AS(hacd_decomposition(no_face, HacdOptions{}), std::runtime_error);
  TriangleMesh out_of_range = convex_star();
  out_of_range.faces[5][1] = static_cast<std::uint32_t>(out_of_range.vertices.size());
  CHECK_THROWS_AS(hacd_decomposition(out_of_range, HacdOptions{}), std::runtime_error);
  TriangleMesh not_finite = convex_star();
  not_finite.vertices[3].y() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(hacd_decomposition(not_finite, HacdOptions{}), std::runtime_error);
}

#endif  // GJKLAB_HAVE_HACD
