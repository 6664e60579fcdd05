// Support functions: the blocked scan returns the textbook loop's index (first maximiser, ties
// included), and hill climbing over the exact hull's vertex graph returns a maximiser.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "../support/random_pairs.hpp"
#include "gjklab/exact/hull_adjacency.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/geometry/support.hpp"

using namespace gjklab;
using gjklab::testing::Rng;

namespace {

/// The loop the blocked scan must reproduce: Eigen's dot, strict >, first index on ties.
std::size_t textbook_support(std::span<const Vec3> v, const Vec3& d) {
  std::size_t best = 0;
  double best_dot = v[0].dot(d);
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double dot = v[i].dot(d);
    if (dot > best_dot) {
      best_dot = dot;
      best = i;
    }
  }
  return best;
}

double max_dot(std::span<const Vec3> v, const Vec3& d) {
  return v[textbook_support(v, d)].dot(d);
}

/// Points on a small integer grid (many exact ties and repeated points).
std::vector<Vec3> grid_cloud(Rng& rng, int n) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i)
    pts.emplace_back(rng.integer(-2, 2), rng.integer(-2, 2), rng.integer(-2, 2));
  return pts;
}

std::vector<Vec3> sphere_cloud(Rng& rng, int n) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i)
    pts.push_back(rng.unit_vector());
  return pts;
}

/// Directions that produce ties on grids: axes, diagonals, with small integer components.
Vec3 tie_direction(Rng& rng) {
  for (;;) {
    const Vec3 d(rng.integer(-1, 1), rng.integer(-1, 1), rng.integer(-1, 1));
    if (!d.isZero()) return d;
  }
}

Mat3 random_rotation(Rng& rng) {
  const Quat q(rng.normal(), rng.normal(), rng.normal(), rng.normal());
  return q.normalized().toRotationMatrix();
}

}  // namespace

TEST_CASE("blocked scan returns the textbook loop's index on random clouds, ties included",
          "[unit][support]") {
  Rng rng(20240601);
  int ties_seen = 0, checks = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // Sizes across the block boundaries (padding) and a few larger clouds.
    const int n = trial < 300 ? 1 + trial % 40 : rng.integer(41, 3000);
    const bool grid = trial % 2 == 0;
    const std::vector<Vec3> cloud = grid ? grid_cloud(rng, n) : sphere_cloud(rng, n);
    const Polytope p(cloud);
    for (int k = 0; k < 20; ++k) {
      const Vec3 d = k % 2 ? rng.unit_vector() * rng.log_uniform(1e-3, 1e3) : tie_direction(rng);
      const std::size_t expected = textbook_support(cloud, d);
      REQUIRE(p.scan_support_index(d) == expected);
      REQUIRE(p.support_index(d) == expected);
      ++checks;
      int maximisers = 0;
      for (const Vec3& v : cloud)
        maximisers += v.dot(d) == cloud[expected].dot(d);
      ties_seen += maximisers > 1;
    }
  }
  // The sample must exercise ties (on the grids), or the tie rule is untested.
  CHECK(ties_seen > checks / 10);
}

TEST_CASE("blocked scan: zero, NaN and overflowing directions as the textbook loop",
          "[unit][support]") {
  Rng rng(7);
  const std::vector<Vec3> cloud = sphere_cloud(rng, 37);
  const Polytope p(cloud);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double big = std::numeric_limits<double>::max();
  for (const Vec3& d : {Vec3(0, 0, 0), Vec3(nan, 0, 0), Vec3(nan, nan, nan), Vec3(big, big, big),
                        Vec3(big, -big, 0), Vec3(-big, 0, 0)})
    CHECK(p.scan_support_index(d) == textbook_support(cloud, d));
  // The demo shapes have many exact ties along the axes.
  for (const Polytope& s : {shapes::box(), shapes::cone(), shapes::cylinder(), shapes::uv_sphere()})
    for (const Vec3& d :
         {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(1, 1, 0), Vec3(0, 0, -1)})
      CHECK(s.support_index(d) == textbook_support(s.vertices(), d));
}

