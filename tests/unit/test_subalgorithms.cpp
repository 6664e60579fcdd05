// The distance sub-algorithms as GJK policies (Johnson, Johnson with backup, signed volumes,
// Voronoi regions): every Voronoi region of the segment, triangle and tetrahedron in every
// point order, degenerate simplices, and the backup procedure's search.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "../support/simplex_regions.hpp"
#include "gjklab/gjk/subalgorithms.hpp"

using namespace gjklab;

namespace {

/// A simplex of the points y (a = y, b = 0), each tagged with its position in index_a.
Simplex simplex_of(const std::array<Vec3, 4>& y, int count) {
  Simplex s;
  for (int i = 0; i < count; ++i) {
    SimplexVertex v;
    v.w = y[i];
    v.a = y[i];
    v.b = Vec3(0, 0, 0);
    v.index_a = i;
    s.push(v);
  }
  return s;
}

/// Bitmask of the original positions kept in s, and whether they kept their order.
unsigned kept_mask(const Simplex& s, bool& ordered) {
  unsigned mask = 0;
  ordered = true;
  for (int i = 0; i < s.size(); ++i) {
    if (i > 0 && s[i].index_a <= s[i - 1].index_a) ordered = false;
    mask |= 1u << s[i].index_a;
  }
  return mask;
}

struct Reduced {
  bool ok = false;
  Simplex simplex;
  ClosestOnSimplex closest;
};

template <class Sub>
Reduced reduce_with(const std::array<Vec3, 4>& y, int count) {
  Reduced r;
  r.simplex = simplex_of(y, count);
  r.ok = Sub{}.reduce(r.simplex, r.closest);
  return r;
}

/// Checks one region case through the policy interface; returns the number of cases.
template <class Sub>
/// Returns the number of region cases checked.
int check_regions(const char* name, double tolerance) {
  int checked = 0;
  testing::for_each_region_case([&](const testing::RegionCase& c) {
    const Reduced r = reduce_with<Sub>(c.y, c.count);
    INFO(name << ": count " << c.count << " feature " << c.feature << " closest "
              << c.closest.transpose());
    REQUIRE(r.ok);
    bool ordered = false;
    CHECK(kept_mask(r.simplex, ordered) == c.feature);
    CHECK(ordered);
    CHECK((r.closest.v - c.closest).norm() <= tolerance);
    // Weights of the kept points, in order: positive, summing to 1, reproducing v.
    double sum = 0;
    Vec3 combination = Vec3::Zero();
    for (int k = 0; k < r.simplex.size(); ++k) {
      CHECK(r.closest.weights[k] > 0);
      sum += r.closest.weights[k];
      combination += r.closest.weights[k] * r.simplex[k].w;
    }
    CHECK(sum == Approx(1.0).epsilon(1e-15));
    CHECK((combination - r.closest.v).norm() <= tolerance);
    CHECK((r.closest.witness_a - r.closest.witness_b - r.closest.v).norm() <= tolerance);
    ++checked;
  });
  CHECK(checked > 500);
  return checked;
}

}  // namespace

TEST_CASE("sub-algorithms: every region of the segment, triangle and tetrahedron",
          "[unit][subalgorithm]") {
  // Every policy sees the same region cases.
  const int johnson = check_regions<JohnsonSubAlgorithm>("johnson", 1e-15);
  CHECK(check_regions<JohnsonBackupSubAlgorithm>("johnson-backup", 1e-15) == johnson);
  CHECK(check_regions<SignedVolumesSubAlgorithm>("signed volumes", 1e-15) == johnson);
  CHECK(check_regions<VoronoiSubAlgorithm>("voronoi", 1e-15) == johnson);
}

