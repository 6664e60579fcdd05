// The exact truth for two closed meshes (exact::mesh_truth) against an independent brute force:
// every pair of triangles by the tests' own rational oracle (each triangle a convex cloud of
// three points), and containment by the parity of an exact ray cast, also in rationals. On
// convex meshes it must also equal the library's convex oracle on the vertex clouds.
#include <catch2/catch.hpp>

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <span>
#include <vector>

#include "../support/brute_force_oracle.hpp"
#include "../support/posed_mesh.hpp"
#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/exact/hull_features.hpp"
#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/exact/oracle.hpp"

using namespace gjklab;
namespace bf = gjklab::testing::brute_force;

namespace {

using Face = MeshFace;
using Mesh = TriangleMesh;

/// A star mesh (gjklab::star_mesh) with radii drawn uniformly from [lo, 1] (lo = 1: a convex
/// UV sphere, up to the rounding of its vertices).
Mesh star_mesh(int rings, int segments, double lo, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> radius(lo, 1.0);
  return gjklab::star_mesh(rings, segments,
                           [&](const Vec3&) { return lo < 1 ? radius(rng) : 1.0; });
}

using gjklab::testing::posed;

/// The exact convex hull of a cloud as a closed mesh: the solid is exactly the hull, whatever
/// the rounding of the points.
Mesh hull_mesh(const std::vector<Vec3>& cloud) {
  return exact::hull_mesh(cloud);
}

/// Whether p lies strictly inside the closed mesh, by the parity of an exact ray cast in a
/// direction that meets no edge or vertex (another is drawn when one does).
bool brute_inside(const Vec3& point, const Mesh& m, std::mt19937_64& rng) {
  const bf::Q3 p = bf::exact(point);
  std::uniform_int_distribution<int> coordinate(-1000, 1000);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const bf::Q3 r{coordinate(rng), coordinate(rng), coordinate(rng)};
    if (bf::is_zero(r)) continue;
    int crossings = 0;
    bool degenerate = false;
    for (const Face& f : m.faces) {
      const bf::Q3 v[3] = {bf::exact(m.vertices[f[0]]) - p, bf::exact(m.vertices[f[1]]) - p,
                           bf::exact(m.vertices[f[2]]) - p};
      int sign[3];
      for (int i = 0; i < 3; ++i)
        sign[i] = sgn(bf::det(v[i], v[(i + 1) % 3], r));
      if (sign[0] == 0 || sign[1] == 0 || sign[2] == 0) {
        // The ray's line passes an edge's plane through p: degenerate only if it also meets
        // the triangle's closure in front of p; simplest to draw another direction.
        if ((sign[0] >= 0 && sign[1] >= 0 && sign[2] >= 0) ||
            (sign[0] <= 0 && sign[1] <= 0 && sign[2] <= 0)) {
          degenerate = true;
          break;
        }
        continue;
      }
      if (sign[0] != sign[1] || sign[1] != sign[2]) continue;  // the line misses the triangle
      const bf::Q3 n = bf::cross(v[1] - v[0], v[2] - v[0]);
      const int front = sgn(bf::dot(n, v[0])) * sgn(bf::dot(n, r));  // t > 0: same signs
      if (bf::dot(n, v[0]) == 0) {
        degenerate = true;  // p on the triangle's plane
        break;
      }
      crossings += front > 0;
    }
    if (!degenerate) return crossings % 2 == 1;
  }
  FAIL("no ray direction without degeneracy");
  return false;
}

struct BruteAnswer {
  bool intersect;
  mpq_class distance2;
};

using Tri = std::array<bf::Q3, 3>;

Tri exact_triangle(const Mesh& m, const Face& f) {
  return {bf::exact(m.vertices[f[0]]), bf::exact(m.vertices[f[1]]), bf::exact(m.vertices[f[2]])};
}

