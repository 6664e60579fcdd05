// The benchmark's direct loops: every algorithm but the exact oracle has one, and each makes
// the same queries as a loop over the registry's run(): equal iteration, support-call and
// intersection counts and the same sum of distances, on overlapping and separated pairs.
#include <catch2/catch.hpp>

#include <vector>

#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/shapes.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

namespace {

/// Boxes and cones, overlapping and apart, in a few orientations: boolean and distance answers.
std::vector<Polytope> test_shapes() {
  std::vector<Polytope> shapes;
  const Polytope box = shapes::box(), cone = shapes::cone();
  for (int k = 0; k < 4; ++k) {
    const double angle = 0.4 * k + 0.1;
    const Mat3 r = Eigen::AngleAxisd(angle, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    shapes.push_back(box.transformed({r, Vec3::Zero()}));
    shapes.push_back(cone.transformed({r.transpose(), Vec3(0.5 + 0.7 * k, 0.1 * k, 0)}));
  }
  return shapes;
}

}  // namespace

TEST_CASE("bench: each direct loop makes the registry's queries", "[unit][bench]") {
  const std::vector<Polytope> shapes = test_shapes();
  std::vector<BenchPair> pairs;
  for (std::size_t i = 0; i + 1 < shapes.size(); i += 2)
    pairs.push_back({&shapes[i], &shapes[i + 1]});
  const AlgorithmOptions options;
  for (const AlgorithmInfo& algorithm : algorithms()) {
    const BenchLoop loop = find_bench_loop(algorithm.name);
    if (algorithm.name == "exact") {
      CHECK(loop == nullptr);  // minutes per query on large clouds: never in a timed loop
      continue;
    }
    INFO(algorithm.name);
    REQUIRE(loop != nullptr);
    const BenchTally direct = loop(pairs, options, 2);
    const BenchTally registry = run_bench_loop_via_registry(algorithm, pairs, options, 2);
    CHECK(direct.queries == 2 * static_cast<long long>(pairs.size()));
    CHECK(direct.queries == registry.queries);
    CHECK(direct.iterations == registry.iterations);
    CHECK(direct.support_calls == registry.support_calls);
    CHECK(direct.intersections == registry.intersections);
    CHECK(direct.distance_sum == registry.distance_sum);
    // Both kinds of pair were queried.
    CHECK(registry.intersections > 0);
    CHECK(registry.intersections < registry.queries);
  }
}