TEMPLATE_TEST_CASE("sub-algorithms: degenerate simplices", "[unit][subalgorithm]",
                   JohnsonBackupSubAlgorithm, SignedVolumesSubAlgorithm, VoronoiSubAlgorithm) {
  struct Degenerate {
    std::string name;
    std::array<Vec3, 4> y;
    int count;
    Vec3 closest;
  };
  const std::vector<Degenerate> cases = {
      {"repeated point in a segment", {Vec3(1, 2, 3), Vec3(1, 2, 3)}, 2, Vec3(1, 2, 3)},
      {"collinear triangle", {Vec3(1, 1, -1), Vec3(1, 1, 2), Vec3(1, 1, 4)}, 3, Vec3(1, 1, 0)},
      {"collinear triangle, middle point nearest",
       {Vec3(1, 1, 3), Vec3(1, 1, 1), Vec3(1, 1, 2)},
       3,
       Vec3(1, 1, 1)},
      {"triangle with a repeated vertex",
       {Vec3(-1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)},
       3,
       Vec3(0, 1, 1)},
      {"triangle collapsed to a point",
       {Vec3(2, 1, 1), Vec3(2, 1, 1), Vec3(2, 1, 1)},
       3,
       Vec3(2, 1, 1)},
      {"coplanar tetrahedron off the origin",
       {Vec3(-1, -1, 1), Vec3(2, -1, 1), Vec3(-1, 2, 1), Vec3(1, 2, 1)},
       4,
       Vec3(0, 0, 1)},
      {"coplanar tetrahedron, nearest point on an edge",
       {Vec3(1, -1, 1), Vec3(1, 1, 1), Vec3(3, -1, 1), Vec3(3, 1, 1)},
       4,
       Vec3(1, 0, 1)},
      {"tetrahedron with two repeated points",
       {Vec3(1, -1, 2), Vec3(1, 1, 2), Vec3(1, -1, 2), Vec3(1, 1, 2)},
       4,
       Vec3(1, 0, 2)},
      {"collinear tetrahedron",
       {Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(5, 0, 0), Vec3(4, 0, 0)},
       4,
       Vec3(2, 0, 0)},
  };
  for (const Degenerate& c : cases) {
    INFO(c.name);
    const Reduced r = reduce_with<TestType>(c.y, c.count);
    REQUIRE(r.ok);
    CHECK((r.closest.v - c.closest).norm() <= 1e-15);
    CHECK(r.simplex.size() >= 1);
    CHECK(r.simplex.size() < c.count);  // a degenerate simplex never survives whole
    double sum = 0;
    for (int k = 0; k < r.simplex.size(); ++k)
      sum += r.closest.weights[k];
    CHECK(sum == Approx(1.0).epsilon(1e-15));
  }
}

TEST_CASE("signed volumes: the paper's sign tests on a tetrahedron around the origin",
          "[unit][subalgorithm]") {
  // The origin inside: all four cofactors share det M's sign, weights are the barycentrics.
  const std::array<Vec3, 4> y = {Vec3(-1, -1, -1), Vec3(3, -1, -1), Vec3(-1, 3, -1),
                                 Vec3(-1, -1, 3)};
  const SubsimplexSolution s = signed_volumes_closest_point(y, 4);
  REQUIRE(s.found);
  CHECK(s.subset == 0b1111);
  for (double w : s.weights)
    CHECK(w == Approx(0.25).epsilon(1e-15));
  CHECK(s.closest.norm() <= 1e-15);
  // The same points with the origin moved beyond the face opposite y_0: that face wins.
  std::array<Vec3, 4> moved;
  for (int i = 0; i < 4; ++i)
    moved[i] = y[i] - Vec3(3, 3, 3);
  const SubsimplexSolution f = signed_volumes_closest_point(moved, 4);
  CHECK(f.subset == 0b1110);
  CHECK((f.closest - Vec3(-8, -8, -8) / 3.0).norm() <= 1e-14);  // the face centroid
}

