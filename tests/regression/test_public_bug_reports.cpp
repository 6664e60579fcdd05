// Configurations from public GJK bug reports, each kept with its vertices (computed once in
// double and stored, so the oracle sees exactly what the algorithms see), run through every
// registered algorithm. gjklab's own algorithms must be right; peers' disagreements are
// reported, not asserted.
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/regression_case.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/algorithms.hpp"
#include "gjklab/experiment/cloud_io.hpp"

using namespace gjklab;

namespace {

/// Every algorithm on the case: finite answers; gjklab's own agree with the exact answer.
exact::OracleAnswer check_every_algorithm(const experiment::PointCase& c) {
  const Polytope a(c.a), b(c.b);
  const double size = pair_size(c.a, c.b);
  const auto exact = exact::solve(c.a, c.b, {.depth = true});
  for (const auto& algorithm : experiment::algorithms()) {
    if (algorithm.kind == experiment::AnswerKind::exact) continue;
    INFO(c.id << " with " << algorithm.name);
    const auto o = algorithm.run(a, b, {});
    // Whatever a library does inside, no answer that leaves an algorithm is NaN.
    if (o.distance) CHECK(std::isfinite(*o.distance));
    if (o.witness_a) CHECK(o.witness_a->allFinite());
    if (o.witness_b) CHECK(o.witness_b->allFinite());
    if (o.depth) CHECK(std::isfinite(*o.depth));
    if (!algorithm.peer) {
      CHECK(o.termination != Termination::numerical_failure);
      CHECK(o.intersect == exact.intersect);
      if (o.distance) CHECK(std::abs(*o.distance - exact.distance) <= 1e-10 * size);
    } else if (o.intersect != exact.intersect || o.termination != Termination::converged) {
      WARN(c.id << ": peer " << algorithm.name << " says intersect=" << o.intersect << " ("
                << to_string(o.termination) << "), exact says " << exact.intersect);
    }
  }
  return exact;
}

}  // namespace

TEST_CASE("cubes of side 2 centred 1.9 apart along z: depth 0.1, no NaN", "[regression]") {
  const auto exact =
      check_every_algorithm(testing::regression_case("cubes_side2_offset_1p9_along_z.jsonl"));
  CHECK(exact.intersect);
  REQUIRE(exact.depth.has_value());
  CHECK(*exact.depth == Approx(0.1).epsilon(1e-12));
}

TEST_CASE("flat polygons at z = 0 intersect (a library reported distance 0.509)", "[regression]") {
  const auto exact =
      check_every_algorithm(testing::regression_case("flat_polygons_z0_intersecting.jsonl"));
  CHECK(exact.intersect);
  CHECK(exact.hull_vertices_a == 4);
  CHECK(exact.hull_vertices_b == 3);
}

TEST_CASE("thin plate vs rotated small box: no NaN witness from a collinear simplex",
          "[regression]") {
  const auto exact =
      check_every_algorithm(testing::regression_case("thin_plate_vs_rotated_small_box.jsonl"));
  CHECK_FALSE(exact.intersect);
  CHECK(exact.distance == Approx(0.0535161628).epsilon(1e-9));
}

TEST_CASE("point vs degenerate triangle with a repeated vertex: distance 0.17148", "[regression]") {
  const auto exact =
      check_every_algorithm(testing::regression_case("point_vs_degenerate_triangle.jsonl"));
  CHECK_FALSE(exact.intersect);
  CHECK(exact.distance == Approx(0.17148).epsilon(1e-4));
}
