// The unrolled Johnson sub-algorithm gives bit for bit the answers of the generic recursion it
// replaced (reproduced here as the reference). Its cofactors equal the reference's as numbers:
// its sums start from their first term instead of 0 + it, which can change only the sign of a
// zero cofactor, and the answers must not depend on that sign.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstring>

#include "../support/random_pairs.hpp"
#include "gjklab/gjk/johnson.hpp"
#include "gjklab/gjk/subsimplex.hpp"

using namespace gjklab;

namespace {

constexpr std::array<std::uint8_t, 15> kOrder = {1, 2, 4, 8, 3, 5, 6, 9, 10, 12, 7, 11, 13, 14, 15};

JohnsonCofactors reference_cofactors(const std::array<Vec3, 4>& y, int count) {
  JohnsonCofactors c;
  const auto all = static_cast<std::uint8_t>((1u << count) - 1);
  for (std::uint8_t x : kOrder) {
    if ((x & all) != x) continue;
    if (std::popcount(static_cast<unsigned>(x)) == 1) {
      c.delta[x][std::countr_zero(static_cast<unsigned>(x))] = 1.0;
      c.total[x] = 1.0;
      continue;
    }
    double total = 0;
    for (int j = 0; j < count; ++j) {
      if (!(x & (1u << j))) continue;
      const auto rest = static_cast<std::uint8_t>(x & ~(1u << j));
      const int k = std::countr_zero(static_cast<unsigned>(rest));
      const Vec3 edge = y[k] - y[j];
      double dj = 0;
      for (int i = 0; i < count; ++i)
        if (rest & (1u << i)) dj += c.delta[rest][i] * edge.dot(y[i]);
      c.delta[x][j] = dj;
      total += dj;
    }
    c.total[x] = total;
  }
  return c;
}

bool reference_valid(const JohnsonCofactors& c, std::uint8_t subset, int count) {
  if (!(c.total[subset] > 0)) return false;
  for (int i = 0; i < count; ++i) {
    const bool inside = subset & (1u << i);
    if (inside && !(c.delta[subset][i] > 0)) return false;
    if (!inside && !(c.delta[subset | (1u << i)][i] <= 0)) return false;
  }
  return true;
}

JohnsonSolution reference_closest(const std::array<Vec3, 4>& y, int count) {
  const JohnsonCofactors c = reference_cofactors(y, count);
  const auto all = static_cast<std::uint8_t>((1u << count) - 1);
  JohnsonSolution s;
  for (std::uint8_t x : kOrder) {
    if ((x & all) != x || !reference_valid(c, x, count)) continue;
    s.found = true;
    s.subset = x;
    for (int i = 0; i < count; ++i) {
      if (!(x & (1u << i))) continue;
      s.weights[i] = c.delta[x][i] / c.total[x];
      s.closest += s.weights[i] * y[i];
    }
    refine_triangle_point(s, y);  // a point inside a triangle: its plane's projection
    return s;
  }
  return s;
}

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

/// Equal as numbers: −0 equals +0, and NaN equals NaN.
bool same_value(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}

bool same_values(const JohnsonCofactors& a, const JohnsonCofactors& b) {
  for (int x = 0; x < 16; ++x) {
    if (!same_value(a.total[x], b.total[x])) return false;
    for (int i = 0; i < 4; ++i)
      if (!same_value(a.delta[x][i], b.delta[x][i])) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("unrolled Johnson matches the generic recursion bit for bit", "[unit][johnson]") {
  testing::Rng rng(424242);
  int found = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int count = 1 + trial % 4;
    std::array<Vec3, 4> y;
    const double scale = rng.log_uniform(1e-6, 1e6);
    for (auto& p : y)
      p = scale * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    // Degenerate simplices: repeated, collinear and coplanar points, and exact small integers.
    switch (trial % 7) {
      case 1:
        y[count - 1] = y[0];
        break;
      case 2:
        y[count - 1] = 0.5 * (y[0] + y[1 % count]);
        break;
      case 3:
        for (auto& p : y)
          p.z() = 0.25 * scale;
        break;
      case 4:
        for (auto& p : y)
          p = Vec3(rng.integer(-2, 2), rng.integer(-2, 2), rng.integer(-2, 2));
        break;
      default:
        break;
    }
    const JohnsonCofactors a = johnson_cofactors(y, count), b = reference_cofactors(y, count);
    REQUIRE(same_values(a, b));
    for (std::uint8_t x = 1; x < 16; ++x)
      if ((x & ((1u << count) - 1)) == x)
        REQUIRE(johnson_subset_is_valid(a, x, count) == reference_valid(b, x, count));
    const JohnsonSolution s = johnson_closest_point(y, count), r = reference_closest(y, count);
    REQUIRE(s.found == r.found);
    REQUIRE(s.subset == r.subset);
    REQUIRE(same_bits(s.weights, r.weights));
    REQUIRE(same_bits(s.closest, r.closest));
    found += s.found;
  }
  CHECK(found > 15000);
}
