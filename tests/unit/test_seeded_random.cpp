// The seeded stream of the benchmark suites and the property tests: fixed by its seed (the
// standard fixes std::mt19937_64's sequence), and the placement of one cloud beside another.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "gjklab/experiment/cases/seeded_random.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

TEST_CASE("seeded random: a seed gives std::mt19937_64's sequence, top 53 bits", "[unit][random]") {
  SeededRandom r(42);
  std::mt19937_64 engine(42);
  for (int i = 0; i < 100; ++i)
    CHECK(r.uniform() == static_cast<double>(engine() >> 11) * 0x1p-53);
  SeededRandom a(7), b(7);
  for (int i = 0; i < 100; ++i) {
    const Vec3 u = a.unit_vector();
    CHECK(u == b.unit_vector());
    CHECK(u.norm() == Approx(1));
    CHECK(a.rotation() == b.rotation());
  }
}

TEST_CASE("seeded random: the separating shift puts B's extent gap after A's along u",
          "[unit][random]") {
  SeededRandom r(3);
  for (const double gap : {0.25, -0.25}) {
    std::vector<Vec3> a, b;
    for (int i = 0; i < 32; ++i) {
      a.push_back(r.unit_vector());
      b.push_back(r.unit_vector());
    }
    const Vec3 u = r.unit_vector();
    const double shift = separating_shift(a, b, u, gap);
    for (Vec3& p : b)
      p += shift * u;
    CHECK(min_projection(b, u) - max_projection(a, u) == Approx(gap).margin(1e-12));
  }
  CHECK(max_projection(std::vector<Vec3>{}, Vec3::UnitX()) < 0);
  CHECK(min_projection(std::vector<Vec3>{}, Vec3::UnitX()) > 0);
}