/// Exact squared distance from p to the triangle: to its plane when p projects inside it, else
/// to the nearest edge.
mpq_class point_triangle_distance2(const bf::Q3& p, const Tri& t) {
  const bf::Q3 n = bf::cross(t[1] - t[0], t[2] - t[0]);
  bool inside = true;
  for (int i = 0; i < 3; ++i)
    inside = inside && sgn(bf::dot(bf::cross(t[(i + 1) % 3] - t[i], p - t[i]), n)) >= 0;
  if (inside) {
    const mpq_class h = bf::dot(n, p - t[0]);
    return h * h / bf::dot(n, n);
  }
  mpq_class best = bf::point_segment_distance2(p, t[0], t[1]);
  for (int i = 1; i < 3; ++i)
    best = std::min(best, bf::point_segment_distance2(p, t[i], t[(i + 1) % 3]));
  return best;
}

/// Exact squared distance between two segments: interior to interior where the closest points
/// of the lines fall inside both, else from an end point.
mpq_class segment_distance2(const bf::Q3& p1, const bf::Q3& q1, const bf::Q3& p2,
                            const bf::Q3& q2) {
  mpq_class best =
      std::min({bf::point_segment_distance2(p1, p2, q2), bf::point_segment_distance2(q1, p2, q2),
                bf::point_segment_distance2(p2, p1, q1), bf::point_segment_distance2(q2, p1, q1)});
  const bf::Q3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const mpq_class a = bf::dot(d1, d1), e = bf::dot(d2, d2), b = bf::dot(d1, d2);
  const mpq_class c = bf::dot(d1, r), f = bf::dot(d2, r), denom = a * e - b * b;
  if (sgn(denom) == 0) return best;
  const mpq_class s = (b * f - c * e) / denom, t = (a * f - b * c) / denom;
  if (s < 0 || s > 1 || t < 0 || t > 1) return best;
  const bf::Q3 v = (p1 + s * d1) - (p2 + t * d2);
  return std::min(best, bf::dot(v, v));
}

/// Whether the segment crosses the triangle's plane strictly and passes through the closed
/// triangle (the one way two triangles can meet that no vertex or edge distance shows).
bool pierces(const bf::Q3& p, const bf::Q3& q, const Tri& t) {
  const int sp = sgn(bf::det(t[1] - t[0], t[2] - t[0], p - t[0]));
  const int sq = sgn(bf::det(t[1] - t[0], t[2] - t[0], q - t[0]));
  if (sp * sq >= 0) return false;
  int side[3];
  for (int i = 0; i < 3; ++i)
    side[i] = sgn(bf::det(q - p, t[i] - p, t[(i + 1) % 3] - p));
  return (side[0] >= 0 && side[1] >= 0 && side[2] >= 0) ||
         (side[0] <= 0 && side[1] <= 0 && side[2] <= 0);
}

/// Exact squared distance between two non-degenerate triangles (0 when they meet): the nearest
/// of the six vertex–triangle and nine edge–edge distances, or 0 when an edge pierces.
mpq_class triangle_distance2(const Tri& x, const Tri& y) {
  for (int i = 0; i < 3; ++i)
    if (pierces(x[i], x[(i + 1) % 3], y) || pierces(y[i], y[(i + 1) % 3], x)) return 0;
  mpq_class best = point_triangle_distance2(x[0], y);
  for (int i = 0; i < 3; ++i) {
    best = std::min({best, point_triangle_distance2(x[i], y), point_triangle_distance2(y[i], x)});
    for (int j = 0; j < 3; ++j)
      best = std::min(best, segment_distance2(x[i], x[(i + 1) % 3], y[j], y[(j + 1) % 3]));
  }
  return best;
}

/// The least exact squared distance over every pair of the given faces of a and b.
mpq_class brute_min_distance2(const Mesh& a, std::span<const Face> faces_a, const Mesh& b,
                              std::span<const Face> faces_b) {
  std::vector<Tri> tb;
  for (const Face& f : faces_b)
    tb.push_back(exact_triangle(b, f));
  mpq_class best = -1;
  for (const Face& fa : faces_a) {
    const Tri x = exact_triangle(a, fa);
    for (const Tri& y : tb) {
      const mpq_class d2 = triangle_distance2(x, y);
      if (best < 0 || d2 < best) best = d2;
    }
  }
  return best;
}

