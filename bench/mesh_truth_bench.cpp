// The exact truth for two closed meshes (exact::mesh_truth) near contact: two non-convex star
// meshes of 2·segments·(rings − 1) triangles each, B placed along x so that the boxes are 10⁻³
// apart (length units; the meshes have radius ≤ 1), where the culling has the least room.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>

#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"

namespace {

using gjklab::TriangleMesh;
using gjklab::Vec3;

TriangleMesh random_star(int segments, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> radius(0.8, 1.0);
  return gjklab::star_mesh(segments + 1, segments, [&](const Vec3&) { return radius(rng); });
}

/// B rotated about (1, 2, 3) by `angle` and moved along x to 10⁻³ beyond A's box.
TriangleMesh near_contact(const TriangleMesh& a, TriangleMesh b, double angle) {
  const gjklab::Mat3 r = Eigen::AngleAxisd(angle, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  double a_max = -1e300, b_min = 1e300;
  for (const Vec3& v : a.vertices)
    a_max = std::max(a_max, v.x());
  for (Vec3& v : b.vertices) {
    v = r * v;
    b_min = std::min(b_min, v.x());
  }
  for (Vec3& v : b.vertices)
    v.x() += a_max - b_min + 1e-3;
  return b;
}

void BM_MeshTruthNearContact(benchmark::State& state) {
  const int segments = static_cast<int>(state.range(0));
  std::mt19937_64 rng(5);
  const TriangleMesh a = random_star(segments, rng);
  const TriangleMesh b = near_contact(a, random_star(segments, rng), 0.7);
  std::uint64_t evaluations = 0;
  for (auto _ : state) {
    const gjklab::exact::MeshTruth t = gjklab::exact::mesh_truth(a, b);
    evaluations = t.exact_distance_evaluations;
    benchmark::DoNotOptimize(t.distance);
  }
  state.counters["triangles"] = static_cast<double>(a.faces.size());
  state.counters["exact_evaluations"] = static_cast<double>(evaluations);
}

}  // namespace

// 10, 22 and 50 segments: 200, 968 and 5 000 triangles per mesh.
BENCHMARK(BM_MeshTruthNearContact)->Arg(10)->Arg(22)->Arg(50)->Unit(benchmark::kMillisecond);
