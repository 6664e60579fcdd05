// Support-function micro-benchmarks: the blocked scan against the textbook loop it replaces,
// and hill climbing with a coherent hint (a slowly turning direction) and with random
// directions, on points of the unit sphere and on the demo shapes.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "gjklab/exact/hull_adjacency.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "random_inputs.hpp"

namespace {

using gjklab::Polytope;
using gjklab::Vec3;
using gjklab::bench::random_unit;

std::vector<Vec3> sphere_cloud(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i)
    pts.push_back(random_unit(rng));
  return pts;
}

std::vector<Vec3> random_directions(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Vec3> out;
  for (int i = 0; i < count; ++i)
    out.push_back(random_unit(rng));
  return out;
}

/// Directions turning by about `step` radians from one to the next (coherent queries).
std::vector<Vec3> turning_directions(int count, double step) {
  std::vector<Vec3> out;
  for (int i = 0; i < count; ++i) {
    const double t = step * i;
    out.push_back(Vec3(std::cos(t), std::sin(t), 0.3 * std::sin(0.37 * t)).normalized());
  }
  return out;
}

/// The loop the blocked scan replaces (Eigen dot per vertex, strict >).
std::size_t textbook_support(std::span<const Vec3> v, const Vec3& d) {
  std::size_t best = 0;
  double best_dot = v[0].dot(d);
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double dot = v[i].dot(d);
    if (dot > best_dot) {
      best_dot = dot;
      best = i;
    }
  }
  return best;
}

void BM_SupportTextbook(benchmark::State& state) {
  const Polytope p(sphere_cloud(static_cast<int>(state.range(0)), 1));
  const auto dirs = random_directions(256, 2);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(textbook_support(p.vertices(), dirs[k++ & 255]));
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_SupportBlockedScan(benchmark::State& state) {
  const Polytope p(sphere_cloud(static_cast<int>(state.range(0)), 1));
  const auto dirs = random_directions(256, 2);
  std::size_t k = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(p.scan_support_index(dirs[k++ & 255]));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

/// The blocked scan when each call needs the previous answer, as in a GJK iteration: the next
/// direction is chosen by the index just returned, so calls cannot overlap (latency, not
/// throughput).
void BM_SupportBlockedScanChained(benchmark::State& state) {
  const Polytope p(sphere_cloud(static_cast<int>(state.range(0)), 1));
  const auto dirs = random_directions(256, 2);
  std::size_t k = 0, last = 0;
  for (auto _ : state) {
    last = p.scan_support_index(dirs[(k++ + last) & 255]);
    benchmark::DoNotOptimize(last);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_SupportHillClimbRandom(benchmark::State& state) {
  const auto cloud = sphere_cloud(static_cast<int>(state.range(0)), 1);
  Polytope p(cloud);
  p.enable_hill_climbing(gjklab::exact::hull_vertex_adjacency(cloud));
  const auto dirs = random_directions(256, 2);
  std::size_t k = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(p.support_index(dirs[k++ & 255]));
}

void BM_SupportHillClimbCoherent(benchmark::State& state) {
  const auto cloud = sphere_cloud(static_cast<int>(state.range(0)), 1);
  Polytope p(cloud);
  p.enable_hill_climbing(gjklab::exact::hull_vertex_adjacency(cloud));
  const auto dirs = turning_directions(4096, 0.02);
  std::size_t k = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(p.support_index(dirs[k++ & 4095]));
}

void BM_SupportDemoShape(benchmark::State& state) {
  const Polytope shapes[] = {gjklab::shapes::box(), gjklab::shapes::cone(),
                             gjklab::shapes::cylinder(), gjklab::shapes::uv_sphere()};
  const Polytope& p = shapes[state.range(0)];
  const auto dirs = random_directions(256, 3);
  std::size_t k = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(p.support_index(dirs[k++ & 255]));
  state.SetLabel(std::to_string(p.size()) + " vertices");
}

}  // namespace

BENCHMARK(BM_SupportTextbook)->RangeMultiplier(4)->Range(8, 8192);
BENCHMARK(BM_SupportBlockedScan)->RangeMultiplier(4)->Range(8, 8192);
BENCHMARK(BM_SupportBlockedScanChained)->RangeMultiplier(4)->Range(8, 8192);
BENCHMARK(BM_SupportHillClimbRandom)->RangeMultiplier(4)->Range(8, 8192);
BENCHMARK(BM_SupportHillClimbCoherent)->RangeMultiplier(4)->Range(8, 8192);
BENCHMARK(BM_SupportDemoShape)->DenseRange(0, 3);
