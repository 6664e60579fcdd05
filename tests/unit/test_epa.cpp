// EPA: depth against the exact oracle, known boxes, touching pairs, simplices that need a
// blow-up, bounds, and the answer for separated pairs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../support/random_pairs.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/gjk/epa.hpp"

using namespace gjklab;
using testing::CloudKind;
using testing::Rng;

namespace {

Polytope moved(const Polytope& p, const Vec3& t) {
  return p.transformed(Pose::from_translation(t));
}

bool unit_and_finite(const Vec3& n) {
  return n.allFinite() && std::abs(n.norm() - 1) < 1e-12;
}

/// A simplex vertex for a point a of A and b of B.
SimplexVertex vertex(const Vec3& a, const Vec3& b) {
  SimplexVertex v;
  v.a = a;
  v.b = b;
  v.w = a - b;
  return v;
}

/// A GJK answer claiming contact with the given final simplex.
DistanceResult contact_with(std::initializer_list<SimplexVertex> points) {
  DistanceResult r;
  r.intersect = true;
  for (const SimplexVertex& v : points)
    r.simplex.push(v);
  r.witness_a = r.simplex[0].a;
  r.witness_b = r.simplex[0].b;
  return r;
}

double exact_depth(const Polytope& a, const Polytope& b) {
  const auto answer = exact::solve(a.vertices(), b.vertices(), {.depth = true});
  REQUIRE(answer.intersect);
  return answer.depth.value();
}

}  // namespace

TEST_CASE("epa: cubes of side 2 at z = 0 and z = 1.9 overlap by 0.1 along z", "[unit][epa]") {
  // libccd 2.1's GJK+EPA answers this pair with depth 0 and a NaN direction (see
  // test_depth_peers.cpp).
  const Polytope a = shapes::box(Vec3(2, 2, 2));
  const Polytope b = moved(a, Vec3(0, 0, 1.9));
  const EpaResult r = gjk_epa(a, b);
  CHECK(r.intersect);
  CHECK(r.termination == Termination::converged);
  CHECK(r.stop == EpaStop::converged);
  CHECK(std::abs(r.depth - 0.1) <= 1e-15);
  REQUIRE(unit_and_finite(r.normal));
  CHECK(r.normal.isApprox(Vec3::UnitZ(), 1e-15));
  // The deepest points: A's top face and B's bottom face.
  CHECK(std::abs(r.witness_a.z() - 1.0) <= 1e-15);
  CHECK(std::abs(r.witness_b.z() - 0.9) <= 1e-15);
  CHECK((r.witness_a - r.witness_b - r.depth * r.normal).norm() <= 1e-15);
  CHECK(r.depth <= r.depth_upper_bound);
  CHECK(r.depth == Approx(exact_depth(a, b)).epsilon(1e-15));
}

TEST_CASE("epa: known depths of boxes and a point", "[unit][epa]") {
  const Polytope box = shapes::box();
  struct Known {
    const char* name;
    Polytope b;
    double depth;
    Vec3 normal;
  };
  const std::vector<Known> known = {
      {"offset along x", moved(box, Vec3(0.5, 0.25, 0)), 0.5, Vec3::UnitX()},
      {"offset along -y", moved(box, Vec3(0.1, -0.7, 0.05)), 0.3, -Vec3::UnitY()},
      {"identical boxes", box, 1.0, Vec3::Zero()},
      {"point inside", Polytope({Vec3(0.1, 0.2, 0.35)}), 0.15, Vec3::UnitZ()},
  };
  for (const Known& k : known) {
    INFO(k.name);
    const EpaResult r = gjk_epa(box, k.b);
    CHECK(r.intersect);
    CHECK(r.termination == Termination::converged);
    CHECK(std::abs(r.depth - k.depth) <= 1e-15);
    CHECK(unit_and_finite(r.normal));
    if (k.normal != Vec3::Zero()) CHECK(r.normal.isApprox(k.normal, 1e-15));
    CHECK((r.witness_a - r.witness_b - r.depth * r.normal).norm() <= 1e-15);
  }
}