TEST_CASE("johnson backup: decides where Johnson's tests accept no subset",
          "[unit][subalgorithm]") {
  // A sliver tetrahedron: four points within 1e-15 of the plane z = 1, the origin's
  // projection inside. Its rounded cofactors fail Johnson's tests for every subset (found
  // by a seeded search over such slivers, where about 1 in 120 fails; kept as exact doubles).
  const std::array<Vec3, 4> y = {
      Vec3(0x1.f6c583d53202p-4, 0x1.95b8519956244p-2, 0x1.0000000000004p+0),
      Vec3(-0x1.aa3e21f76b4bp-3, -0x1.d6921c6ea8638p-3, 0x1.0000000000004p+0),
      Vec3(0x1.8aac64fb0c3ecp-1, -0x1.4676b5a1e2dacp-1, 0x1p+0),
      Vec3(0x1.6376c2f2ba05cp-1, 0x1.b1749b3ca0098p-2, 0x1.0000000000002p+0)};
  REQUIRE_FALSE(johnson_closest_point(y, 4).found);
  bool used_backup = false;
  const JohnsonSolution backup = johnson_closest_point_with_backup(y, 4, &used_backup);
  REQUIRE(backup.found);
  CHECK(used_backup);
  CHECK((backup.closest - Vec3(0, 0, 1)).norm() <= 1e-14);
  // The backup's answer is the nearest affine closest point over the subsets with positive
  // cofactors, and it is one of them.
  const JohnsonCofactors c = johnson_cofactors(y, 4);
  CHECK(johnson_subset_has_positive_cofactors(c, backup.subset, 4));
  int candidates = 0;
  for (std::uint8_t x = 1; x < 16; ++x) {
    if (!johnson_subset_has_positive_cofactors(c, x, 4)) continue;
    JohnsonSolution candidate;
    candidate.subset = x;
    for (int i = 0; i < 4; ++i)
      if (x & (1u << i)) candidate.closest += (c.delta[x][i] / c.total[x]) * y[i];
    refine_triangle_point(candidate, y);  // as every sub-algorithm evaluates a triangle's point
    CHECK(backup.closest.squaredNorm() <= candidate.closest.squaredNorm());
    ++candidates;
  }
  CHECK(candidates >= 4);  // at least the singletons
  // Through the policy: the plain Johnson policy cannot decide, the backup policy can.
  Simplex plain_simplex, backup_simplex;
  for (int i = 0; i < 4; ++i) {
    SimplexVertex v;
    v.w = v.a = y[i];
    plain_simplex.push(v);
    backup_simplex.push(v);
  }
  ClosestOnSimplex out;
  CHECK_FALSE(JohnsonSubAlgorithm{}.reduce(plain_simplex, out));
  CHECK(plain_simplex.size() == 4);  // left untouched
  CHECK(JohnsonBackupSubAlgorithm{}.reduce(backup_simplex, out));
  CHECK(backup_simplex.size() == std::popcount(static_cast<unsigned>(backup.subset)));
  CHECK(out.v == backup.closest);
}

