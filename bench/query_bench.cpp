// Whole GJK distance queries (gjk-johnson, full-scan support) on the small shapes where the
// sub-algorithm, not the support function, sets the pace: random clouds of n points on the unit
// sphere 0.1 apart or overlapping by 0.1 (as `gjklab bench --suite random`), and two boxes
// with centres 0.5 apart (as the seed suite's box–box overlap). 64 seeded configurations,
// visited in turn.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "random_inputs.hpp"

namespace {

using gjklab::Polytope;
using gjklab::Vec3;
using gjklab::bench::random_unit;

constexpr int kConfigurations = 8;

gjklab::Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

struct Pair {
  Polytope a, b;
};

/// Two clouds of n unit vectors, B moved along a random u so that its extent along u starts
/// `gap` after A's ends (negative gap: overlap).
std::vector<Pair> cloud_pairs(int n, double gap) {
  std::mt19937_64 rng(11);
  std::vector<Pair> out;
  for (int k = 0; k < kConfigurations; ++k) {
    std::vector<Vec3> a, b;
    for (int i = 0; i < n; ++i)
      a.push_back(random_unit(rng));
    for (int i = 0; i < n; ++i)
      b.push_back(random_unit(rng));
    const Vec3 u = random_unit(rng);
    double a_max = -INFINITY, b_min = INFINITY;
    for (const Vec3& p : a)
      a_max = std::max(a_max, p.dot(u));
    for (const Vec3& p : b)
      b_min = std::min(b_min, p.dot(u));
    for (Vec3& p : b)
      p += (a_max - b_min + gap) * u;
    out.push_back({Polytope(a), Polytope(b)});
  }
  return out;
}

/// Two demo boxes, randomly rotated, centres `distance` apart in a random direction.
std::vector<Pair> box_pairs(double distance) {
  std::mt19937_64 rng(13);
  const Polytope box = gjklab::shapes::box();
  std::vector<Pair> out;
  for (int k = 0; k < kConfigurations; ++k) {
    const gjklab::Pose pa{random_rotation(rng), Vec3::Zero()};
    const gjklab::Pose pb{random_rotation(rng), distance * random_unit(rng)};
    out.push_back({box.transformed(pa), box.transformed(pb)});
  }
  return out;
}

void run_queries(benchmark::State& state, const std::vector<Pair>& pairs) {
  std::size_t k = 0;
  double iterations = 0;
  for (auto _ : state) {
    const Pair& p = pairs[k++ % pairs.size()];
    const auto r = gjklab::gjk_distance(p.a, p.b);
    benchmark::DoNotOptimize(r.distance);
    iterations += r.iterations;
  }
  state.counters["iterations"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}

void BM_GjkJohnsonCloudSeparated(benchmark::State& state) {
  run_queries(state, cloud_pairs(static_cast<int>(state.range(0)), 0.1));
}
void BM_GjkJohnsonCloudOverlap(benchmark::State& state) {
  run_queries(state, cloud_pairs(static_cast<int>(state.range(0)), -0.1));
}
void BM_GjkJohnsonBoxOverlap(benchmark::State& state) {
  run_queries(state, box_pairs(0.5));
}

}  // namespace

BENCHMARK(BM_GjkJohnsonCloudSeparated)->Arg(8)->Arg(32);
BENCHMARK(BM_GjkJohnsonCloudOverlap)->Arg(8)->Arg(32);
BENCHMARK(BM_GjkJohnsonBoxOverlap);