TEST_CASE("epa: touching pairs have depth 0", "[unit][epa]") {
  const Polytope box = shapes::box();
  const std::vector<std::pair<const char*, Vec3>> offsets = {
      {"face", Vec3(1, 0.25, 0.5)},
      {"edge", Vec3(1, 1, 0.5)},
      {"vertex", Vec3(1, 1, 1)},
      {"face, other side", Vec3(-0.3, 0.2, -1)}};
  for (const auto& [name, t] : offsets) {
    INFO(name);
    const EpaResult r = gjk_epa(box, moved(box, t));
    CHECK(r.intersect);
    CHECK(r.termination == Termination::converged);
    CHECK(r.depth <= 1e-15);
    CHECK(unit_and_finite(r.normal));
  }
  // A tetrahedron touching a box at a vertex, rotated so nothing is axis-aligned.
  const Polytope tetra({Vec3(0, 0, 0), Vec3(1, 0.2, 0.1), Vec3(0.3, 1, 0.2), Vec3(0.2, 0.3, 1)});
  const Polytope turned =
      box.transformed(Pose::from_quaternion(Quat(0.9, 0.1, 0.3, 0.2), Vec3::Zero()));
  const Vec3 corner = turned.support(Vec3(-1, -1, -1));
  const Polytope placed =
      tetra.transformed(Pose::from_translation(corner - tetra.support(Vec3(1, 1, 1))));
  const auto exact = exact::solve(turned.vertices(), placed.vertices(), {.depth = true});
  const EpaResult r = gjk_epa(turned, placed);
  CHECK(r.intersect == exact.intersect);
  if (exact.intersect) CHECK(std::abs(r.depth - *exact.depth) <= 1e-14);
}

