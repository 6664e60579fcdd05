// Johnson's distance sub-algorithm on random simplices of one to four points.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "gjklab/gjk/johnson.hpp"

namespace {

void BM_JohnsonClosestPoint(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::array<gjklab::Vec3, 4>> simplices(256);
  for (auto& s : simplices)
    for (auto& p : s)
      p = gjklab::Vec3(u(rng), u(rng), u(rng)) + gjklab::Vec3(0.5, 0, 0);
  std::size_t k = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(gjklab::johnson_closest_point(simplices[k++ & 255], count));
}

void BM_JohnsonCofactors(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::array<gjklab::Vec3, 4>> simplices(256);
  for (auto& s : simplices)
    for (auto& p : s)
      p = gjklab::Vec3(u(rng), u(rng), u(rng));
  std::size_t k = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(gjklab::johnson_cofactors(simplices[k++ & 255], count));
}

}  // namespace

BENCHMARK(BM_JohnsonClosestPoint)->DenseRange(1, 4);
BENCHMARK(BM_JohnsonCofactors)->DenseRange(1, 4);
