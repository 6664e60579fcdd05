// Convex decompositions of closed meshes (hull, exact) and the convex algorithms run over their
// pieces, judged against the exact truth of the solids (exact::mesh_truth).
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/exact/convex_decomposition.hpp"
#include "gjklab/exact/hull_features.hpp"
#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/meshes/piece_query.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"

using namespace gjklab;
using experiment::Decomposition;

namespace {

/// The prism over a polygon (gjklab::prism_mesh).
TriangleMesh prism(const std::vector<PlanePoint>& polygon, double z0, double z1) {
  return prism_mesh(polygon, z0, z1);
}

/// An L: the unit square's 2 × 1 bar along x and 1 × 1 arm up y, one unit thick.
TriangleMesh l_prism() {
  return prism({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 0, 1);
}

TriangleMesh box(const Vec3& lo, const Vec3& hi) {
  return prism({{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}}, lo.z(),
               hi.z());
}

/// Six times the volume of the convex hull of a piece's corners (its hull mesh, fanned
/// triple products; exact for small integer coordinates).
double six_volume(const std::vector<Vec3>& corners) {
  const TriangleMesh hull = exact::hull_mesh(corners);
  double sum = 0;
  for (const MeshFace& f : hull.faces)
    sum += hull.vertices[f[0]].dot(hull.vertices[f[1]].cross(hull.vertices[f[2]]));
  return sum;
}

struct RigidMotion {
  Mat3 rotation;
  Vec3 shift;
  Vec3 operator()(const Vec3& v) const { return rotation * v + shift; }
};

TriangleMesh posed(TriangleMesh m, const RigidMotion& pose) {
  for (Vec3& v : m.vertices)
    v = pose(v);
  return m;
}

/// The decomposition's pieces moved by the pose exactly as the mesh's vertices are.
std::vector<Polytope> posed_pieces(const Decomposition& d, const RigidMotion& pose) {
  std::vector<Polytope> out;
  for (std::vector<Vec3> corners : d.pieces) {
    for (Vec3& c : corners)
      c = pose(c);
    out.emplace_back(std::move(corners));
  }
  return out;
}

Decomposition decomposed(const char* name, const TriangleMesh& m) {
  return experiment::decomposition_named(name).decompose(m, "test mesh", {});
}

const experiment::AlgorithmInfo& algorithm(const char* name) {
  const experiment::AlgorithmInfo* a = experiment::find_algorithm(name);
  REQUIRE(a != nullptr);
  return *a;
}

/// Whether moving B by `band` along one of the six axis directions separates the solids: the
/// pair is then within `band` of touching, where a floating-point answer may go either way.
bool within_band(const TriangleMesh& a, const TriangleMesh& b, double band) {
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {-1.0, 1.0}) {
      const Vec3 step = sign * band * Vec3::Unit(axis);
      if (!exact::mesh_truth(a, posed(b, {Mat3::Identity(), step})).intersect) return true;
    }
  return false;
}

}  // namespace

TEST_CASE("decompositions: by name, and an unknown name lists the valid ones",
          "[unit][decomposition]") {
  CHECK(experiment::decomposition_named("hull").name == "hull");
  CHECK(experiment::decomposition_named("exact").name == "exact");
  CHECK_THROWS_WITH(
      experiment::decomposition_named("vhacd"),
      Catch::Contains("unknown decomposition 'vhacd'") && Catch::Contains("hull, exact"));
  const Decomposition h = decomposed("hull", l_prism());
  REQUIRE(h.pieces.size() == 1);
  CHECK(h.pieces[0] == l_prism().vertices);
  CHECK_FALSE(h.proven);
}

TEST_CASE("exact decomposition: an L prism is convex pieces whose volumes add up to the L's",
          "[unit][decomposition]") {
  const TriangleMesh l = l_prism();
  REQUIRE_NOTHROW(exact::validate_closed_mesh(l, "L"));
  const Decomposition d = decomposed("exact", l);
  CHECK(d.proven);
  CHECK(d.pieces.size() >= 2);
  // Cut along the planes of the reflex edge (x = 1 or y = 1): every corner an integer point.
  CHECK(d.max_rounding == 0);
  double total = 0;
  for (const auto& piece : d.pieces) {
    for (const Vec3& c : piece) {
      CHECK((c.array() >= 0).all());
      CHECK((c.array() <= 2).all());
      CHECK(c == c.array().round().matrix());
    }
    total += six_volume(piece);
  }
  CHECK(total == 6 * 3.0);  // the L's volume is 3
}

