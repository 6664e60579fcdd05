// Sphere-swept configurations that broke a query, with their data (swept.toml, seed 11).
#include <catch2/catch.hpp>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"

#include "../support/regression_case.hpp"

using namespace gjklab;

TEST_CASE("two spheres overlapping by 0.5% of the size: gjk-bool's centre start",
          "[regression][swept]") {
  // The centre start puts c = c_A − c_B in the simplex; on two balls the first support point
  // lies on the ray from c through the origin, so the origin is on the segment up to rounding.
  // The triple product then gave a direction of pure noise (1e-19), and the walk cycled
  // through the same four states until its step limit, answering "not intersecting".
  const experiment::PointCase c =
      testing::regression_case("spheres_overlapping_0p5pct_of_size.jsonl");
  const Polytope a(c.a), b(c.b);
  const SweptRadii radii{c.radius_a, c.radius_b};
  const auto exact = exact::solve_swept(c.a, c.b, radii.a, radii.b, {.depth = true});
  REQUIRE(exact.intersect);
  REQUIRE(*exact.depth > 0.003);
  const auto o =
      experiment::run_algorithm(*experiment::find_algorithm("gjk-bool"), a, b, radii, {});
  CHECK(o.intersect);
  CHECK(o.termination == Termination::converged);
  CHECK(o.iterations <= 2);
}

TEST_CASE("two spheres 1.2e-8 apart: gjk-bool on the swept support", "[regression][swept]") {
  // With the fixed first direction the walk crawled along the ball's surface and ran out of
  // its 64 steps (75 were needed); the centre start proves the separation with one support.
  const experiment::PointCase c = testing::regression_case("spheres_1p2e-8_apart.jsonl");
  const Polytope a(c.a), b(c.b);
  const SweptRadii radii{c.radius_a, c.radius_b};
  const auto exact = exact::solve_swept(c.a, c.b, radii.a, radii.b);
  REQUIRE_FALSE(exact.intersect);
  REQUIRE(exact.distance < 2e-8);
  const auto o =
      experiment::run_algorithm(*experiment::find_algorithm("gjk-bool"), a, b, radii, {});
  CHECK_FALSE(o.intersect);
  CHECK(o.termination == Termination::converged);
  CHECK(o.support_calls == 1);
}