/// All pairs of triangles and the two containment tests.
BruteAnswer brute_mesh_truth(const Mesh& a, const Mesh& b, std::mt19937_64& rng) {
  const mpq_class best = brute_min_distance2(a, a.faces, b, b.faces);
  if (best == 0) return {true, 0};
  if (brute_inside(a.vertices[a.faces[0][0]], b, rng) ||
      brute_inside(b.vertices[b.faces[0][0]], a, rng))
    return {true, 0};
  return {false, best};
}

mpq_class as_mpq(const exact::Rational& r) {
  return mpq_class(r.numerator() + "/" + r.denominator());
}

/// A random pose of a copy of `m` near A: scaled in [0.15, 1.2], rotated, moved 0 … 2.6.
Mesh random_partner(const Mesh& m, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1, 1), scale(0.15, 1.2), reach(0, 2.6);
  const Vec3 axis(unit(rng), unit(rng), unit(rng) + 2);
  Vec3 direction(unit(rng), unit(rng), unit(rng));
  direction = direction.normalized();
  return posed(m, scale(rng), axis, 3 * unit(rng), reach(rng) * direction);
}

}  // namespace

/// Answers counted by kind over a run of random pairs.
struct Tally {
  int intersecting = 0, separated = 0;
};

/// Random pairs of star meshes (rings × segments, radii in [lo, 1]) judged by mesh_truth and by
/// the brute force, which must agree exactly.
Tally cross_check(int pairs, int rings, int segments, double lo, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Tally tally;
  for (int k = 0; k < pairs; ++k) {
    const Mesh a = star_mesh(rings, segments, lo, rng);
    const Mesh b = random_partner(star_mesh(rings, segments - 1, lo, rng), rng);
    const exact::MeshTruth t = exact::mesh_truth(a, b);
    const BruteAnswer brute = brute_mesh_truth(a, b, rng);
    INFO("pair " << k);
    REQUIRE(t.intersect == brute.intersect);
    CHECK(as_mpq(t.distance_squared) == brute.distance2);
    CHECK(t.distance == Approx(std::sqrt(brute.distance2.get_d())).epsilon(1e-15));
    tally.intersecting += t.contact == exact::MeshContact::triangles_meet;
    tally.separated += !t.intersect;
  }
  return tally;
}

TEST_CASE("mesh truth: non-convex star meshes agree with the brute force over all triangle pairs",
          "[unit][mesh-truth]") {
  const Tally tally = cross_check(16, 4, 6, 0.55, 20261127);
  // The family reaches triangles that meet and solids apart (containment: the next test).
  CHECK(tally.intersecting > 0);
  CHECK(tally.separated > 0);
}

TEST_CASE("mesh truth: a small star inside a star is contained, either way round",
          "[unit][mesh-truth]") {
  std::mt19937_64 rng(3);
  const Mesh outer = star_mesh(5, 7, 0.6, rng);
  const Mesh inner = posed(star_mesh(4, 5, 0.6, rng), 0.3, Vec3(1, 1, 0), 0.7, Vec3(0.05, 0, 0));
  const exact::MeshTruth ab = exact::mesh_truth(outer, inner);
  CHECK(ab.intersect);
  CHECK(ab.contact == exact::MeshContact::b_inside_a);
  const exact::MeshTruth ba = exact::mesh_truth(inner, outer);
  CHECK(ba.intersect);
  CHECK(ba.contact == exact::MeshContact::a_inside_b);
  CHECK(brute_mesh_truth(outer, inner, rng).intersect);
  // Moved out through the outer surface: the triangles meet; moved far: separated.
  const Mesh crossing = posed(inner, 1, Vec3::UnitZ(), 0, Vec3(0.55, 0, 0));
  CHECK(exact::mesh_truth(outer, crossing).contact == exact::MeshContact::triangles_meet);
  const Mesh far = posed(inner, 1, Vec3::UnitZ(), 0, Vec3(3, 0, 0));
  CHECK_FALSE(exact::mesh_truth(outer, far).intersect);
}

