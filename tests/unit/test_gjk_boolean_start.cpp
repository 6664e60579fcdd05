// The starts of the boolean GJK (GjkBooleanOptions::start): separation proved by one support
// evaluation, the fall-back to the fixed direction for coincident or non-finite centres and
// for shapes without a centre, single points, touching contact, and agreement of the starts
// with each other and with the distance query on random pairs.
#include <catch2/catch.hpp>

#include <limits>

#include "../support/random_pairs.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

using namespace gjklab;

namespace {

constexpr GjkBooleanStart kStarts[] = {GjkBooleanStart::fixed_direction,
                                       GjkBooleanStart::centre_direction,
                                       GjkBooleanStart::centre_point};

GjkBooleanOptions with_start(GjkBooleanStart start) {
  GjkBooleanOptions o;
  o.start = start;
  return o;
}

Polytope moved(const Polytope& p, const Vec3& offset) {
  return p.transformed(Pose{Mat3::Identity(), offset});
}

/// A unit ball by its support function: a SupportMap without vertex_mean().
struct Ball {
  Vec3 centre = Vec3::Zero();
  Vec3 support(const Vec3& d) const {
    const double n = d.norm();
    return n > 0 ? Vec3(centre + d / n) : centre;
  }
};

}  // namespace

TEST_CASE("gjk-bool defaults to the centre-point start", "[unit][gjk_boolean]") {
  CHECK(GjkBooleanOptions{}.start == GjkBooleanStart::centre_point);
  CHECK(boolean_start_from_string("centre_direction") == GjkBooleanStart::centre_direction);
  CHECK_FALSE(boolean_start_from_string("centre").has_value());
}

TEST_CASE("centre starts prove a separated pair with one support evaluation",
          "[unit][gjk_boolean]") {
  const Polytope a = shapes::box();
  // Apart along a direction that is not a coordinate axis, so the fixed start needs more.
  const Polytope b = moved(shapes::cylinder(), Vec3(-2.0, 1.5, 0.7));
  for (GjkBooleanStart start : {GjkBooleanStart::centre_direction, GjkBooleanStart::centre_point}) {
    INFO(to_string(start));
    const BooleanResult r = gjk_intersect(a, b, with_start(start));
    CHECK_FALSE(r.intersect);
    CHECK(r.termination == Termination::converged);
    CHECK(r.support_calls == 1);
    CHECK(r.iterations == 1);
    // The trace has one record: the separating evaluation, in direction c_B − c_A.
    TraceRecorder trace;
    const BooleanResult traced = gjk_intersect(a, b, with_start(start), trace);
    CHECK(traced.support_calls == 1);
    REQUIRE(trace.iterations.size() == 1);
    CHECK(trace.iterations[0].step == GjkStep::separated);
    CHECK(trace.iterations[0].direction == b.vertex_mean() - a.vertex_mean());
  }
  const BooleanResult fixed = gjk_intersect(a, b, with_start(GjkBooleanStart::fixed_direction));
  CHECK_FALSE(fixed.intersect);
  CHECK(fixed.support_calls >= 2);
}

TEST_CASE("centre-point start encloses the origin with fewer support evaluations",
          "[unit][gjk_boolean]") {
  // Deeply overlapping boxes: the centre difference is one vertex of the enclosing simplex.
  const Polytope a = shapes::box();
  const Polytope b = moved(shapes::box(), Vec3(0.3, 0.2, 0.1));
  const BooleanResult centre = gjk_intersect(a, b, with_start(GjkBooleanStart::centre_point));
  const BooleanResult fixed = gjk_intersect(a, b, with_start(GjkBooleanStart::fixed_direction));
  CHECK(centre.intersect);
  CHECK(fixed.intersect);
  CHECK(centre.support_calls >= 3);  // a tetrahedron needs three points besides the centre
  CHECK(centre.support_calls < fixed.support_calls);
}

