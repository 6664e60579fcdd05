// Needles and thin rods where GJK's sub-simplex solves in double lose the answer: each
// configuration with its vertices (computed once in double and stored), run through every
// registered algorithm of gjklab's own. Before the proven stopping test and the double-word
// continuation, gjk-johnson answered the first rods 4.3e-6 apart (degenerate_simplex) and the
// second 4.4e-6 apart, `converged`, for exact distances of about 2e-11 and 7e-11.
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/regression_case.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"

using namespace gjklab;

namespace {

/// Every distance algorithm of gjklab's own (not the peers, the exact answers or gjk-bool):
/// converged, the exact boolean, the distance within 1e-12 × size, and the exact distance
/// inside the query's proven bracket where it reports one. Returns how many were checked.
int check_own_algorithms(const experiment::PointCase& c) {
  const Polytope a(c.a), b(c.b);
  const double size = pair_size(c.a, c.b);
  const auto exact = exact::solve(c.a, c.b);
  int checked = 0;
  for (const auto& algorithm : experiment::algorithms()) {
    if (algorithm.peer || algorithm.kind == experiment::AnswerKind::exact) continue;
    const auto o = experiment::run_algorithm(algorithm, a, b, {}, {});
    if (!o.distance) continue;
    INFO(c.id << " with " << algorithm.name << ": " << *o.distance << " for " << exact.distance
              << ", " << to_string(o.termination));
    ++checked;
    CHECK(o.termination == Termination::converged);
    CHECK(o.intersect == exact.intersect);
    CHECK(std::abs(*o.distance - exact.distance) <= 1e-12 * size);
    if (o.lower_bound && o.upper_bound) {
      CHECK(std::nextafter(*o.lower_bound, -1.0) <= exact.distance);
      CHECK(exact.distance <= std::nextafter(*o.upper_bound, 1e300));
    }
  }
  return checked;
}

}  // namespace

TEST_CASE("thin rods of radius 8e-6, 2e-11 apart at an angle of 1e-9", "[regression]") {
  CHECK(check_own_algorithms(
            testing::regression_case("thin_rods_radius_8e-6_2e-11_apart_angle_1e-9.jsonl")) >= 7);
}

TEST_CASE("thin rods of radius 3e-6, 7e-11 apart at an angle of 1e-9", "[regression]") {
  CHECK(check_own_algorithms(
            testing::regression_case("thin_rods_radius_3e-6_7e-11_apart_angle_1e-9.jsonl")) >= 7);
}

TEST_CASE("a point 3e-12 above a needle triangle of aspect 1e7", "[regression]") {
  CHECK(check_own_algorithms(
            testing::regression_case("needle_triangle_aspect_1e7_point_3e-12_above.jsonl")) >= 7);
}

TEST_CASE("wedges whose edges cross 1e-8 deep (hunted against gjk-johnson)", "[regression]") {
  // The five cases `gjklab hunt --algorithm gjk-johnson` found before the proven stopping test:
  // Johnson's cofactors on the thin tetrahedron put its closest point farther than the
  // previous one, and the query stopped on no_progress at "apart, 6e-10 … 5.1e-9".
  const auto cases =
      experiment::read_cases_file(std::string(GJKLAB_REGRESSION_DATA_DIR) +
                                  "/hunted_wedges_crossing_1e-8_deep_johnson_no_progress.jsonl");
  REQUIRE(cases.size() == 5);
  for (const auto& c : cases) {
    REQUIRE(std::holds_alternative<experiment::PointCase>(c));
    CHECK(check_own_algorithms(std::get<experiment::PointCase>(c)) >= 7);
  }
}
