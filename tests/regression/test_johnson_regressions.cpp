// Configurations that broke gjk-johnson, kept with their data.
#include <catch2/catch.hpp>

#include "../support/regression_case.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

using namespace gjklab;

TEST_CASE("johnson flat tetrahedron near contact: 102 sphere points vs 9, gap 0.0135",
          "[regression]") {
  // At iteration 7 the new support point is coplanar with the triangle closest to the origin
  // (duality gap 2e-12 of ‖v‖²). The flat tetrahedron's cofactors are rounding noise, all
  // positive, so Johnson's tests accept it and GJK claimed contact — although an earlier
  // support point had already proved separation (v·w > 0). The driver now continues from the
  // flat tetrahedron's nearest face, which did not improve ‖v‖: a no-progress stop with the
  // right answer. Since a triangle's closest point is its plane's projection
  // (refine_triangle_point), the query converges there.
  const auto c = testing::regression_case("johnson_flat_tetrahedron_near_contact.jsonl");
  const Polytope a(c.a), b(c.b);
  const auto exact = exact::solve(a.vertices(), b.vertices());
  REQUIRE_FALSE(exact.intersect);
  GjkDistanceOptions fixed;  // the path of the failure: the fixed first direction (1, 0, 0)
  fixed.start = GjkDistanceStart::fixed_direction;
  const auto r = gjk_distance(a, b, fixed);
  CHECK_FALSE(r.intersect);
  CHECK(std::abs(r.distance - exact.distance) <= 1e-10 * pair_size(c.a, c.b));
  CHECK(r.termination == Termination::converged);
  const auto centre = gjk_distance(a, b);
  CHECK_FALSE(centre.intersect);
  CHECK(std::abs(centre.distance - exact.distance) <= 1e-10 * pair_size(c.a, c.b));
}

TEST_CASE("contact pair separated by 5.6e-14: tetrahedron holds the origin only by rounding",
          "[regression]") {
  // An edge-face contact family case (degeneracy study, case 2830), 5.6e-14 apart. The first
  // support point proves separation; at iteration 4 every GJK distance variant's sub-algorithm
  // accepted a tetrahedron around the origin, and the driver stopped with the previous bound
  // 0.316 (relative error 0.1). Continuing from the nearest face gives the exact distance.
  const auto c =
      testing::regression_case("contact_eps_5e-14_flat_tetrahedron_after_separation.jsonl");
  const Polytope a(c.a), b(c.b);
  const auto exact = exact::solve(a.vertices(), b.vertices());
  REQUIRE_FALSE(exact.intersect);
  REQUIRE(exact.distance < 1e-13);
  // The failure happened on the path from the fixed first direction (1, 0, 0), which the
  // queries took before they started from the centre difference.
  experiment::AlgorithmOptions fixed;
  fixed.gjk_distance.start = GjkDistanceStart::fixed_direction;
  fixed.gjk_nesterov.start = GjkDistanceStart::fixed_direction;
  for (const auto& algorithm : experiment::algorithms()) {
    if (algorithm.kind != experiment::AnswerKind::distance || algorithm.peer) continue;
    INFO(algorithm.name);
    const auto o = experiment::run_algorithm(algorithm, a, b, {}, fixed);
    CHECK_FALSE(o.intersect);
    CHECK(std::abs(*o.distance - exact.distance) <= 1e-10 * pair_size(c.a, c.b));
    CHECK(o.termination == Termination::converged);
    // From the centre difference the simplex reaches the closest face directly; 5.6e-14 is
    // below the contact tolerance (1e-13 of the simplex's scale), so contact is an answer too.
    const auto centre = experiment::run_algorithm(algorithm, a, b, {}, {});
    CHECK(std::abs(*centre.distance - exact.distance) <= 1e-10 * pair_size(c.a, c.b));
    CHECK(centre.termination == Termination::converged);
  }
}
