// The certificates on hand-made exact cases, and on adversarial hints: a hint that is wrong,
// perturbed, out of range, open, reversed or non-convex either still leads to the exact answer
// or falls back; it never certifies a wrong value.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "../support/gjk_hints.hpp"
#include "gjklab/exact/certificate.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/exact/witness.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/epa.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

using namespace gjklab;
using exact::AnswerMethod;
using exact::DepthHint;
using exact::DistanceHint;
using exact::IndexPair;
using gjklab::testing::gjk_hint;

namespace {

using Cloud = std::vector<Vec3>;

bool same(const exact::Rational& x, const exact::Rational& y) {
  return x.numerator() == y.numerator() && x.denominator() == y.denominator();
}

exact::Rational rational(const char* num, const char* den = "1") {
  return {num, den};
}

exact::OracleAnswer qp(const Cloud& a, const Cloud& b) {
  return exact::solve(a, b, {.depth = true, .certificates = false});
}

DepthHint epa_hint(const Cloud& a, const Cloud& b) {
  const Polytope pa(a), pb(b);
  EpaPolytope ws;
  const EpaResult r = epa_from_gjk(pa, pb, gjk_distance(pa, pb), EpaOptions{}, ws);
  DepthHint h;
  if (r.faces == 0) return h;
  for (const SimplexVertex& v : ws.vertices)
    h.vertices.push_back({v.index_a, v.index_b});
  for (const EpaPolytope::Face& f : ws.faces)
    if (f.alive) h.faces.push_back(f.v);
  return h;
}

Cloud box(const Vec3& centre, double half = 1) {
  Cloud out;
  for (int i = 0; i < 8; ++i)
    out.push_back(centre + half * Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
  return out;
}

/// A certified distance, when there is one, must equal the QP's.
void check_never_wrong(const Cloud& a, const Cloud& b, const DistanceHint& hint, int steps) {
  const auto c = exact::certify_distance(a, b, hint, steps);
  if (!c) return;
  const exact::OracleAnswer q = qp(a, b);
  CHECK(same(c->distance_squared, q.distance_squared));
  CHECK(c->intersect == q.intersect);
}

}  // namespace

TEST_CASE("distance certificate: hand-made exact cases", "[unit][certificate]") {
  struct Case {
    const char* name;
    Cloud a, b;
    exact::Rational d2;
    Vec3 witness_a, witness_b;
  };
  const std::vector<Case> cases = {
      {"crossing edges at distance 1",
       {{-1, 0, 0}, {1, 0, 0}},
       {{0, -1, 1}, {0, 1, 1}},
       rational("1"),
       {0, 0, 0},
       {0, 0, 1}},
      {"vertex over a face",
       {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, -1}},
       {{1, 1, 3}},
       rational("9"),
       {1, 1, 0},
       {1, 1, 3}},
      {"single points", {{0, 0, 0}}, {{1, 2, 2}}, rational("9"), {0, 0, 0}, {1, 2, 2}},
      {"collinear segments",
       {{0, 0, 0}, {1, 0, 0}, {0.5, 0, 0}},
       {{4, 0, 0}, {3, 0, 0}},
       rational("4"),
       {1, 0, 0},
       {3, 0, 0}},
      {"coplanar triangles 1/2 apart",
       {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
       {{1.5, 0, 0}, {2, 1, 0}, {2, -1, 0}},
       rational("1", "4"),
       {1, 0, 0},
       {1.5, 0, 0}},
      {"edge to edge at a skew angle",
       {{0, 0, 0}, {2, 2, 0}},
       {{2, 0, 1}, {0, 2, 1}},
       rational("1"),
       {1, 1, 0},
       {1, 1, 1}},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    for (const DistanceHint& hint : {gjk_hint(c.a, c.b), DistanceHint{}}) {
      const auto cert = exact::certify_distance(c.a, c.b, hint);
      REQUIRE(cert.has_value());
      CHECK_FALSE(cert->intersect);
      CHECK(same(cert->distance_squared, c.d2));
      CHECK(cert->witness_a == c.witness_a);
      CHECK(cert->witness_b == c.witness_b);
    }
  }
}

TEST_CASE("distance certificate: touching and crossing pairs are proven intersecting",
          "[unit][certificate]") {
  const std::vector<std::pair<Cloud, Cloud>> pairs = {
      {box({0, 0, 0}), box({2, 0.25, 0.5})},                        // faces touching exactly
      {box({0, 0, 0}), box({2, 2, 2})},                             // corners touching
      {{{-1, 0, 0}, {1, 0, 0}}, {{0, -1, 0}, {0, 1, 0}}},           // crossing segments
      {{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, {{1, 1, 0}, {3, 3, 0}}},  // coplanar: edge meets edge
      {{{0, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}},                        // point on a segment's end
      {box({0, 0, 0}), {{0.3, 0.1, -0.2}}},                         // point inside a box
  };
  for (const auto& [a, b] : pairs) {
    const auto cert = exact::certify_distance(a, b, gjk_hint(a, b));
    REQUIRE(cert.has_value());
    CHECK(cert->intersect);
    CHECK(cert->distance_squared.is_zero());
    CHECK(cert->witness_a == cert->witness_b);  // a common point
  }
}

TEST_CASE("distance certificate: non-dyadic, tiny, huge and mixed coordinates equal the QP",
          "[unit][certificate]") {
  const std::vector<std::pair<Cloud, Cloud>> pairs = {
      {{{0.1, 0.2, 0.3}, {0.7, -0.1, 0.2}, {0.3, 0.3, 0.9}}, {{1.1, 0.1, 0.1}, {1.3, 0.9, -0.4}}},
      {{{1e-300, 0, 0}, {0, 1e-300, 0}, {0, 0, 1e-300}}, {{3e-300, 3e-300, 3e-300}}},
      {{{1e300, 0, 0}, {0, 1e300, 0}}, {{1e300, 1e300, 1e300}, {-1e300, 2e300, 1e299}}},
      {{{1e-310, 5e-324, 0}, {1, 1e-20, 1e20}}, {{3, 3, 3}, {1e8, -1e-8, 4}}},
      {{{1e8, 0, 0}, {1e8 + 1, 0, 0}, {1e8, 1, 0}}, {{1e8 + 0.25, 0.25, 1e-9}}},
  };
  for (const auto& [a, b] : pairs) {
    const auto cert = exact::certify_distance(a, b, gjk_hint(a, b));
    REQUIRE(cert.has_value());
    const exact::OracleAnswer q = qp(a, b);
    CHECK(same(cert->distance_squared, q.distance_squared));
    CHECK(cert->intersect == q.intersect);
  }
}

TEST_CASE("distance certificate: adversarial hints never certify a wrong value",
          "[unit][certificate]") {
  std::mt19937_64 rng(20261123);
  std::normal_distribution<double> normal;
  auto sphere = [&](int n, const Vec3& centre) {
    Cloud out;
    for (int i = 0; i < n; ++i)
      out.push_back(centre + Vec3(normal(rng), normal(rng), normal(rng)).normalized());
    return out;
  };
  int fallbacks = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Cloud a = sphere(24, Vec3::Zero());
    const Cloud b = sphere(24, Vec3(trial % 2 ? 2.5 : 1.5, 0.1, 0));
    std::uniform_int_distribution<int> index(-3, 26);  // some out of range on purpose
    DistanceHint wrong;
    for (int k = 0; k < 1 + trial % 6; ++k)  // up to six points, some repeated
      wrong.simplex.push_back({index(rng), index(rng)});
    for (int steps : {0, 1, 64}) {
      check_never_wrong(a, b, wrong, steps);
      fallbacks += !exact::certify_distance(a, b, wrong, steps);
    }
    // The right simplex with one point swapped for another vertex pair.
    DistanceHint perturbed = gjk_hint(a, b);
    perturbed.simplex.back().a = (perturbed.simplex.back().a + 1) % 24;
    check_never_wrong(a, b, perturbed, 0);
    check_never_wrong(a, b, perturbed, 64);
  }
  CHECK(fallbacks > 100);  // wrong hints with no repair steps must fall back
}

TEST_CASE("oracle: a hint that cannot be certified falls back to the QP", "[unit][certificate]") {
  const Cloud a = box({0, 0, 0}), b = box({3, 0.5, 0.25});
  exact::OracleHints hints;
  hints.distance = DistanceHint{{{0, 7}}};  // a far pair, and no repair steps allowed
  const exact::OracleAnswer fallback =
      exact::solve(a, b, {.certificate_steps = 0, .verify = true}, hints);
  CHECK(fallback.method == AnswerMethod::qp);
  CHECK(same(fallback.distance_squared, rational("1")));
  const exact::OracleAnswer repaired = exact::solve(a, b, {.verify = true}, hints);
  CHECK(repaired.method == AnswerMethod::certified);
  CHECK(same(repaired.distance_squared, rational("1")));
  CHECK(repaired.hull_vertices_a == 8);
  const exact::OracleAnswer no_counts = exact::solve(a, b, {.hull_vertices = false}, hints);
  CHECK(no_counts.hull_vertices_a == -1);
}

TEST_CASE("depth certificate: overlapping boxes, certified and exact", "[unit][certificate]") {
  const Cloud a = box({0, 0, 0}), b = box({1.5, 0.25, 0.5});
  const DepthHint hint = epa_hint(a, b);
  REQUIRE(hint.faces.size() >= 4);
  const auto cert = exact::certify_depth(a, b, hint);
  REQUIRE(cert.has_value());
  CHECK(same(cert->depth_squared, rational("1", "4")));
  CHECK(cert->normal.isApprox(Vec3(1, 0, 0), 1e-15));
  exact::OracleHints hints;
  hints.depth = hint;
  const exact::OracleAnswer answer = exact::solve(a, b, {.depth = true, .verify = true}, hints);
  CHECK(answer.depth_method == AnswerMethod::certified);
  CHECK(*answer.depth == 0.5);
}

TEST_CASE("depth certificate: adversarial polytopes are rebuilt or fall back, never wrong",
          "[unit][certificate]") {
  const Cloud a = box({0, 0, 0}), b = box({1.5, 0.25, 0.5});
  const DepthHint good = epa_hint(a, b);
  REQUIRE(exact::certify_depth(a, b, good).has_value());

  // Faces that fail the checks are rebuilt once from the exact hull of the hint's points of
  // A − B: the answer is then the right one, certified.
  DepthHint open = good;  // one face missing: not a closed surface
  open.faces.pop_back();
  DepthHint reversed = good;  // every face turned inside out
  for (auto& f : reversed.faces)
    std::swap(f[1], f[2]);
  for (const DepthHint& rebuilt : {open, reversed}) {
    const auto c = exact::certify_depth(a, b, rebuilt);
    REQUIRE(c.has_value());
    CHECK(same(c->depth_squared, rational("1", "4")));
  }
  // Points that do not span space cannot be rebuilt: a flat set of four of the hint's points.
  DepthHint flat;
  flat.vertices = {{0, 0}, {1, 0}, {2, 0}, {3, 0}};  // a face of the box A minus one b: flat
  flat.faces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
  CHECK_FALSE(exact::certify_depth(a, b, flat).has_value());

  DepthHint out_of_range = good;  // a face index past the vertices: rebuilt from the points
  out_of_range.faces[0][0] = static_cast<int>(good.vertices.size());
  const auto rebuilt = exact::certify_depth(a, b, out_of_range);
  REQUIRE(rebuilt.has_value());
  CHECK(same(rebuilt->depth_squared, rational("1", "4")));

  DepthHint bad_index = good;
  bad_index.vertices[0].a = 99;
  CHECK_FALSE(exact::certify_depth(a, b, bad_index).has_value());

  DepthHint duplicate = good;  // two vertex slots for one point
  duplicate.vertices.push_back(duplicate.vertices[duplicate.faces[0][0]]);
  duplicate.faces[0][0] = static_cast<int>(duplicate.vertices.size()) - 1;
  CHECK_FALSE(exact::certify_depth(a, b, duplicate).has_value());

  CHECK_FALSE(exact::certify_depth(a, b, DepthHint{}).has_value());

  // Closed polytopes of points of A − B that need not hold the origin, and need not touch the
  // boundary of A − B: certified only if they really give the answer.
  const Cloud small_a = {{-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}, {0.2, 0.2, 0.2}};
  const Cloud small_b = {{0.1, 0.1, 0.1}};
  DepthHint inner;
  inner.vertices = {{0, 0}, {1, 0}, {2, 0}, {3, 0}};
  inner.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const auto inner_cert = exact::certify_depth(small_a, small_b, inner);
  if (inner_cert) {  // only if it really is the answer
    const exact::OracleAnswer q = qp(small_a, small_b);
    CHECK(same(inner_cert->depth_squared, *q.depth_squared));
  }
  // The same with a vertex replaced by an interior point of A − B.
  DepthHint dented = inner;
  dented.vertices[3] = {4, 0};
  const auto dented_cert = exact::certify_depth(small_a, small_b, dented);
  if (dented_cert) CHECK(same(dented_cert->depth_squared, *qp(small_a, small_b).depth_squared));

  // Through the oracle: a depth hint that can be neither checked nor rebuilt is answered by
  // the Minkowski hull.
  exact::OracleHints hints;
  hints.depth = bad_index;
  const exact::OracleAnswer answer = exact::solve(a, b, {.depth = true}, hints);
  CHECK(answer.depth_method == AnswerMethod::qp);
  CHECK(same(*answer.depth_squared, rational("1", "4")));
}

TEST_CASE("depth certificate: a polytope that misses the origin is never certified",
          "[unit][certificate]") {
  // A − B is the box [−1, 1]³ moved by 0.9 along x, so the origin is 0.1 from its face
  // x = −0.1. The hint is the tetrahedron of four of its corners (x-major order below) whose
  // nearest face plane lies on the facet y = −1 of A − B, a supporting plane 1 from the origin:
  // without the check that the origin is behind every face, that plane would pass as the depth.
  Cloud a;
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0})
      for (double z : {-1.0, 1.0})
        a.push_back({x, y, z});
  const Cloud b = {{-0.9, 0, 0}};
  DepthHint hint;
  hint.vertices = {{0, 0}, {4, 0}, {5, 0}, {6, 0}};
  hint.faces = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  // Orient each face outward (away from the tetrahedron's centroid).
  Vec3 centroid = Vec3::Zero();
  for (const IndexPair& v : hint.vertices)
    centroid += (a[v.a] - b[v.b]) / 4;
  for (auto& f : hint.faces) {
    const Vec3 p0 = a[hint.vertices[f[0]].a] - b[0];
    const Vec3 n =
        (a[hint.vertices[f[1]].a] - b[0] - p0).cross(a[hint.vertices[f[2]].a] - b[0] - p0);
    if (n.dot(centroid - p0) > 0) std::swap(f[1], f[2]);
  }
  // Rebuilding from the hull of its points gives the same tetrahedron: no certificate, so the
  // oracle falls back to the Minkowski hull (whose depth is 0.1 up to the rounding of 0.9).
  CHECK_FALSE(exact::certify_depth(a, b, hint, 0).has_value());
  CHECK_FALSE(exact::certify_depth(a, b, hint).has_value());
  exact::OracleHints hints;
  hints.depth = hint;
  const exact::OracleAnswer answer = exact::solve(a, b, {.depth = true}, hints);
  CHECK(answer.depth_method == AnswerMethod::qp);
  CHECK(std::abs(*answer.depth - 0.1) < 1e-15);
}