TEST_CASE("mesh truth: on convex meshes it equals the convex oracle on the vertex clouds",
          "[unit][mesh-truth]") {
  std::mt19937_64 rng(7);
  for (int k = 0; k < 30; ++k) {
    const Mesh a = hull_mesh(random_partner(star_mesh(5, 8, 0.6, rng), rng).vertices);
    const Mesh b = hull_mesh(random_partner(star_mesh(4, 7, 0.6, rng), rng).vertices);
    const exact::MeshTruth t = exact::mesh_truth(a, b);
    const exact::OracleAnswer o = exact::solve(a.vertices, b.vertices, {});
    INFO("pair " << k << ": mesh " << t.distance_squared.numerator() << "/"
                 << t.distance_squared.denominator() << " (" << t.distance << "), oracle "
                 << o.distance_squared.numerator() << "/" << o.distance_squared.denominator()
                 << " (" << o.distance << "), intersect " << o.intersect);
    CHECK(t.intersect == o.intersect);
    CHECK(t.distance_squared == o.distance_squared);
  }
}

TEST_CASE("mesh truth: touching meshes meet exactly, a gap of one ulp does not close",
          "[unit][mesh-truth]") {
  // Two unit cubes as meshes, face to face at x = 1: touching; then B moved by the next
  // double above 1: apart by exactly that step.
  Mesh cube;
  cube.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  cube.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  const Mesh touching = posed(cube, 1, Vec3::UnitZ(), 0, Vec3(1, 0.25, 0.5));
  const exact::MeshTruth t = exact::mesh_truth(cube, touching);
  CHECK(t.intersect);
  CHECK(t.contact == exact::MeshContact::triangles_meet);
  const double next = std::nextafter(1.0, 2.0);
  const Mesh apart = posed(cube, 1, Vec3::UnitZ(), 0, Vec3(next, 0.25, 0.5));
  const exact::MeshTruth s = exact::mesh_truth(cube, apart);
  CHECK_FALSE(s.intersect);
  const mpq_class gap = mpq_class(next) - 1;
  CHECK(as_mpq(s.distance_squared) == gap * gap);
}

TEST_CASE("mesh truth: star meshes are closed meshes, convex or not", "[unit][mesh-truth]") {
  std::mt19937_64 rng(4);
  for (const double lo : {1.0, 0.7, 0.2}) {
    const Mesh m = star_mesh(6, 9, lo, rng);
    CHECK(m.faces.size() == 2 * 9 * 5);
    CHECK_NOTHROW(exact::validate_closed_mesh(m, "star"));
  }
  CHECK_THROWS_AS(gjklab::star_mesh(1, 5, [](const Vec3&) { return 1.0; }), std::invalid_argument);
  CHECK_THROWS_AS(gjklab::star_mesh(3, 5, [](const Vec3&) { return 0.0; }), std::invalid_argument);
}

TEST_CASE("mesh truth: bad meshes are refused, naming the face", "[unit][mesh-truth]") {
  std::mt19937_64 rng(1);
  const Mesh good = star_mesh(3, 4, 1.0, rng);
  Mesh bad = good;
  bad.faces[2][1] = 999;
  CHECK_THROWS_WITH(exact::mesh_truth(good, bad),
                    Catch::Contains("mesh B: face 2 names vertex 999"));
  bad = good;
  bad.faces[3] = {bad.faces[3][0], bad.faces[3][0], bad.faces[3][1]};
  CHECK_THROWS_WITH(exact::mesh_truth(bad, good), Catch::Contains("mesh A: face 3 is degenerate"));
  bad = good;
  bad.vertices[1].x() = std::nan("");
  CHECK_THROWS_WITH(exact::mesh_truth(bad, good),
                    Catch::Contains("mesh A: vertex 1 is not finite"));
  CHECK_THROWS_WITH(exact::mesh_truth(exact::MeshView(good), exact::MeshView(Mesh{})),
                    Catch::Contains("mesh B: has no faces"));
}