TEST_CASE("coincident, non-finite or missing centres fall back to the fixed direction",
          "[unit][gjk_boolean]") {
  auto same_as_fixed = [](const auto& a, const auto& b) {
    const BooleanResult fixed = gjk_intersect(a, b, with_start(GjkBooleanStart::fixed_direction));
    for (GjkBooleanStart start : kStarts) {
      INFO(to_string(start));
      const BooleanResult r = gjk_intersect(a, b, with_start(start));
      CHECK(r.intersect == fixed.intersect);
      CHECK(r.iterations == fixed.iterations);
      CHECK(r.support_calls == fixed.support_calls);
      CHECK(r.termination == fixed.termination);
    }
    return fixed;
  };
  SECTION("coincident means: a box and a smaller box about the same centre") {
    // Both are symmetric about the origin, so both vertex means are exactly 0.
    const Polytope a = shapes::box();
    const Polytope b = shapes::box(Vec3(0.5, 0.25, 0.75));
    REQUIRE((a.vertex_mean() - b.vertex_mean()).isZero(0));
    CHECK(same_as_fixed(a, b).intersect);
    // Flat clouds in one plane with the same mean (exactly 0): they share that mean.
    const Polytope square({{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}});
    const Polytope diamond({{2, 0, 0}, {0, 2, 0}, {-2, 0, 0}, {0, -2, 0}});
    REQUIRE((square.vertex_mean() - diamond.vertex_mean()).isZero(0));
    CHECK(same_as_fixed(square, diamond).intersect);
  }
  SECTION("a single point against itself") {
    const Polytope p({{0.25, -1.5, 3.0}});
    const BooleanResult r = same_as_fixed(p, p);
    CHECK(r.intersect);
    CHECK(r.termination == Termination::converged);
  }
  SECTION("non-finite means (the vertex sum overflows)") {
    const double big = std::numeric_limits<double>::max();
    const Polytope a({{big, 0, 0}, {big, 1, 0}, {big, 0, 1}});
    REQUIRE_FALSE(a.vertex_mean().allFinite());
    const Polytope b({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    same_as_fixed(a, b);
  }
  SECTION("shapes without vertex_mean()") {
    const Ball a, b{Vec3(1.0, 1.5, 0.5)};
    CHECK(same_as_fixed(a, b).intersect);
    const Ball far{Vec3(3.0, -1.0, 0.5)};
    CHECK_FALSE(same_as_fixed(a, far).intersect);
  }
}

TEST_CASE("single-point pairs under every start", "[unit][gjk_boolean]") {
  const Polytope p({{0.25, -1.5, 3.0}});
  const Polytope q({{0.25, -1.5, 3.0 + 0x1p-40}});
  const Polytope box = shapes::box();
  const Polytope corner({{0.5, 0.5, 0.5}});  // a vertex of the box: touching
  const Polytope outside({{0.5, 0.5, 0.5 + 1e-12}});
  const Polytope inside({{0.1, -0.2, 0.3}});
  for (GjkBooleanStart start : kStarts) {
    INFO(to_string(start));
    const GjkBooleanOptions o = with_start(start);
    const BooleanResult apart = gjk_intersect(p, q, o);
    CHECK_FALSE(apart.intersect);
    CHECK(apart.termination == Termination::converged);
    if (start != GjkBooleanStart::fixed_direction) CHECK(apart.support_calls == 1);
    CHECK(gjk_intersect(corner, box, o).intersect);
    CHECK(gjk_intersect(box, corner, o).intersect);
    CHECK_FALSE(gjk_intersect(outside, box, o).intersect);
    CHECK(gjk_intersect(inside, box, o).intersect);
    CHECK(gjk_intersect(box, inside, o).intersect);
  }
}

TEST_CASE("the starts agree with each other and with the distance query on random pairs",
          "[unit][gjk_boolean]") {
  testing::Rng rng(4242);
  int intersecting = 0, compared = 0;
  for (int i = 0; i < 400; ++i) {
    // Gaps well outside the rounding band, so every correct answer is the same answer.
    const double gap = i % 2 ? rng.log_uniform(1e-6, 2) : -rng.uniform(1e-6, 0.8);
    const auto pair =
        testing::random_pair(rng, i % 4 < 2 ? testing::CloudKind::sphere : testing::CloudKind::cube,
                             rng.integer(1, 64), rng.integer(2, 64), gap);
    const Polytope a(pair.a), b(pair.b);
    const DistanceResult d = gjk_distance(a, b);
    if (!d.intersect && d.distance < 1e-9 * pair_size(pair.a, pair.b)) continue;
    intersecting += d.intersect;
    ++compared;
    for (GjkBooleanStart start : kStarts) {
      INFO("pair " << i << " start " << to_string(start));
      const BooleanResult r = gjk_intersect(a, b, with_start(start));
      CHECK(r.termination == Termination::converged);
      CHECK(r.intersect == d.intersect);
    }
  }
  CHECK(compared > 350);
  CHECK(intersecting > 50);
  CHECK(compared - intersecting > 50);
}
