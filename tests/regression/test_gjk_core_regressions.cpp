// Configurations where every GJK distance variant stopped on a wrong answer for reasons of
// the driver (not of one sub-algorithm): near-parallel ridges, where the exact decrease of ‖v‖
// per step is below double resolution, and boxes far from the origin, where support values
// are rounded at the magnitude of the offset. Judged against the exact oracle.
#include <catch2/catch.hpp>

#include <string>

#include "../support/regression_case.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/trace.hpp"

using namespace gjklab;

namespace {

constexpr const char* kDistanceVariants[] = {"gjk-johnson", "gjk-johnson-backup", "gjk-sv",
                                             "gjk-voronoi", "gjk-nesterov",       "gjk-polyak",
                                             "epa"};

/// Every distance variant: the exact boolean, a distance within 1e-10 × size, converged.
void check_every_variant(const experiment::PointCase& c, const exact::OracleAnswer& exact) {
  const Polytope a(c.a), b(c.b);
  const double size = pair_size(c.a, c.b);
  for (const char* name : kDistanceVariants) {
    INFO(name);
    const auto o = experiment::run_algorithm(*experiment::find_algorithm(name), a, b, {}, {});
    CHECK(o.intersect == exact.intersect);
    REQUIRE(o.distance.has_value());
    CHECK(std::abs(*o.distance - exact.distance) <= 1e-10 * size);
    CHECK(o.termination == Termination::converged);
  }
}

/// The number of stalled steps (see detail::may_stall) on gjk-johnson's path for the pair.
int stalled_steps(const Polytope& a, const Polytope& b, DistanceResult& result) {
  TraceRecorder trace;
  result = gjk_distance(a, b, {}, trace);
  int stalls = 0;
  for (const auto& row : trace.iterations)
    stalls += row.step == GjkStep::stalled;
  return stalls;
}

}  // namespace

TEST_CASE("parallel ridges 1.2e-8 rad apart, overlapping by 1.2e-9: every variant finds contact",
          "[regression]") {
  // A parallel-edges contact case (hard configurations study, case 2562): two prism ridges
  // cross at 1.2e-8 rad and overlap by 1.2e-9. After two iterations v lay on a segment far
  // from the thin face of A − B that holds the origin; the next support point passes the gap
  // test by 1.4e-16 (far above the 1e-23 rounding of v·w), but the exact decrease of ‖v‖² it
  // brings is a relative 1e-17, below double resolution. Every variant stopped with
  // no_progress at distance 7.8e-9: a wrong boolean. The driver then took such steps as
  // bounded stalls and reached the contact; since a triangle's closest point is its plane's
  // projection (refine_triangle_point), v is normal to the thin face and contact comes at the
  // third iteration without a stall.
  const auto c = testing::regression_case("parallel_ridges_1p2e-8_rad_overlapping_1p2e-9.jsonl");
  const auto exact = exact::solve(c.a, c.b);
  REQUIRE(exact.intersect);
  check_every_variant(c, exact);
  DistanceResult r;
  CHECK(stalled_steps(Polytope(c.a), Polytope(c.b), r) <= detail::kMaxStalledSteps);
  CHECK(r.intersect);
  CHECK(r.iterations <= 3);
}

TEST_CASE("parallel ridges separated by 6.9e-9: a stalled step to 1e-10 of the size",
          "[regression]") {
  // The same family separated (case 3733): the variants stopped with no_progress at
  // 1.27e-8 instead of 6.9e-9, an error of 1.9e-9 × size. The exact decrease of ‖v‖ on the
  // way is below double resolution once: gjk-johnson takes one stalled step (of at most
  // kMaxStalledSteps) and converges.
  const auto c = testing::regression_case("parallel_ridges_separated_6p9e-9.jsonl");
  const auto exact = exact::solve(c.a, c.b);
  REQUIRE_FALSE(exact.intersect);
  check_every_variant(c, exact);
  DistanceResult r;
  const int stalls = stalled_steps(Polytope(c.a), Polytope(c.b), r);
  CHECK(stalls >= 1);
  CHECK(stalls <= detail::kMaxStalledSteps);
  CHECK(r.termination == Termination::converged);
}

TEST_CASE("boxes 1e8 from the origin, 0.18 apart: exact re-centring", "[regression]") {
  // Two unit boxes near (9.2e7, −3.0e7, 2.6e7) (offset study of boxes, case 1735): support
  // values d·x are rounded at 1e8, where one ulp is 1.5e-8, so vertices of nearly parallel
  // faces are confused and the answers were off by 1.8e-9 × size. Re-centred exactly, every
  // variant is exact to rounding. Without it (recenter = false) the error was 1.8e-9 × size
  // until a triangle's closest point became its plane's projection (refine_triangle_point):
  // the naive query is now within 1e-15 × size too (2.3e-17 measured), in 5 iterations.
  const auto c = testing::regression_case("boxes_offset_1e8_separated_0p18.jsonl");
  const auto exact = exact::solve(c.a, c.b);
  REQUIRE_FALSE(exact.intersect);
  check_every_variant(c, exact);

  const Polytope a(c.a), b(c.b);
  GjkDistanceOptions naive;
  naive.recenter = false;
  const double size = pair_size(c.a, c.b);
  CHECK(std::abs(gjk_distance(a, b, naive).distance - exact.distance) <= 1e-15 * size);
  const auto r = gjk_distance(a, b);
  CHECK(std::abs(r.distance - exact.distance) <= 1e-15 * size);
  // The answer is in the original frame: the witnesses lie on the boxes, 1e8 from the origin.
  CHECK(std::abs((r.witness_a - r.witness_b).norm() - r.distance) <= 1e-7);
  CHECK(r.witness_a.norm() > 1e7);
  for (const SimplexVertex& v : r.simplex.vertices()) {
    CHECK(v.a == c.a[v.index_a]);
    CHECK(v.b == c.b[v.index_b]);
  }
}