TEST_CASE("paired scan returns the two single scans' indices, ties and NaN included",
          "[unit][support]") {
  Rng rng(20261121);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double big = std::numeric_limits<double>::max();
  for (int trial = 0; trial < 200; ++trial) {
    // Different sizes on the two sides, across block boundaries.
    const int na = 1 + trial % 37, nb = 1 + (trial * 7) % 53;
    const bool grid = trial % 2 == 0;
    const std::vector<Vec3> ca = grid ? grid_cloud(rng, na) : sphere_cloud(rng, na);
    const std::vector<Vec3> cb = grid ? grid_cloud(rng, nb) : sphere_cloud(rng, nb);
    const Polytope a(ca), b(cb);
    for (int k = 0; k < 12; ++k) {
      Vec3 d = k % 2 ? rng.unit_vector() * rng.log_uniform(1e-3, 1e3) : tie_direction(rng);
      if (k == 10) d = Vec3(nan, 1, 0);
      if (k == 11) d = Vec3(big, -big, 0);
      const auto [i, j] = scan_support_pair(a, d, b);
      REQUIRE(i == textbook_support(ca, d));
      REQUIRE(j == textbook_support(cb, -d));
    }
  }
}

TEST_CASE("is_finite and is_zero answer as Eigen's allFinite and isZero(0)", "[unit][support]") {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double big = std::numeric_limits<double>::max();
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double values[] = {0.0, -0.0, 1.0, -2.5, big, -big, tiny, inf, -inf, nan};
  for (double x : values)
    for (double y : values)
      for (double z : values) {
        const Vec3 v(x, y, z);
        REQUIRE(is_finite(v) == v.allFinite());
        REQUIRE(is_zero(v) == v.isZero(0));
      }
}

TEST_CASE("polytope copies keep the scan layout, and vertex_mean is the mean", "[unit][support]") {
  Rng rng(3);
  const std::vector<Vec3> cloud = sphere_cloud(rng, 21);
  Polytope p(cloud);
  const Polytope copy = p;
  Polytope moved = std::move(p);
  const Vec3 d(0.3, -0.2, 0.9);
  CHECK(copy.support_index(d) == textbook_support(cloud, d));
  CHECK(moved.support_index(d) == textbook_support(cloud, d));
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : cloud)
    sum += v;
  CHECK(copy.vertex_mean() == sum / 21.0);
  const Polytope scaled = copy.scaled(2.0);
  CHECK(scaled.support_index(d) == textbook_support(scaled.vertices(), d));
}

TEST_CASE("hull adjacency: symmetric, in range, and the expected degrees on simple clouds",
          "[unit][hill-climbing]") {
  // A cube with repeated corners and an interior point.
  std::vector<Vec3> cube;
  for (int i = 0; i < 8; ++i)
    cube.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  cube.push_back(Vec3(0.5, 0.5, 0.5));
  cube.push_back(cube[3]);
  const auto adj = exact::hull_vertex_adjacency(cube);
  REQUIRE(adj.size() == cube.size());
  for (int i = 0; i < 8; ++i)
    CHECK(adj[i].size() >= 3);
  CHECK(adj[8].empty());  // interior
  CHECK(adj[9].empty());  // repeated copy of point 3
  for (std::size_t i = 0; i < adj.size(); ++i)
    for (int j : adj[i]) {
      REQUIRE(j >= 0);
      REQUIRE(j < static_cast<int>(adj.size()));
      CHECK(std::find(adj[j].begin(), adj[j].end(), static_cast<int>(i)) != adj[j].end());
    }
  // A flat square: a 4-cycle; a segment with an interior point; a single point.
  const auto square = exact::hull_vertex_adjacency(
      std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}});
  for (int i = 0; i < 4; ++i)
    CHECK(square[i].size() == 2);
  CHECK(square[4].empty());
  const auto segment =
      exact::hull_vertex_adjacency(std::vector<Vec3>{{0, 0, 0}, {0.5, 0.5, 0.5}, {1, 1, 1}});
  CHECK(segment[0] == std::vector<int>{2});
  CHECK(segment[1].empty());
  CHECK(segment[2] == std::vector<int>{0});
  CHECK(exact::hull_vertex_adjacency(std::vector<Vec3>{{1, 2, 3}})[0].empty());
  CHECK_THROWS_AS(exact::hull_vertex_adjacency(std::vector<Vec3>{}), std::invalid_argument);
}