TEST_CASE("exact decomposition: a convex mesh is one piece of its own corners",
          "[unit][decomposition]") {
  const TriangleMesh cube = box(Vec3(-1, -2, -3), Vec3(1, 2, 3));
  const Decomposition d = decomposed("exact", cube);
  REQUIRE(d.pieces.size() == 1);
  CHECK(d.max_rounding == 0);
  std::vector<Vec3> corners = d.pieces[0], vertices = cube.vertices;
  auto lex = [](const Vec3& x, const Vec3& y) {
    return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
  };
  std::sort(corners.begin(), corners.end(), lex);
  std::sort(vertices.begin(), vertices.end(), lex);
  CHECK(corners == vertices);
}

TEST_CASE("exact decomposition: beyond the face limit the reason is given",
          "[unit][decomposition]") {
  const TriangleMesh big = star_mesh(40, 30, [](const Vec3&) { return 1.0; });
  REQUIRE(big.faces.size() > exact::kMaxDecompositionFaces);
  CHECK_THROWS_AS(exact::exact_convex_decomposition(big, "big"), exact::DecompositionError);
  CHECK_THROWS_WITH(exact::exact_convex_decomposition(big, "big"),
                    Catch::Contains("big: exact convex decomposition: 2340 faces, more than the "
                                    "2000 it accepts"));
}

TEST_CASE(
    "box in the notch of an L: the hull says intersect, the exact pieces and the truth "
    "say apart",
    "[unit][decomposition]") {
  const TriangleMesh l = l_prism();
  // In the notch [1, 2] × [1, 2], a quarter unit from both arms of the L.
  const TriangleMesh inside_notch = box(Vec3(1.25, 1.25, 0), Vec3(1.75, 1.75, 1));
  const exact::MeshTruth truth = exact::mesh_truth(l, inside_notch);
  REQUIRE_FALSE(truth.intersect);
  CHECK(truth.distance == 0.25);
  const auto& gjk = algorithm("gjk-johnson");
  const experiment::AlgorithmOptions options;
  const auto hull_l = experiment::piece_polytopes(decomposed("hull", l));
  const auto exact_l = experiment::piece_polytopes(decomposed("exact", l));
  const auto notch = experiment::piece_polytopes(decomposed("hull", inside_notch));
  CHECK(experiment::run_on_pieces(gjk, hull_l, notch, options).outcome.intersect);
  const experiment::PieceOutcome pieces = experiment::run_on_pieces(gjk, exact_l, notch, options);
  CHECK_FALSE(pieces.outcome.intersect);
  CHECK(*pieces.outcome.distance == Approx(0.25).margin(1e-12));
  CHECK(pieces.piece_pairs == exact_l.size());
  CHECK(pieces.outcome.termination == Termination::converged);
}

TEST_CASE("piece query: the answer is the least over every pair of pieces, fewer pairs run",
          "[unit][decomposition]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> radius(0.4, 1.0);
  const TriangleMesh star = star_mesh(4, 7, [&](const Vec3&) { return radius(rng); });
  const auto pieces = experiment::piece_polytopes(decomposed("exact", star));
  REQUIRE(pieces.size() >= 3);
  const auto& gjk = algorithm("gjk-johnson");
  const experiment::AlgorithmOptions options;
  std::uniform_real_distribution<double> offset(-3, 3);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 shift(offset(rng), offset(rng), offset(rng));
    std::vector<Polytope> moved;
    for (const Polytope& p : pieces)
      moved.push_back(p.translated(shift));
    const experiment::PieceOutcome found = experiment::run_on_pieces(gjk, pieces, moved, options);
    bool any = false;
    double least = std::numeric_limits<double>::infinity();
    for (const Polytope& p : pieces)
      for (const Polytope& q : moved) {
        const experiment::Outcome o = experiment::run_algorithm(gjk, p, q, {}, options);
        any = any || o.intersect;
        if (!o.intersect) least = std::min(least, *o.distance);
      }
    CHECK(found.outcome.intersect == any);
    if (!any) CHECK(*found.outcome.distance == least);
    CHECK(found.piece_pairs == pieces.size() * pieces.size());
    CHECK(found.piece_pairs_tested <= found.piece_pairs);
    if (shift.norm() > 2.5) CHECK(found.piece_pairs_tested < found.piece_pairs);
  }
}

