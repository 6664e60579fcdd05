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
#include "gjklab/gjk/swept.hpp"

using namespace gjklab;

namespace {

/// Every algorithm that handles the case's radii: finite answers; gjklab's own agree with the
/// exact answer (boolean; distance within 1e-10 × size; EPA's depth within its relative gap
/// plus 1e-10 × size), and converge.
exact::OracleAnswer check_every_algorithm(const experiment::PointCase& c) {
  const Polytope a(c.a), b(c.b);
  const SweptRadii radii{c.radius_a, c.radius_b};
  const double size = pair_size(c.a, c.b) + 2 * radii.sum();
  const auto exact = exact::solve_swept(c.a, c.b, radii.a, radii.b, {.depth = true});
  for (const auto& algorithm : experiment::algorithms()) {
    if (algorithm.kind == experiment::AnswerKind::exact || !experiment::handles(algorithm, radii))
      continue;
    INFO(c.id << " with " << algorithm.name);
    const auto o = experiment::run_algorithm(algorithm, a, b, radii, {});
    // Whatever a library does inside, no answer that leaves an algorithm is NaN.
    if (o.distance) CHECK(std::isfinite(*o.distance));
    if (o.witness_a) CHECK(o.witness_a->allFinite());
    if (o.witness_b) CHECK(o.witness_b->allFinite());
    if (o.depth) CHECK(std::isfinite(*o.depth));
    if (!algorithm.peer) {
      CHECK(o.termination == Termination::converged);
      CHECK(o.intersect == exact.intersect);
      if (o.distance) CHECK(std::abs(*o.distance - exact.distance) <= 1e-10 * size);
      if (o.depth && exact.depth)
        CHECK(std::abs(*o.depth - *exact.depth) <= 1e-6 * *exact.depth + 1e-10 * size);
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

TEST_CASE("fcl issue 445, rotated stacked boxes 4.6e-11 deep: every distance variant finds contact",
          "[regression]") {
  // Two rotated boxes stacked on each other; libccd's EPA threw "origin is outside of the
  // polytope" (flexible-collision-library/fcl issue 445). A − B holds the origin 4.6e-11 deep
  // (exact). Every gjklab distance variant and EPA answered "apart, 2.6e-10": GJK ended on a
  // triangle whose plane passes 2.6e-10 from the origin, with v = Σ λ y tilted off the face
  // normal by 1e-7, so that one of its own vertices looked like the support point beyond the
  // origin (see the unit test of refine_triangle_point).
  const auto exact = check_every_algorithm(
      testing::regression_case("fcl_445_stacked_rotated_boxes_touching.jsonl"));
  CHECK(exact.intersect);
  REQUIRE(exact.depth.has_value());
  CHECK(*exact.depth == Approx(4.613859609769972e-11).epsilon(1e-9));
}

TEST_CASE("fcl issue 390, small box 1.7e-8 from a tall thin box: EPA's GJK phase converges",
          "[regression]") {
  // A 0.03 × 0.12 × 0.1 box beside a 0.025 × 0.35 × 1.845 box; FCL's EPA threw "origin is
  // outside of the polytope" (fcl issue 390). Plain Johnson's sub-algorithm finds no valid
  // subset at the fourth iteration and stops with degenerate_simplex at 2.01e-8 (exact:
  // 1.708e-8): gjk-johnson reports that, as Johnson's algorithm does; `epa`, whose GJK phase
  // now has the backup procedure, converges to the right distance.
  const auto c = testing::regression_case("fcl_390_small_box_vs_tall_thin_box.jsonl");
  const Polytope a(c.a), b(c.b);
  const auto exact = exact::solve(c.a, c.b);
  REQUIRE_FALSE(exact.intersect);
  CHECK(exact.distance == Approx(1.7082191661188517e-08).epsilon(1e-12));
  const double size = pair_size(c.a, c.b);
  for (const char* name : {"gjk-johnson-backup", "gjk-sv", "gjk-voronoi", "gjk-nesterov",
                           "gjk-polyak", "epa", "gjk-certified"}) {
    INFO(name);
    const auto o = experiment::find_algorithm(name)->run(a, b, {});
    CHECK_FALSE(o.intersect);
    REQUIRE(o.distance.has_value());
    CHECK(std::abs(*o.distance - exact.distance) <= 1e-10 * size);
    CHECK(o.termination == Termination::converged);
  }
  const auto johnson = experiment::find_algorithm("gjk-johnson")->run(a, b, {});
  CHECK(johnson.termination == Termination::degenerate_simplex);
}

TEST_CASE("public bug reports of peer libraries: gjklab's own algorithms right on each",
          "[regression]") {
  // Each configuration a library's report gave with its numbers (the issue named in the file
  // name); what went wrong there, and the exact answer, in the comment.
  struct Report {
    const char* file;
    bool intersect;
    double distance_or_depth;  ///< exact distance, or depth if intersecting
  };
  const Report reports[] = {
      // coal issue 604: box-box distance "totally wrong" with gjk_tolerance 1e-6, boxes nearly
      // touching (10-digit rotations, not exactly orthonormal, used as given).
      {"coal_604_boxes_nearly_touching.jsonl", false, 3.575454309318231e-06},
      // distance3d issue 27: "GJK error" on two 6-vertex hulls.
      {"distance3d_27_six_vertex_hulls.jsonl", false, 0.027535806024984632},
      // distance3d issue 72: an assertion inside GJK on two overlapping boxes.
      {"distance3d_72_long_box_vs_rotated_cube_overlapping.jsonl", true, 1.2071067899999974},
      // dolfinx issue 3653: a point against a 7-point hull, "max iteration limit reached".
      {"dolfinx_3653_point_vs_seven_point_hull.jsonl", false, 1.8134526453385027},
      // drake issue 21673: FCL's EPA threw on an almost penetrating pair of prisms, and on a
      // thin box against a box.
      {"drake_21673_octagonal_prism_vs_triangular_prism.jsonl", true, 0.5747809100146694},
      {"drake_21673_thin_box_vs_box_sharing_centre_x.jsonl", true, 0.15005968486978194},
      // fcl issue 31: libccd's capsule-box distance was wrong (capsule r = 2, h = 4, 0.5 away).
      {"fcl_31_capsule_r2_vs_box_0p5_apart.jsonl", false, 0.5},
      // fcl issue 395: EPA's "triangle_size_is_zero" on a plate and a rotated small box.
      {"fcl_395_plate_vs_rotated_small_box.jsonl", true, 0.013408613773995293},
      // fcl issue 408: "origin outside polytope" for a sphere of radius 0.06 touching a box of
      // 0.1 exactly (the core's squared distance is 0.06² exactly): depth 0.
      {"fcl_408_sphere_0p06_touching_box_0p1.jsonl", true, 0},
      // fcl issue 415: "query point colinear with the edge" on two boxes.
      {"fcl_415_box_vs_box_colinear_edge.jsonl", true, 0.0391529701145068},
      // fcl issue 428: a signed-distance failure on axis-aligned boxes.
      {"fcl_428_axis_aligned_boxes_overlapping.jsonl", true, 0.08422044196125167},
      // fcl issue 493, first example: kissing boxes of side 0.5, EPA threw (depth at rounding).
      {"fcl_493_kissing_boxes_0p5.jsonl", true, 5.3810564310687815e-17},
      // fcl issue 508: unit boxes 4 apart along y; libccd answered 3.16228 instead of 3.
      {"fcl_508_unit_boxes_4_apart_along_y.jsonl", false, 3},
  };
  for (const Report& r : reports) {
    DYNAMIC_SECTION(r.file) {
      const auto exact = check_every_algorithm(testing::regression_case(r.file));
      CHECK(exact.intersect == r.intersect);
      if (r.intersect) {
        REQUIRE(exact.depth.has_value());
        CHECK(*exact.depth == Approx(r.distance_or_depth).epsilon(1e-12).margin(1e-20));
      } else {
        CHECK(exact.distance == Approx(r.distance_or_depth).epsilon(1e-12));
      }
    }
  }
}