TEST_CASE("hill climbing returns a maximiser on random hulls and after random rotations",
          "[unit][hill-climbing]") {
  Rng rng(99);
  int checks = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const int n = trial < 8 ? 4 + trial * 7 : rng.integer(60, 1500);
    std::vector<Vec3> cloud = trial % 3 == 2 ? grid_cloud(rng, n) : sphere_cloud(rng, n);
    Polytope p(cloud);
    p.enable_hill_climbing(exact::hull_vertex_adjacency(cloud));
    REQUIRE(p.uses_hill_climbing());
    // Coherent directions (small turns, the hint matters) and random ones.
    Vec3 d = rng.unit_vector();
    for (int k = 0; k < 60; ++k) {
      d = k % 2 ? rng.unit_vector() : Vec3((d + 0.05 * rng.unit_vector()).normalized());
      const std::size_t i = p.support_index(d);
      REQUIRE(i < cloud.size());
      REQUIRE(cloud[i].dot(d) == max_dot(cloud, d));
      ++checks;
    }
    // Rotated copies keep the adjacency (transformed), and the Transformed adapter rotates
    // directions into the body frame instead.
    const Pose pose{random_rotation(rng), rng.unit_vector()};
    const Polytope moved = p.transformed(pose);
    REQUIRE(moved.uses_hill_climbing());
    const Transformed<Polytope> adapter(p, pose);
    for (int k = 0; k < 30; ++k) {
      const Vec3 e = rng.unit_vector();
      const std::size_t i = moved.support_index(e);
      REQUIRE(moved.vertices()[i].dot(e) == max_dot(moved.vertices(), e));
      const Vec3 body = pose.to_body_direction(e);
      REQUIRE(adapter.support(e).dot(e) == pose.apply(cloud[textbook_support(cloud, body)]).dot(e));
      checks += 2;
    }
  }
  CHECK(checks > 2000);
}

TEST_CASE("hill climbing on flat, collinear and single-point clouds; bad adjacency refused",
          "[unit][hill-climbing]") {
  Rng rng(5);
  const std::vector<std::vector<Vec3>> clouds = {
      {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, 0.2, 0}, {0.5, 0.5, 0}, {2, 1, 0}},
      {{0, 0, 0}, {1, 1, 1}, {0.25, 0.25, 0.25}, {2, 2, 2}},
      {{1, 1, 1}, {1, 1, 1}},
  };
  for (const auto& cloud : clouds) {
    Polytope p(cloud);
    p.enable_hill_climbing(exact::hull_vertex_adjacency(cloud));
    for (int k = 0; k < 50; ++k) {
      const Vec3 d = rng.unit_vector();
      CHECK(cloud[p.support_index(d)].dot(d) == max_dot(cloud, d));
    }
    p.disable_hill_climbing();
    CHECK(!p.uses_hill_climbing());
  }
  Polytope p(clouds[0]);
  CHECK_THROWS_AS(p.enable_hill_climbing({{1}}), std::invalid_argument);
  CHECK_THROWS_AS(p.enable_hill_climbing(std::vector<std::vector<int>>(6, std::vector<int>{7})),
                  std::invalid_argument);
  CHECK(!p.uses_hill_climbing());
}
