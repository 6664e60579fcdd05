// Johnson's sub-algorithm on every Voronoi region of the segment, triangle and tetrahedron
// sub-problems, and on degenerate simplices.
#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <vector>

#include "../support/simplex_regions.hpp"
#include "gjklab/gjk/johnson.hpp"

using gjklab::johnson_closest_point;
using gjklab::Vec3;

TEST_CASE("johnson: every region of the segment, triangle and tetrahedron", "[unit][johnson]") {
  // Every point order: the recursion must not depend on the order.
  int checked = 0;
  gjklab::testing::for_each_region_case([&](const gjklab::testing::RegionCase& c) {
    const auto s = johnson_closest_point(c.y, c.count);
    INFO("count " << c.count << " feature " << c.feature << " closest " << c.closest.transpose());
    REQUIRE(s.found);
    CHECK(s.subset == c.feature);
    CHECK((s.closest - c.closest).norm() <= 1e-15);
    const double weight_sum = std::accumulate(s.weights.begin(), s.weights.end(), 0.0);
    CHECK(weight_sum == Approx(1.0).epsilon(1e-15));
    ++checked;
  });
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
