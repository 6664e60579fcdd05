// The GJK distance variants on the configurations that broke gjk-johnson.
#include <catch2/catch.hpp>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

#include "../support/regression_case.hpp"

using namespace gjklab;

TEST_CASE("GJK distance variants on the flat tetrahedron near contact (102 vs 9 points)",
          "[regression]") {
  // See test_johnson_regressions.cpp: a support point coplanar with the closest triangle
  // makes a flat tetrahedron whose rounded cofactors all look positive. No variant may claim
  // contact after a separation certificate, and all must return the distance.
  const experiment::PointCase c =
      testing::regression_case("johnson_flat_tetrahedron_near_contact.jsonl");
  const Polytope a(c.a), b(c.b);
  const auto exact = exact::solve(a.vertices(), b.vertices());
  REQUIRE_FALSE(exact.intersect);
  for (const char* name : {"gjk-johnson", "gjk-johnson-backup", "gjk-sv", "gjk-voronoi",
                           "gjk-nesterov", "gjk-polyak"}) {
    INFO(name);
    const auto o = experiment::run_algorithm(*experiment::find_algorithm(name), a, b, {}, {});
    CHECK_FALSE(o.intersect);
    REQUIRE(o.distance.has_value());
    CHECK(std::abs(*o.distance - exact.distance) <= 1e-10 * pair_size(c.a, c.b));
  }
}