TEST_CASE("non-convex stars: GJK over the exact pieces is never wrong outside the touching band",
          "[unit][decomposition]") {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> radius(0.35, 1.0), unit(-1, 1), angle(0, 2 * M_PI);
  const TriangleMesh a = star_mesh(5, 8, [&](const Vec3&) { return radius(rng); });
  const TriangleMesh b = star_mesh(4, 7, [&](const Vec3&) { return radius(rng); });
  const Decomposition da = decomposed("exact", a), db = decomposed("exact", b);
  const auto pieces_a = experiment::piece_polytopes(da);
  const auto& gjk = algorithm("gjk-johnson");
  const experiment::AlgorithmOptions options;
  constexpr double kBand = 1e-9;  // absolute, length units; the meshes have radius ≤ 1
  int checked = 0, intersecting = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Vec3 axis = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const RigidMotion pose{Eigen::AngleAxisd(angle(rng), axis).toRotationMatrix(),
                           1.6 * Vec3(unit(rng), unit(rng), unit(rng))};
    const TriangleMesh moved = posed(b, pose);
    const exact::MeshTruth truth = exact::mesh_truth(a, moved);
    const experiment::PieceOutcome p =
        experiment::run_on_pieces(gjk, pieces_a, posed_pieces(db, pose), options);
    if (truth.intersect) {
      if (!p.outcome.intersect) CHECK(within_band(a, moved, kBand));
      intersecting += truth.intersect;
    } else if (truth.distance > kBand) {
      CHECK_FALSE(p.outcome.intersect);
      CHECK(std::abs(*p.outcome.distance - truth.distance) <= 1e-9);
    }
    ++checked;
  }
  CHECK(intersecting > 10);
  CHECK(checked - intersecting > 10);
}

TEST_CASE("generated meshes: prisms and solids of revolution are closed meshes",
          "[unit][decomposition]") {
  std::vector<PlanePoint> circle;
  for (int k = 0; k < 10; ++k)
    circle.push_back({1 + 0.3 * std::cos(2 * M_PI * k / 10), 0.3 * std::sin(2 * M_PI * k / 10)});
  const std::vector<PlanePoint> cup = {{0, 0},      {1, 0},       {1, 1.2},
                                       {0.85, 1.2}, {0.85, 0.15}, {0, 0.15}};
  const std::vector<PlanePoint> washer = {{0.5, -0.25}, {1, -0.25}, {1, 0.25}, {0.5, 0.25}};
  const std::vector<PlanePoint> peg = {{0, -1}, {0.3, -1}, {0.3, 1}, {0, 1}};
  CHECK_NOTHROW(exact::validate_closed_mesh(lathe_mesh(circle, 12, true), "torus"));
  CHECK_NOTHROW(exact::validate_closed_mesh(lathe_mesh(cup, 16, false), "cup"));
  CHECK_NOTHROW(exact::validate_closed_mesh(lathe_mesh(washer, 7, true), "washer"));
  CHECK_NOTHROW(exact::validate_closed_mesh(lathe_mesh(peg, 3, false), "peg"));
  CHECK_NOTHROW(exact::validate_closed_mesh(l_prism(), "L"));
  CHECK(lathe_mesh(circle, 12, true).faces.size() == 2 * 10 * 12);
  CHECK(lathe_mesh(cup, 16, false).faces.size() == 2 * 16 * 4);  // 3 bands and 2 pole fans
  // A clockwise profile turns the solid inside out, which the checks refuse.
  std::vector<PlanePoint> clockwise(circle.rbegin(), circle.rend());
  CHECK_THROWS_WITH(exact::validate_closed_mesh(lathe_mesh(clockwise, 12, true), "inverted"),
                    Catch::Contains("negative signed volume"));
  CHECK_THROWS_WITH(lathe_mesh(cup, 16, true), Catch::Contains("point 0 must have r > 0"));
  CHECK_THROWS_WITH(lathe_mesh(washer, 16, false), Catch::Contains("starts and ends on the axis"));
  CHECK_THROWS_WITH(lathe_mesh(peg, 2, false), Catch::Contains("segments >= 3"));
  CHECK_THROWS_WITH(prism_mesh(std::vector<PlanePoint>{{0, 0}, {1, 0}}, 0, 1),
                    Catch::Contains("at least 3 corners"));
  CHECK_THROWS_WITH(prism_mesh(cup, 1, 1), Catch::Contains("z0 < z1"));
}

