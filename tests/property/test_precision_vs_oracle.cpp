// The GJK queries in float and long double against the exact oracle, on seeded random pairs.
//
// A query in float runs on the clouds rounded to float, so it is judged against the exact
// answer for those rounded clouds (input rounding is not the query's error): booleans must be
// right outside a touching band of 1e-5 × size and distances within 1e-5 × size (float's unit
// roundoff is 6e-8; GJK's distance error grows with a few hundred of them on these pairs). In
// long double the queries must be at least as accurate as the double bound of
// test_gjk_vs_oracle.cpp (1e-14 × size for Johnson's sub-algorithm).
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>

#include "../support/random_pairs.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/scalar_cloud.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/subalgorithms.hpp"

using namespace gjklab;
using testing::CloudKind;
using testing::Rng;

namespace {

std::vector<Vec3> rounded_to_float(const std::vector<Vec3>& cloud) {
  std::vector<Vec3> out;
  for (const Vec3& x : cloud)
    out.push_back(x.cast<float>().cast<double>());
  return out;
}

struct Tally {
  int wrong_outside_band = 0;
  int not_converged = 0;
  double worst_relative_error = 0;
};

/// Runs every GJK query of the registry in `precision` on `pairs` random pairs and tallies its
/// answers against the exact answer of the inputs as the query sees them.
std::map<std::string, Tally> tally_precision(ScalarPrecision precision, int pairs, double band,
                                             int& intersecting, int& separated) {
  Rng rng(20261125);
  experiment::AlgorithmOptions options;
  options.precision = precision;
  std::map<std::string, Tally> tallies;
  for (int i = 0; i < pairs; ++i) {
    const CloudKind kind = (i % 2 == 0) ? CloudKind::sphere : CloudKind::cube;
    const int na = static_cast<int>(std::round(rng.log_uniform(4, 128)));
    const int nb = static_cast<int>(std::round(rng.log_uniform(4, 128)));
    const double gap = (i % 3 == 0) ? rng.log_uniform(1e-3, 3) : -rng.uniform(1e-3, 0.5);
    auto pair = testing::random_pair(rng, kind, na, nb, gap);
    if (precision == ScalarPrecision::single_float) {
      // The pair as the float query sees it: its exact answer is the reference.
      pair.a = rounded_to_float(pair.a);
      pair.b = rounded_to_float(pair.b);
    }
    const Polytope a(pair.a), b(pair.b);
    const double size = pair_size(pair.a, pair.b);
    const auto exact = exact::solve(a.vertices(), b.vertices());
    exact.intersect ? ++intersecting : ++separated;
    for (const auto& algorithm : experiment::algorithms()) {
      if (!experiment::takes_precision(algorithm)) continue;
      const auto o = experiment::run_algorithm(algorithm, a, b, {}, options);
      Tally& t = tallies[std::string(algorithm.name)];
      const bool in_band = !exact.intersect && exact.distance <= band * size;
      if (o.intersect != exact.intersect && !in_band && !exact.intersect) ++t.wrong_outside_band;
      if (o.intersect != exact.intersect && exact.intersect) {
        const double depth =
            exact::solve(a.vertices(), b.vertices(), {.depth = true}).depth.value();
        if (depth > band * size) ++t.wrong_outside_band;
      }
      if (o.termination != Termination::converged) ++t.not_converged;
      if (o.distance)
        t.worst_relative_error =
            std::max(t.worst_relative_error, std::abs(*o.distance - exact.distance) / size);
    }
  }
  return tallies;
}

}  // namespace

TEST_CASE("GJK queries in float agree with the exact answer of the rounded inputs",
          "[property][precision]") {
  int intersecting = 0, separated = 0;
  const auto tallies =
      tally_precision(ScalarPrecision::single_float, 300, 1e-5, intersecting, separated);
  CHECK(intersecting > 50);
  CHECK(separated > 50);
  REQUIRE(tallies.size() == 8);  // gjk-bool, five distance variants, nesterov/polyak, epa
  for (const auto& [name, t] : tallies) {
    INFO(name << ": wrong " << t.wrong_outside_band << ", not converged " << t.not_converged
              << ", worst error / size " << t.worst_relative_error);
    CHECK(t.wrong_outside_band == 0);
    CHECK(t.worst_relative_error <= 1e-5);
    // Float's rounding leaves the GJK distance variants short of the double tolerances
    // (relative_gap 1e-12): they end by a repeated support point (converged) or by
    // no_progress at the best point found, never at the step limit.
    CHECK(t.not_converged <= 300);
  }
}

TEST_CASE("GJK queries in long double are at least as accurate as in double",
          "[property][precision]") {
  int intersecting = 0, separated = 0;
  const auto tallies =
      tally_precision(ScalarPrecision::long_double, 200, 1e-10, intersecting, separated);
  CHECK(intersecting > 30);
  CHECK(separated > 30);
  for (const auto& [name, t] : tallies) {
    INFO(name << ": wrong " << t.wrong_outside_band << ", not converged " << t.not_converged
              << ", worst error / size " << t.worst_relative_error);
    CHECK(t.wrong_outside_band == 0);
    CHECK(t.worst_relative_error <= 1e-13);
    CHECK(t.not_converged <= 2);
  }
}

TEST_CASE("the double instantiation on a ScalarCloud<double> is the Polytope query, bit for bit",
          "[property][precision]") {
  // ScalarCloud's plain scan returns Polytope's support indices (the first maximiser, the same
  // dot products), so a query templated on double must answer exactly as on a Polytope.
  Rng rng(7);
  for (int i = 0; i < 200; ++i) {
    const auto pair =
        testing::random_pair(rng, i % 2 ? CloudKind::cube : CloudKind::sphere, 16 + i % 40,
                             8 + i % 30, i % 3 ? rng.log_uniform(1e-6, 1) : -0.1);
    const Polytope pa(pair.a), pb(pair.b);
    const ScalarCloud<double> ca(pair.a), cb(pair.b);
    const DistanceResult p = gjk_distance(pa, pb);
    const DistanceResult c = gjk_distance(ca, cb);
    CHECK(p.distance == c.distance);
    CHECK(p.witness_a == c.witness_a);
    CHECK(p.iterations == c.iterations);
    const DistanceResult ps = gjk_distance_with<SignedVolumesSubAlgorithm>(pa, pb, {});
    const DistanceResult cs = gjk_distance_with<SignedVolumesSubAlgorithm>(ca, cb, {});
    CHECK(ps.distance == cs.distance);
    CHECK(gjk_intersect(pa, pb).intersect == gjk_intersect(ca, cb).intersect);
    CHECK(gjk_intersect(pa, pb).iterations == gjk_intersect(ca, cb).iterations);
  }
}