TEST_CASE("rotated boxes face to face, 4.1e-11 apart: a flat tetrahedron is not contact",
          "[regression]") {
  // Kissing boxes of side 0.25 with one random rotation (the configuration of FCL issues 493
  // and 495; hard configurations study, case 2131). The fourth support point lies on the
  // plane of the touching faces' Minkowski face, so the tetrahedron is flat within rounding,
  // while the origin is 4.1e-11 off that plane; Johnson's rounded weights were all positive
  // and gjk-johnson claimed contact (error 5.8e-11 × size). The driver now checks that the
  // origin is not provably outside the tetrahedron before it accepts contact.
  const auto c = testing::regression_case("kissing_boxes_rotated_4p1e-11_apart.jsonl");
  const auto exact = exact::solve(c.a, c.b);
  REQUIRE_FALSE(exact.intersect);
  REQUIRE(exact.distance > 4e-11);
  const Polytope a(c.a), b(c.b);
  const double size = pair_size(c.a, c.b);
  for (const char* name : kDistanceVariants) {
    INFO(name);
    const auto o = experiment::run_algorithm(*experiment::find_algorithm(name), a, b, {}, {});
    CHECK_FALSE(o.intersect);
    REQUIRE(o.distance.has_value());
    CHECK(std::abs(*o.distance - exact.distance) <= 1e-12 * size);
  }
}

TEST_CASE("origin_outside_tetrahedron: certain only beyond rounding", "[regression]") {
  using detail::origin_outside_tetrahedron;
  // A proper tetrahedron around the origin, and the same one moved off it.
  const std::array<Vec3, 4> around = {Vec3(1, 1, 1), Vec3(-1, -1, 1), Vec3(-1, 1, -1),
                                      Vec3(1, -1, -1)};
  CHECK_FALSE(origin_outside_tetrahedron(around));
  std::array<Vec3, 4> off = around;
  for (Vec3& p : off)
    p += Vec3(0, 0, 3);
  CHECK(origin_outside_tetrahedron(off));
  // A flat tetrahedron (z = 1e-9 for all points): the origin is 1e-9 off its plane.
  const std::array<Vec3, 4> flat = {Vec3(1, 0, 1e-9), Vec3(-1, 1, 1e-9), Vec3(-1, -1, 1e-9),
                                    Vec3(0.2, 0.3, 1e-9)};
  CHECK(origin_outside_tetrahedron(flat));
  // The origin on a face: not certainly outside.
  const std::array<Vec3, 4> on_face = {Vec3(1, 0, 0), Vec3(-1, 1, 0), Vec3(-1, -1, 0),
                                       Vec3(0, 0, 1)};
  CHECK_FALSE(origin_outside_tetrahedron(on_face));
}

TEST_CASE("gjk-bool on cube points 6 vs 59, 0.03 apart: a period-10 cycle is caught",
          "[regression]") {
  // Quickstart seed 1, case 7786: the triple-product walk came back to the same ten states
  // over and over and ran into its 64-step limit; the ring of its last six states could not
  // see a period of 10. Brent's detection catches it, and the distance walk decides.
  const auto c = testing::regression_case("gjk_bool_cycle_period_10_cube_points_6_vs_59.jsonl");
  const auto exact = exact::solve(c.a, c.b);
  REQUIRE_FALSE(exact.intersect);
  const Polytope a(c.a), b(c.b);
  TraceRecorder trace;
  const BooleanResult r = gjk_intersect(a, b, {}, trace);
  CHECK_FALSE(r.intersect);
  CHECK(r.termination == Termination::converged);
  CHECK(r.iterations < GjkBooleanDefaults::max_iterations);
  int cycled = 0;
  const Vec3 centre = a.vertex_mean() - b.vertex_mean();
  for (const auto& row : trace.iterations) {
    cycled += row.step == GjkStep::cycled;
    if (cycled) break;  // the distance walk's rows follow
    // The boolean rows say what the walk used: d·w and ‖d‖², and the simplex points' vertices
    // (only the centre start, c = c_A − c_B, has none).
    CHECK(row.v_dot_w == row.support.w.dot(row.direction));
    CHECK(row.v_norm_squared == row.direction.squaredNorm());
    for (const SimplexVertex& v : row.simplex.vertices())
      CHECK((v.index_a >= 0 || v.w == centre));
  }
  CHECK(cycled == 1);
}