TEST_CASE("interlocking rings: the hulls meet, the solids do not, the exact pieces agree",
          "[unit][decomposition]") {
  std::vector<PlanePoint> hexagon;
  for (int k = 0; k < 6; ++k)
    hexagon.push_back({1 + 0.2 * std::cos(M_PI * k / 3), 0.2 * std::sin(M_PI * k / 3)});
  const TriangleMesh ring = lathe_mesh(hexagon, 8, true);
  // The second ring stands in the plane y = 0, through the first one's hole.
  TriangleMesh linked = ring;
  for (Vec3& v : linked.vertices)
    v = Vec3(v.x() + 1, v.z(), v.y());
  for (MeshFace& f : linked.faces)  // swapping y and z mirrors the ring: turn its faces back
    std::swap(f[1], f[2]);
  REQUIRE_NOTHROW(exact::validate_closed_mesh(linked, "linked ring"));
  const exact::MeshTruth truth = exact::mesh_truth(ring, linked);
  REQUIRE_FALSE(truth.intersect);
  CHECK(truth.distance > 0.4);
  const auto& gjk = algorithm("gjk-johnson");
  const experiment::AlgorithmOptions options;
  const auto hull_a = experiment::piece_polytopes(decomposed("hull", ring));
  const auto hull_b = experiment::piece_polytopes(decomposed("hull", linked));
  CHECK(experiment::run_on_pieces(gjk, hull_a, hull_b, options).outcome.intersect);
  const auto exact_a = experiment::piece_polytopes(decomposed("exact", ring));
  const auto exact_b = experiment::piece_polytopes(decomposed("exact", linked));
  const experiment::PieceOutcome p = experiment::run_on_pieces(gjk, exact_a, exact_b, options);
  CHECK_FALSE(p.outcome.intersect);
  CHECK(std::abs(*p.outcome.distance - truth.distance) <= 1e-9);
}

TEST_CASE("decomposition options: set by key from text, refused by name, range and form",
          "[unit][decomposition]") {
  experiment::DecompositionOptions options;
  const auto& exact_info = experiment::decomposition_named("exact");
  CHECK_THROWS_WITH(
      experiment::set_decomposition_option(exact_info, options, "concavity", "50"),
      Catch::Contains("decomposition 'exact' takes no option 'concavity'; it takes none"));
#ifdef GJKLAB_HAVE_HACD
  const auto& approximate = experiment::decomposition_named("approximate");
  experiment::set_decomposition_option(approximate, options, "concavity", "50");
  experiment::set_decomposition_option(approximate, options, "min_clusters", "3");
  experiment::set_decomposition_option(approximate, options, "add_faces_points", "true");
  CHECK(options.hacd.concavity == 50);
  CHECK(options.hacd.min_clusters == 3);
  CHECK(options.hacd.add_faces_points);
  CHECK_THROWS_WITH(
      experiment::set_decomposition_option(approximate, options, "min_clusters", "2.5"),
      Catch::Contains("option 'min_clusters': cannot read '2.5'"));
  CHECK_THROWS_WITH(experiment::set_decomposition_option(approximate, options, "concavity", "nan"),
                    Catch::Contains("cannot read 'nan'"));
  CHECK_THROWS_AS(experiment::set_decomposition_option(approximate, options, "min_clusters", "0"),
                  std::invalid_argument);
  CHECK_THROWS_WITH(experiment::set_decomposition_option(approximate, options, "clusters", "3"),
                    Catch::Contains("its options: min_clusters, concavity"));
  // The options reach HACD: merging stops at min_clusters (2 by default), and the L's
  // concavity as HACD measures it at the vertices is 0, so with 1 it merges into one piece.
  experiment::DecompositionOptions one;
  experiment::set_decomposition_option(approximate, one, "min_clusters", "1");
  CHECK(approximate.decompose(l_prism(), "L", one).pieces.size() <
        approximate.decompose(l_prism(), "L", {}).pieces.size());
#endif
}
