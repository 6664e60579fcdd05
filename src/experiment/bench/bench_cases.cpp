// The benchmark's cases: the classic demo's shape pairs (seed), random clouds from 8 to 8192
// points (random) and one scene of demo shapes (scene), each drawn from the seeded random module.
#include <string>
#include <string_view>
#include <vector>

#include "bench_parts.hpp"
#include "gjklab/exact/hull_adjacency.hpp"
#include "gjklab/experiment/cases/seeded_random.hpp"

namespace gjklab::experiment::bench {

namespace {

using Rng = SeededRandom;

/// The shape as the "+hc" rows use it: with hill climbing from kHillClimbingMinVertices
/// vertices on (where it beats the scan), else the same full-scan shape.
Polytope climbing_copy(const Polytope& shape) {
  Polytope copy = shape;
  if (shape.size() >= kHillClimbingMinVertices)
    copy.enable_hill_climbing(exact::hull_vertex_adjacency(shape.vertices()));
  return copy;
}

const Polytope* with_hill_climbing(ShapeStore& store, const Polytope& shape) {
  return store.add(climbing_copy(shape));
}

bool wanted(const BenchConfig& config, const std::string& name) {
  return config.case_filter.empty() || name.find(config.case_filter) != std::string::npos;
}

std::vector<Case> seed_cases(const BenchConfig& config, ShapeStore& store, bool hill_climbing) {
  std::vector<Case> out;
  // Body-frame shapes; hill-climbing copies carry their adjacency through transformed().
  std::vector<Polytope> base, base_hc;
  for (const DemoShape& s : kDemoShapes) {
    base.push_back(s.make());
    if (hill_climbing) base_hc.push_back(climbing_copy(base.back()));
  }
  int case_index = 0;
  for (const auto& [ia, ib] : kSeedPairs) {
    for (const bool overlap : {true, false}) {
      Case c;
      c.suite = "seed";
      c.pair = std::string(kDemoShapes[ia].name) + "-" + kDemoShapes[ib].name;
      c.placement = overlap ? "overlap" : "separated";
      c.name = c.pair + " " + c.placement;
      Rng rng(config.seed * 1000003 + static_cast<std::uint64_t>(case_index++));
      if (!wanted(config, c.name)) continue;
      const double distance = overlap ? kSeedOverlapDistance : kSeedSeparatedDistance;
      for (int k = 0; k < config.configurations; ++k) {
        const Pose pa{rng.rotation(), Vec3::Zero()};
        const Mat3 rb = rng.rotation();
        const Pose pb{rb, distance * rng.unit_vector()};
        c.pairs.push_back(
            {store.add(base[ia].transformed(pa)), store.add(base[ib].transformed(pb))});
        if (hill_climbing)
          c.hc_pairs.push_back(
              {store.add(base_hc[ia].transformed(pa)), store.add(base_hc[ib].transformed(pb))});
      }
      out.push_back(std::move(c));
    }
  }
  return out;
}

std::vector<Case> random_cases(const BenchConfig& config, ShapeStore& store, bool hill_climbing) {
  std::vector<Case> out;
  int case_index = 0;
  for (int n : kRandomSizes) {
    for (const bool overlap : {false, true}) {
      Case c;
      c.suite = "random";
      c.pair = "n=" + std::to_string(n);
      c.placement = overlap ? "overlap" : "separated";
      c.name = c.pair + " " + c.placement;
      Rng rng(config.seed * 2000003 + static_cast<std::uint64_t>(case_index++));
      if (!wanted(config, c.name)) continue;
      const double gap = overlap ? -kRandomGap : kRandomGap;
      for (int k = 0; k < config.configurations; ++k) {
        std::vector<Vec3> a, b;
        for (int i = 0; i < n; ++i)
          a.push_back(rng.unit_vector());
        for (int i = 0; i < n; ++i)
          b.push_back(rng.unit_vector());
        // Move B along u so that its extent along u starts `gap` after A's ends.
        const Vec3 u = rng.unit_vector();
        const Vec3 shift = separating_shift(a, b, u, gap) * u;
        for (Vec3& p : b)
          p += shift;
        const Polytope* pa = store.add(Polytope(std::move(a)));
        const Polytope* pb = store.add(Polytope(std::move(b)));
        c.pairs.push_back({pa, pb});
        if (hill_climbing)
          c.hc_pairs.push_back({with_hill_climbing(store, *pa), with_hill_climbing(store, *pb)});
      }
      out.push_back(std::move(c));
    }
  }
  return out;
}

std::vector<Case> scene_cases(const BenchConfig& config, ShapeStore& store, bool hill_climbing) {
  std::vector<Polytope> base, base_hc;
  for (const DemoShape& s : kDemoShapes) {
    base.push_back(s.make());
    if (hill_climbing) base_hc.push_back(climbing_copy(base.back()));
  }
  // One scene of 72 objects; the case with N objects uses its first N.
  Rng rng(config.seed * 3000017);
  std::vector<const Polytope*> objects, objects_hc;
  for (int i = 0; i < kSceneMaxObjects; ++i) {
    Vec3 centre;
    do {
      centre = Vec3(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
    } while (centre.squaredNorm() > 1);
    const Pose pose{rng.rotation(), kSceneRadius * centre};
    objects.push_back(store.add(base[i % 4].transformed(pose)));
    if (hill_climbing) objects_hc.push_back(store.add(base_hc[i % 4].transformed(pose)));
  }
  std::vector<Case> out;
  for (int n = kSceneStep; n <= kSceneMaxObjects; n += kSceneStep) {
    Case c;
    c.suite = "scene";
    c.objects = n;
    c.pair = "N=" + std::to_string(n);
    c.placement = "scene";
    c.name = std::to_string(n) + " objects";
    if (!wanted(config, c.name)) continue;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        c.pairs.push_back({objects[i], objects[j]});
        if (hill_climbing) c.hc_pairs.push_back({objects_hc[i], objects_hc[j]});
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

std::vector<Case> suite_cases(std::string_view suite, const BenchConfig& config, ShapeStore& store,
                              bool hill_climbing) {
  if (suite == "seed") return seed_cases(config, store, hill_climbing);
  if (suite == "random") return random_cases(config, store, hill_climbing);
  return scene_cases(config, store, hill_climbing);
}

}  // namespace gjklab::experiment::bench