TEST_CASE("mesh truth: cross-check on 2000 pairs", "[.mesh-truth-crosscheck]") {
  const Tally tally = cross_check(2000, 3, 6, 0.5, 2026);
  CHECK(tally.intersecting > 100);
  CHECK(tally.separated > 100);
  CHECK(tally.intersecting + tally.separated <= 2000);
  WARN("2000 pairs agree; " << tally.intersecting << " with triangles that meet, "
                            << tally.separated << " apart");
}

namespace {

/// A closed cube [0, 1]³ whose six faces are n × n grids of quads (two triangles each), shared
/// vertices along the edges; faces counter-clockwise seen from outside.
Mesh grid_cube(int n) {
  Mesh m;
  std::map<std::array<int, 3>, std::uint32_t> index;  // lattice point → vertex
  auto vertex = [&](std::array<int, 3> p) {
    const auto [it, added] = index.try_emplace(p, static_cast<std::uint32_t>(m.vertices.size()));
    if (added) m.vertices.emplace_back(double(p[0]) / n, double(p[1]) / n, double(p[2]) / n);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto at = [&](int di, int dj) {
            std::array<int, 3> p{};
            p[axis] = side * n;
            p[u] = i + di;
            p[v] = j + dj;
            return vertex(p);
          };
          const std::uint32_t a = at(0, 0), b = at(1, 0), c = at(1, 1), d = at(0, 1);
          // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
          if (side == 1) {
            m.faces.push_back({a, b, c});
            m.faces.push_back({a, c, d});
          } else {
            m.faces.push_back({a, c, b});
            m.faces.push_back({a, d, c});
          }
        }
    }
  return m;
}

}  // namespace

TEST_CASE("mesh truth: facing grids a few ulps apart, the minimum decided in the last bits",
          "[unit][mesh-truth]") {
  // Two grid cubes face to face along x, the facing faces' inner vertices moved by a few ulps,
  // so that hundreds of triangle pairs lie within rounding of the minimum: the floating-point
  // culling must keep every pair that can attain it. The brute force takes the triangles near
  // the facing faces (every other pair is at least 0.5 apart).
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> ulps(-4, 4);
  for (int trial = 0; trial < 3; ++trial) {
    Mesh a = grid_cube(4), b = grid_cube(4);
    for (Vec3& v : a.vertices)
      if (v.x() == 1 && v.y() > 0 && v.y() < 1 && v.z() > 0 && v.z() < 1)
        v.x() = 1 + ulps(rng) * std::numeric_limits<double>::epsilon();
    for (Vec3& v : b.vertices) {
      const bool inner = v.x() == 0 && v.y() > 0 && v.y() < 1 && v.z() > 0 && v.z() < 1;
      v.x() += 1 + 10 * std::numeric_limits<double>::epsilon();
      if (inner) v.x() += ulps(rng) * std::numeric_limits<double>::epsilon();
    }
    const exact::MeshTruth t = exact::mesh_truth(a, b);
    auto near = [](const Mesh& m, auto facing) {
      std::vector<Face> faces;
      for (const Face& f : m.faces)
        if (facing(m.vertices[f[0]]) || facing(m.vertices[f[1]]) || facing(m.vertices[f[2]]))
          faces.push_back(f);
      return faces;
    };
    const mpq_class best =
        brute_min_distance2(a, near(a, [](const Vec3& v) { return v.x() > 0.7; }), b,
                            near(b, [](const Vec3& v) { return v.x() < 1.3; }));
    INFO("trial " << trial << ": exact evaluations " << t.exact_distance_evaluations);
    CHECK(t.intersect == (best == 0));
    CHECK(as_mpq(t.distance_squared) == best);
  }
}