TEST_CASE("witness errors: exact distance to the hull and to the exact distance",
          "[unit][certificate]") {
  const Cloud unit_box = box({0, 0, 0});
  CHECK(exact::distance_to_hull(unit_box, {3, 0, 0}) == 2);
  CHECK(exact::distance_to_hull(unit_box, {2, 2, 1}) == std::sqrt(2.0));
  CHECK(exact::distance_to_hull(unit_box, {0.5, -0.25, 1}) == 0);  // on a face
  CHECK(exact::distance_to_hull(unit_box, {0.1, 0.2, 0.3}) == 0);  // inside
  CHECK(exact::distance_to_hull(Cloud{{1, 1, 1}}, {1, 1, 1 + 0x1p-40}) == 0x1p-40);
  CHECK(exact::distance_difference({0, 0, 0}, {3, 4, 0}, rational("25")) == 0);
  CHECK(exact::distance_difference({0, 0, 0}, {3, 4, 0}, rational("16")) == 1);
  CHECK(exact::distance_difference({0, 0, 0}, {3, 4, 0}, rational("36")) == 1);
  // 1 + 2^-52 against 1: the difference is exactly one ulp of 1, however close.
  CHECK(exact::distance_difference({0, 0, 0}, {1 + 0x1p-52, 0, 0}, rational("1")) == 0x1p-52);
  CHECK_THROWS(exact::distance_to_hull(unit_box, {NAN, 0, 0}));
}