TEST_CASE(
    "a triangle 2.6e-10 from the origin (fcl issue 445's boxes): every sub-algorithm's point is "
    "normal to the face",
    "[unit][subalgorithm]") {
  // The triangle GJK ends on for the rotated stacked boxes of fcl issue 445, whose difference
  // holds the origin 4.6e-11 deep: vertices A[2] − B[5], A[2] − B[6] and A[3] − B[4] of
  // tests/regression/data/fcl_445_stacked_rotated_boxes_touching.jsonl, 0.25 from the origin,
  // with the plane 2.6e-10 from it. v = Σ λ y cancels to 1e-9 of the points' size and was
  // tilted off the face normal by 1e-7: the triangle's own vertex then had v·y = −5e-18, below
  // ‖v‖² = 6.8e-20, and looked like a support point beyond the origin. The plane's projection
  // is normal to the face to rounding: v·y_k = ‖v‖² within 1e-6 of ‖v‖² for every vertex.
  const Vec3 a2(0x1.4bf4641e75b3ep+0, 0x1.a5c0dea505c07p+0, 0x1.a02756e7a8c1cp-2);
  const Vec3 a3(0x1.4bf46417b4d0ep+0, 0x1.a5c0de8f0a4fep+0, 0x1.2a993307b1f8cp-1);
  const Vec3 b4(0x1.149bf2813b68ap+0, 0x1.8a811a21b3508p+0, 0x1.a02756672fc7fp-2);
  const Vec3 b5(0x1.149bf280b53bbp+0, 0x1.8a811a20087eap+0, 0x1.ed2890f9d2cd4p-2);
  const Vec3 b6(0x1.660d0b52d409ep+0, 0x1.b29a0eed329c5p+0, 0x1.a027567df24dep-2);
  const std::array<Vec3, 4> y = {a2 - b5, a2 - b6, a3 - b4, Vec3::Zero()};
  const auto check_normal = [&](const Vec3& v, std::uint8_t subset) {
    CHECK(subset == 0b0111);
    CHECK(v.norm() == Approx(2.6033708e-10).epsilon(1e-6));
    for (int k = 0; k < 3; ++k)
      CHECK(std::abs(v.dot(y[k]) - v.squaredNorm()) <= 1e-6 * v.squaredNorm());
  };
  const JohnsonSolution johnson = johnson_closest_point(y, 3);
  check_normal(johnson.closest, johnson.subset);
  const SubsimplexSolution sv = signed_volumes_closest_point(y, 3);
  check_normal(sv.closest, sv.subset);
  const SubsimplexSolution voronoi = voronoi_closest_point(y, 3);
  check_normal(voronoi.closest, voronoi.subset);
  // The weighted sum itself, for contrast: off the normal by far more than rounding.
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
    sum += johnson.weights[k] * y[k];
  double worst = 0;
  for (int k = 0; k < 3; ++k)
    worst = std::max(worst, std::abs(sum.dot(y[k]) - sum.squaredNorm()));
  CHECK(worst > 10 * sum.squaredNorm());
}

TEST_CASE(
    "a sliver triangle around the origin (fcl issue 399's box and wall): every sub-algorithm's "
    "point is the origin",
    "[unit][subalgorithm]") {
  // The triangle GJK ends on for fcl issue 399's box and thin wall, whose difference holds the
  // origin 3.4e-5 deep: vertices A[0] − B[4], A[4] − B[6] and A[4] − B[4] of
  // tests/regression/data/fcl_399_box_thin_wall_epa.jsonl, all at z = 0, nearly collinear
  // (the third 4e-5 off the line of the others), around the origin with weights (0.65, 0.35,
  // 3.7e-4). Σ λ y lost 1.7e-9 to the weights' rounding, far beyond 64 ε of the points, so the
  // plane's foot (the origin) was refused and the query ended "apart, 1.7e-9". Every weight
  // is far above what that distance can change (foot_inside_triangle): the foot is taken.
  const std::array<Vec3, 4> y = {Vec3(0x1.200e8af450eb8p-5, 0x1.68f1204972e74p-2, 0),
                                 Vec3(-0x1.0e6d6e0ab46e8p-4, -0x1.52da2584b7aa8p-1, 0),
                                 Vec3(0x1.79d121aaed8a0p-7, 0x1.db0da69972735p-4, 0), Vec3::Zero()};
  const JohnsonSolution johnson = johnson_closest_point(y, 3);
  REQUIRE(johnson.subset == 0b0111);
  CHECK(johnson.weights[2] > 1e-4);
  CHECK(johnson.closest.norm() <= 1e-15);
  const SubsimplexSolution sv = signed_volumes_closest_point(y, 3);
  CHECK(sv.closest.norm() <= 1e-15);
  const SubsimplexSolution voronoi = voronoi_closest_point(y, 3);
  REQUIRE(voronoi.subset == 0b0111);
  CHECK(voronoi.closest.norm() <= 1e-15);
  // The weighted sum itself, for contrast: a thousand times the points' rounding from 0.
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
    sum += johnson.weights[k] * y[k];
  CHECK(sum.norm() > 1e-12);
}
