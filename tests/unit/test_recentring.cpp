// Exact re-centring (geometry/recentring.hpp): when it applies, that the translation is exact
// on every coordinate, and that the queries answer in the original frame.
#include <catch2/catch.hpp>

#include <vector>

#include "../support/random_pairs.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/recentring.hpp"
#include "gjklab/gjk/epa.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/trace.hpp"

using namespace gjklab;
using testing::CloudKind;
using testing::Rng;

namespace {

std::vector<Vec3> moved(std::vector<Vec3> cloud, const Vec3& by) {
  for (Vec3& p : cloud)
    p += by;
  return cloud;
}

/// x − t is exact iff (x − t) + t gives x back and x − (x − t) gives t back.
bool exactly_translated(const Polytope& p, const Vec3& t) {
  for (const Vec3& x : p.vertices())
    for (int i = 0; i < 3; ++i) {
      const double d = x[i] - t[i];
      if (d + t[i] != x[i] || x[i] - d != t[i]) return false;
    }
  return true;
}

}  // namespace

TEST_CASE("exact re-centring: only far from the origin, and exact on every coordinate",
          "[unit][recentring]") {
  Rng rng(8);
  const auto a = testing::random_cloud(rng, CloudKind::sphere, 40);
  const auto b = moved(testing::random_cloud(rng, CloudKind::cube, 30), Vec3(2.5, 0, 0));
  // Near the origin: nothing to gain, the queries run on the coordinates as given.
  CHECK_FALSE(exact_recentring(Polytope(a), Polytope(b)).has_value());
  // [4, 5] would only become [0, 1]: less than three bits.
  CHECK_FALSE(exact_recentring(Polytope(moved(a, Vec3(5, 5, 5))), Polytope(moved(b, Vec3(5, 5, 5))))
                  .has_value());

  for (const Vec3& offset : {Vec3(1e8, -3e7, 2.5e6), Vec3(-1e6, 0, 0), Vec3(3e9, 3e9, -3e9)}) {
    INFO(offset.transpose());
    const Polytope pa(moved(a, offset)), pb(moved(b, offset));
    const auto t = exact_recentring(pa, pb);
    REQUIRE(t.has_value());
    CHECK(exactly_translated(pa, *t));
    CHECK(exactly_translated(pb, *t));
    // Axes near 0 (|offset| small against the pair) are not moved.
    for (int i = 0; i < 3; ++i)
      if (offset[i] == 0) CHECK((*t)[i] == 0);
    const Polytope ra = pa.translated(-*t);
    const Vec3 lo = ra.box_lower().cwiseMin(pb.translated(-*t).box_lower());
    CHECK(lo.minCoeff() >= -8);  // the pair is now a few units from the origin
  }
}

TEST_CASE("re-centred queries answer in the original frame, as exactly as at the origin",
          "[unit][recentring]") {
  Rng rng(9);
  for (int i = 0; i < 40; ++i) {
    const auto a0 = testing::random_cloud(rng, CloudKind::cube, 24);
    const auto b0 = moved(testing::random_cloud(rng, CloudKind::cube, 24),
                          rng.unit_vector() * (i % 2 ? 2.0 + rng.log_uniform(1e-9, 1) : 1.5));
    const Vec3 offset = rng.unit_vector() * 1e8;
    const auto a = moved(a0, offset), b = moved(b0, offset);
    const Polytope pa(a), pb(b);
    const auto exact = exact::solve(a, b);
    const double size = pair_size(a, b);
    INFO("pair " << i);

    TraceRecorder trace;
    const DistanceResult r = gjk_distance(pa, pb, {}, trace);
    CHECK(r.intersect == exact.intersect);
    CHECK(std::abs(r.distance - exact.distance) <= 1e-14 * size);
    // Simplex points and trace rows are the clouds' own points (moved back exactly).
    for (const SimplexVertex& v : r.simplex.vertices()) {
      CHECK(v.a == a[v.index_a]);
      CHECK(v.b == b[v.index_b]);
    }
    for (const GjkIterationTrace& row : trace.iterations)
      CHECK(row.support.a == a[row.support.index_a]);

    CHECK(gjk_intersect(pa, pb).intersect == exact.intersect);
    if (exact.intersect) {
      const EpaResult e = gjk_epa(pa, pb);
      CHECK(e.intersect);
      // The deepest points are points of the original shapes: near the pair, not the origin.
      CHECK((e.witness_a - offset).norm() < 4);
    } else {
      CHECK((r.witness_a - offset).norm() < 4);
    }
  }
}