TEST_CASE("epa: A − B without interior is flat and has depth 0", "[unit][epa]") {
  const Polytope tri({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  SECTION("coplanar overlapping triangles") {
    const EpaResult r = gjk_epa(tri, moved(tri, Vec3(0.2, 0.2, 0)));
    CHECK(r.intersect);
    CHECK(r.stop == EpaStop::flat_difference);
    CHECK(r.termination == Termination::converged);
    CHECK(r.depth == 0);
    CHECK(unit_and_finite(r.normal));
    CHECK(std::abs(r.normal.z()) == 1);
  }
  SECTION("crossing segments") {
    const EpaResult r = gjk_epa(Polytope({Vec3(-1, 0, 0), Vec3(1, 0, 0)}),
                                Polytope({Vec3(0, -1, 0), Vec3(0, 1, 0)}));
    CHECK(r.intersect);
    CHECK(r.stop == EpaStop::flat_difference);
    CHECK(r.depth == 0);
    CHECK(unit_and_finite(r.normal));
  }
  SECTION("equal points") {
    const EpaResult r = gjk_epa(Polytope({Vec3(0.1, 0.2, 0.3)}), Polytope({Vec3(0.1, 0.2, 0.3)}));
    CHECK(r.intersect);
    CHECK(r.stop == EpaStop::flat_difference);
    CHECK(r.depth == 0);
    CHECK(unit_and_finite(r.normal));
  }
  SECTION("a triangle through a box has interior") {
    const Polytope b = moved(tri, Vec3(-0.2, -0.2, 0.1));
    const EpaResult r = gjk_epa(shapes::box(), b);
    CHECK(r.stop == EpaStop::converged);
    CHECK(std::abs(r.depth - exact_depth(shapes::box(), b)) <= 1e-15);
  }
}

TEST_CASE("epa: blows up GJK simplices of one to four points, flat ones included", "[unit][epa]") {
  // A = box, B = box shifted: A − B holds the origin in its interior, depth 0.4 along x.
  const Polytope a = shapes::box();
  const Polytope b = moved(a, Vec3(0.6, 0.1, -0.05));
  const double expected = exact_depth(a, b);
  const Vec3 p(0.25, 0.1, 0.0);  // a point of both shapes
  const Vec3 u(0.05, 0.02, 0.01), v(-0.01, 0.04, 0.0), s(0.0, 0.01, 0.03);
  struct Start {
    const char* name;
    DistanceResult gjk;
  };
  const std::vector<Start> starts = {
      {"one point at the origin", contact_with({vertex(p, p)})},
      {"segment through the origin", contact_with({vertex(p + u, p), vertex(p, p + u)})},
      {"triangle around the origin",
       contact_with({vertex(p + u, p), vertex(p + v, p), vertex(p, p + u + v)})},
      {"flat tetrahedron around the origin",
       contact_with({vertex(p + u, p), vertex(p + v, p), vertex(p, p + u), vertex(p, p + v)})},
      {"collinear triangle",
       contact_with({vertex(p + u, p), vertex(p, p + u), vertex(p + 2 * u, p)})},
      {"segment of two equal points", contact_with({vertex(p + s, p + s), vertex(p, p)})},
  };
  for (const Start& start : starts) {
    INFO(start.name);
    EpaPolytope ws;
    const EpaResult r = epa_from_gjk(a, b, start.gjk, EpaOptions{}, ws);
    CHECK(r.intersect);
    CHECK(r.termination == Termination::converged);
    CHECK(std::abs(r.depth - expected) <= 1e-15);
    CHECK(unit_and_finite(r.normal));
    CHECK((r.witness_a - r.witness_b - r.depth * r.normal).norm() <= 1e-14);
  }
}

TEST_CASE("epa: depth agrees with the exact depth on 400 seeded random pairs", "[unit][epa]") {
  // Tolerance: 1e-12 of the pair's size (the larger bounding-box diagonal).
  constexpr double kTolerance = 1e-12;
  Rng rng(20260301);
  EpaPolytope ws;
  int intersecting = 0, shallow = 0, deep = 0, not_converged = 0;
  double worst = 0;
  int max_iterations = 0;
  for (int i = 0; i < 400; ++i) {
    const CloudKind kind = i % 2 ? CloudKind::cube : CloudKind::sphere;
    const int na = static_cast<int>(std::round(rng.log_uniform(4, 64)));
    const int nb = static_cast<int>(std::round(rng.log_uniform(4, 64)));
    // Overlaps from 1e-6 to 1 size: half shallow (log-uniform), half uniform.
    const double gap = (i / 2) % 2 == 0 ? -rng.log_uniform(1e-6, 0.1) : -rng.uniform(0.1, 1.0);
    const auto pair = testing::random_pair(rng, kind, na, nb, gap);
    const Polytope a(pair.a), b(pair.b);
    const auto exact = exact::solve(pair.a, pair.b, {.depth = true});
    const EpaResult r = gjk_epa(a, b, {}, {}, ws);
    const double size = pair_size(pair.a, pair.b);
    INFO("pair " << i << " (" << na << ", " << nb << " points)");
    if (!exact.intersect) {
      // Shallow placements can leave the hulls apart: GJK must see it (outside the band).
      if (exact.distance > 1e-10 * size) CHECK_FALSE(r.intersect);
      continue;
    }
    ++intersecting;
    (*exact.depth < 0.05 * size ? shallow : deep) += 1;
    if (r.termination != Termination::converged) ++not_converged;
    const double error = std::abs(r.depth - *exact.depth) / size;
    worst = std::max(worst, error);
    max_iterations = std::max(max_iterations, r.iterations);
    CHECK(error <= kTolerance);
    CHECK(unit_and_finite(r.normal));
    CHECK(r.depth <= r.depth_upper_bound + 1e-15 * size);  // bounds, up to rounding
  }
  CHECK(not_converged == 0);
  CHECK(intersecting > 200);
  CHECK(shallow > 10);
  CHECK(deep > 100);
  WARN("epa vs exact depth: " << intersecting << " intersecting pairs (" << shallow
                              << " with depth < 5% of size), worst |error| / size " << worst
                              << ", most EPA iterations " << max_iterations);
}

TEST_CASE("epa: separated pairs pass GJK's answer through", "[unit][epa]") {
  const Polytope box = shapes::box();
  const Polytope b = moved(box, Vec3(1.5, 0.2, 0.1));
  const EpaResult r = gjk_epa(box, b);
  CHECK_FALSE(r.intersect);
  CHECK(r.stop == EpaStop::separated);
  CHECK(r.termination == Termination::converged);
  CHECK(r.depth == 0);
  CHECK(std::abs(r.distance - 0.5) <= 1e-15);
  CHECK(r.normal.isApprox(Vec3::UnitX(), 1e-15));
  CHECK(r.iterations == 0);
  CHECK(r.faces == 0);

  GjkDistanceOptions short_gjk;
  short_gjk.max_iterations = 1;
  const Polytope sphere = shapes::uv_sphere();
  const EpaResult cut = gjk_epa(sphere, moved(sphere, Vec3(1.0001, 0.01, 0.02)), short_gjk);
  CHECK(cut.stop == EpaStop::gjk_failed);
  CHECK(cut.termination == Termination::step_limit);
  CHECK_FALSE(cut.intersect);
}

TEST_CASE("epa: iteration and face bounds stop with step_limit and a valid bound", "[unit][epa]") {
  const Polytope a = shapes::uv_sphere();
  const Polytope b =
      a.transformed(Pose::from_quaternion(Quat(0.3, 0.1, 0.5, 0.2), Vec3(0.1, 0.2, 0.05)));
  const double expected = exact_depth(a, b);
  const EpaResult full = gjk_epa(a, b);
  REQUIRE(full.termination == Termination::converged);
  REQUIRE(full.iterations > 10);
  CHECK(std::abs(full.depth - expected) <= 1e-14);

  SECTION("max_iterations") {
    EpaOptions o;
    o.max_iterations = 5;
    const EpaResult r = gjk_epa(a, b, {}, o);
    CHECK(r.stop == EpaStop::step_limit);
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.iterations == 5);
    CHECK(r.depth <= expected * (1 + 1e-15));              // a lower bound
    CHECK(r.depth_upper_bound >= expected * (1 - 1e-15));  // and an upper bound
    CHECK(unit_and_finite(r.normal));
  }
  SECTION("max_iterations = 0 answers the initial tetrahedron") {
    EpaOptions o;
    o.max_iterations = 0;
    const EpaResult r = gjk_epa(a, b, {}, o);
    CHECK(r.stop == EpaStop::step_limit);
    CHECK(r.iterations == 0);
    CHECK(r.faces == 4);
    CHECK(r.depth <= expected);
  }
  SECTION("max_faces") {
    EpaOptions o;
    o.max_faces = 12;
    const EpaResult r = gjk_epa(a, b, {}, o);
    CHECK(r.stop == EpaStop::out_of_faces);
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.faces <= 12);
    CHECK(r.depth <= expected * (1 + 1e-15));
  }
  SECTION("a reused workspace gives the same answer") {
    EpaPolytope ws;
    EpaOptions small;
    small.max_faces = 8;
    small.max_iterations = 2;
    (void)gjk_epa(shapes::box(), moved(shapes::box(), Vec3(0.5, 0, 0)), {}, small, ws);
    const EpaResult again = gjk_epa(a, b, {}, {}, ws);
    CHECK(again.depth == full.depth);
    CHECK(again.iterations == full.iterations);
    CHECK(again.normal == full.normal);
  }
}

TEST_CASE("epa: invalid options are rejected", "[unit][epa]") {
  const Polytope box = shapes::box();
  auto with = [](auto change) {
    EpaOptions o;
    change(o);
    return o;
  };
  CHECK_THROWS_AS(gjk_epa(box, box, {}, with([](EpaOptions& o) { o.max_iterations = -1; })),
                  std::invalid_argument);
  CHECK_THROWS_AS(gjk_epa(box, box, {}, with([](EpaOptions& o) { o.max_faces = 3; })),
                  std::invalid_argument);
  CHECK_THROWS_AS(gjk_epa(box, box, {}, with([](EpaOptions& o) { o.relative_gap = NAN; })),
                  std::invalid_argument);
  CHECK_THROWS_AS(gjk_epa(box, box, {}, with([](EpaOptions& o) { o.relative_noise = -1; })),
                  std::invalid_argument);
  CHECK(to_termination(EpaStop::out_of_faces) == Termination::step_limit);
  CHECK(to_termination(EpaStop::degenerate_polytope) == Termination::degenerate_simplex);
  CHECK(to_termination(EpaStop::non_finite) == Termination::numerical_failure);
  CHECK(to_string(EpaStop::flat_difference) == "flat_difference");
}
