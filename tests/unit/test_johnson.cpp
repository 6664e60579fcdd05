// Johnson's sub-algorithm on every Voronoi region of the segment, triangle and tetrahedron
// sub-problems, and on degenerate simplices.
#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <vector>

#include "gjklab/gjk/johnson.hpp"

using gjklab::johnson_closest_point;
using gjklab::Vec3;

namespace {

/// The corner tetrahedron 0, e1, e2, e3: every region's normal cone is easy to enumerate.
const std::array<Vec3, 4> kCorner = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};

/// Directions n with n ⊥ aff(F) and n·(y_j − p) < 0 for every j ∉ F: offsetting the origin
/// by p + n puts it in the Voronoi region of feature F (p = centroid of F).
std::vector<Vec3> normal_cone_samples(const std::array<Vec3, 4>& y, int count, unsigned feature) {
  Vec3 p = Vec3::Zero();
  int n_in = 0;
  for (int i = 0; i < count; ++i)
    if (feature & (1u << i)) p += y[i], ++n_in;
  p /= n_in;
  std::vector<Vec3> out;
  for (int x = -2; x <= 2; ++x)
    for (int yy = -2; yy <= 2; ++yy)
      for (int z = -2; z <= 2; ++z) {
        const Vec3 n(x, yy, z);
        bool ok = true;
        for (int i = 0; i < count && ok; ++i) {
          const double along = n.dot(y[i] - p);
          ok = (feature & (1u << i)) ? along == 0 : along < 0;
        }
        // Zero offset only for the full tetrahedron (origin strictly inside).
        if (ok && (n != Vec3::Zero() || (count == 4 && feature == 15u))) out.push_back(n);
      }
  return out;
}

Vec3 centroid(const std::array<Vec3, 4>& y, int count, unsigned feature) {
  Vec3 p = Vec3::Zero();
  int n = 0;
  for (int i = 0; i < count; ++i)
    if (feature & (1u << i)) p += y[i], ++n;
  return p / n;
}

}  // namespace

TEST_CASE("johnson: every region of the segment, triangle and tetrahedron", "[unit][johnson]") {
  int checked = 0;
  for (int count = 1; count <= 4; ++count) {
    // Try each ordering of the simplex points: the recursion must not depend on the order.
    std::array<int, 4> order{0, 1, 2, 3};
    do {
      std::array<Vec3, 4> y;
      for (int i = 0; i < count; ++i) y[i] = kCorner[order[i]];
      for (unsigned feature = 1; feature < (1u << count); ++feature) {
        const Vec3 p = centroid(y, count, feature);
        for (const Vec3& n : normal_cone_samples(y, count, feature)) {
          std::array<Vec3, 4> shifted;
          for (int i = 0; i < count; ++i) shifted[i] = y[i] - (p + n);
          const auto s = johnson_closest_point(shifted, count);
          INFO("count " << count << " feature " << feature << " n " << n.transpose());
          REQUIRE(s.found);
          CHECK(s.subset == feature);
          CHECK((s.closest + n).norm() <= 1e-15);
          const double weight_sum = std::accumulate(s.weights.begin(), s.weights.end(), 0.0);
          CHECK(weight_sum == Approx(1.0).epsilon(1e-15));
          ++checked;
        }
      }
    } while (std::next_permutation(order.begin(), order.begin() + count));
  }
  // Every region was reached with several offsets (guards against an empty enumeration).
  CHECK(checked > 500);
}

TEST_CASE("johnson: repeated point in a segment", "[unit][johnson]") {
  const std::array<Vec3, 4> y = {Vec3(1, 2, 3), Vec3(1, 2, 3)};
  const auto s = johnson_closest_point(y, 2);
  REQUIRE(s.found);
  CHECK(s.closest == Vec3(1, 2, 3));
  CHECK(std::popcount(static_cast<unsigned>(s.subset)) == 1);
}

TEST_CASE("johnson: collinear triangle reduces to the right segment or vertex", "[unit][johnson]") {
  // Points on the line x = 1, y = 1: the closest point of the segment to the origin is (1,1,0).
  const std::array<Vec3, 4> y = {Vec3(1, 1, -1), Vec3(1, 1, 2), Vec3(1, 1, 4)};
  const auto s = johnson_closest_point(y, 3);
  REQUIRE(s.found);
  CHECK(s.subset == 0b011);
  CHECK((s.closest - Vec3(1, 1, 0)).norm() <= 1e-15);
}

TEST_CASE("johnson: triangle with a repeated vertex", "[unit][johnson]") {
  const std::array<Vec3, 4> y = {Vec3(-1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)};
  const auto s = johnson_closest_point(y, 3);
  REQUIRE(s.found);
  CHECK((s.closest - Vec3(0, 1, 1)).norm() <= 1e-15);
}

TEST_CASE("johnson: coplanar tetrahedron off the origin reduces to a face", "[unit][johnson]") {
  // All four points on z = 1; the origin projects to (0,0,1), inside triangles but on no edge.
  const std::array<Vec3, 4> y = {Vec3(-1, -1, 1), Vec3(2, -1, 1), Vec3(-1, 2, 1), Vec3(1, 2, 1)};
  const auto s = johnson_closest_point(y, 4);
  REQUIRE(s.found);
  CHECK(std::popcount(static_cast<unsigned>(s.subset)) == 3);
  CHECK((s.closest - Vec3(0, 0, 1)).norm() <= 1e-15);
}

TEST_CASE("johnson: tetrahedron with two repeated points", "[unit][johnson]") {
  const std::array<Vec3, 4> y = {Vec3(1, -1, 2), Vec3(1, 1, 2), Vec3(1, -1, 2), Vec3(1, 1, 2)};
  const auto s = johnson_closest_point(y, 4);
  REQUIRE(s.found);
  CHECK((s.closest - Vec3(1, 0, 2)).norm() <= 1e-15);
}

TEST_CASE("johnson: cofactors of a segment are the barycentric numerators", "[unit][johnson]") {
  const std::array<Vec3, 4> y = {Vec3(-1, 1, 0), Vec3(3, 1, 0)};
  const auto c = gjklab::johnson_cofactors(y, 2);
  // Δ_0({0,1}) = (y1 − y0)·y1 = 12, Δ_1({0,1}) = (y0 − y1)·y0 = 4: weights 3/4 and 1/4.
  CHECK(c.delta[3][0] == 12);
  CHECK(c.delta[3][1] == 4);
  CHECK(c.total[3] == 16);
}
