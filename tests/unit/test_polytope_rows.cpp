// Polytopes built from rows of doubles (Polytope(CoordinateRows), Polytope::assign), as a query
// on NumPy arrays builds them: bit for bit the polytope of the same points given as a
// std::vector<Vec3> (vertices, mean, box with the signs of its zero bounds, scan answers), with
// the same errors, whatever the strides and however the storage was used before.
#include <catch2/catch.hpp>

#include <algorithm>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "gjklab/geometry/polytope.hpp"

using namespace gjklab;

namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same_bits(const Vec3& a, const Vec3& b) {
  return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z());
}

/// The measures as the textbook loop takes them: sum from zero in vertex order, Eigen's
/// cwiseMin / cwiseMax point after point from the first point.
struct Measures {
  Vec3 mean, lower, upper;
};
Measures textbook_measures(const std::vector<Vec3>& cloud) {
  Vec3 sum = Vec3::Zero(), lower = cloud[0], upper = cloud[0];
  for (const Vec3& v : cloud) {
    sum += v;
    lower = lower.cwiseMin(v);
    upper = upper.cwiseMax(v);
  }
  return {sum / static_cast<double>(cloud.size()), lower, upper};
}

/// Everything a query reads of a polytope, compared bit for bit with the textbook's answers.
void check_same(const Polytope& p, const std::vector<Vec3>& cloud, std::mt19937_64& rng) {
  REQUIRE(p.size() == cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    REQUIRE(same_bits(p.vertices()[i], cloud[i]));
  const Measures m = textbook_measures(cloud);
  CHECK(same_bits(p.vertex_mean(), m.mean));
  CHECK(same_bits(p.box_lower(), m.lower));
  CHECK(same_bits(p.box_upper(), m.upper));
  CHECK(same_bits(p.box_extent(), (m.upper - m.lower).maxCoeff()));
  CHECK(same_bits(p.max_magnitude(),
                  std::max(m.lower.cwiseAbs().maxCoeff(), m.upper.cwiseAbs().maxCoeff())));
  // The scan's blocks (the last one padded): the first maximiser, as the textbook loop.
  std::normal_distribution<double> normal;
  for (int k = 0; k < 20; ++k) {
    const Vec3 d = k < 3 ? Vec3::Unit(k) : Vec3(normal(rng), normal(rng), normal(rng));
    std::size_t best = 0;
    for (std::size_t i = 1; i < cloud.size(); ++i)
      if (cloud[i].dot(d) > cloud[best].dot(d)) best = i;
    REQUIRE(p.scan_support_index(d) == best);
  }
}

/// Coordinates that make the box's bounds hard to get bit for bit: many zeros of both signs
/// (a zero bound's sign is that of the first point attaining it), huge values whose sum
/// overflows, and, per `mode`, clouds whose lower or upper bound is zero.
std::vector<Vec3> awkward_cloud(std::size_t n, int mode, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, 5);
  std::normal_distribution<double> normal;
  std::vector<Vec3> cloud(n);
  for (Vec3& v : cloud) {
    for (int c = 0; c < 3; ++c) {
      const int kind = pick(rng);
      double x = kind == 0   ? 0.0
                 : kind == 1 ? -0.0
                 : kind == 2 ? std::copysign(1.5e308, normal(rng))
                             : std::ldexp(normal(rng), 10 * pick(rng) - 20);
      if (mode == 1 && x != 0) x = std::abs(x);   // lower bound zero
      if (mode == 2 && x != 0) x = -std::abs(x);  // upper bound zero
      v[c] = x;
    }
  }
  return cloud;
}

}  // namespace

TEST_CASE("a polytope from rows is the polytope of the same vector, bit for bit",
          "[unit][support]") {
  std::mt19937_64 rng(20);
  Polytope reused(std::vector<Vec3>{Vec3(1, 2, 3)});
  int zero_bounds = 0;
  for (const std::size_t n : {1, 2, 7, 8, 9, 16, 17, 63, 200, 1025}) {
    for (int mode = 0; mode < 3; ++mode) {
      const std::vector<Vec3> cloud = awkward_cloud(n, mode, rng);
      const Measures m = textbook_measures(cloud);
      for (int c = 0; c < 3; ++c)
        zero_bounds += (m.lower[c] == 0) + (m.upper[c] == 0);
      check_same(Polytope(cloud), cloud, rng);
      check_same(Polytope(CoordinateRows{cloud.data(), n}), cloud, rng);
      reused.assign(CoordinateRows{cloud.data(), n});  // storage of another size before
      check_same(reused, cloud, rng);
      // Columns stored one after the other (a transposed NumPy array): strides 8 and 8n.
      std::vector<double> columns(3 * n);
      for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
          columns[c * n + i] = cloud[i][c];
      check_same(Polytope(CoordinateRows{columns.data(), n, sizeof(double),
                                         static_cast<std::ptrdiff_t>(n * sizeof(double))}),
                 cloud, rng);
    }
  }
  CHECK(zero_bounds > 20);  // the sample has zero bounds to get right
}

TEST_CASE("a polytope from rows reads unaligned rows", "[unit][support]") {
  std::mt19937_64 rng(21);
  const std::vector<Vec3> cloud = awkward_cloud(37, 0, rng);
  std::vector<char> bytes(cloud.size() * sizeof(Vec3) + 1);
  std::memcpy(bytes.data() + 1, cloud.data(), cloud.size() * sizeof(Vec3));
  const Polytope from_rows(CoordinateRows{bytes.data() + 1, cloud.size()});
  REQUIRE(from_rows.size() == cloud.size());
  CHECK(std::equal(cloud.begin(), cloud.end(), from_rows.vertices().begin()));
  check_same(from_rows, cloud, rng);
}

TEST_CASE("a polytope from rows refuses the clouds the vector constructor refuses",
          "[unit][support]") {
  CHECK_THROWS_WITH(Polytope(CoordinateRows{nullptr, 0}), "empty point cloud");
  Polytope reused(std::vector<Vec3>(100, Vec3(1, 2, 3)));
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  for (const std::size_t n : {1, 9, 40, 1000}) {
    for (const std::size_t at : {std::size_t{0}, n / 2, n - 1}) {
      for (int c = 0; c < 3; ++c) {
        std::vector<Vec3> cloud(n, Vec3(0.5, -0.25, 2));
        cloud[at][c] = bad[c];
        const std::string message = "non-finite coordinate in point " + std::to_string(at);
        CHECK_THROWS_WITH(Polytope(cloud), message);
        CHECK_THROWS_WITH(Polytope(CoordinateRows{cloud.data(), n}), message);
        CHECK_THROWS_WITH(reused.assign(CoordinateRows{cloud.data(), n}), message);
        // Left usable: the point at the origin, with a new identity.
        REQUIRE(reused.size() == 1);
        CHECK(reused.vertices()[0] == Vec3::Zero());
        CHECK(reused.scan_support_index(Vec3(1, 0, 0)) == 0);
      }
    }
  }
}

TEST_CASE("assign gives a new identity and drops hill climbing", "[unit][support]") {
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  Polytope p(square);
  p.enable_hill_climbing({{1, 3}, {0, 2}, {1, 3}, {0, 2}});
  const std::uint64_t before = p.id();
  p.assign(CoordinateRows{square.data(), square.size()});
  CHECK(p.id() != before);
  CHECK_FALSE(p.uses_hill_climbing());
  CHECK(p.scan_support_index(Vec3(1, 1, 0)) == 2);
}
