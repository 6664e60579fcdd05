// Internal to src/experiment: the parts of the benchmark harness and what they share. The cases
// (bench_cases.cpp) are made from the seeded random module and the demo shapes; the measurement
// (bench_measure.cpp) times the registry's benchmark loops on them; the run (bench.cpp) picks
// the algorithms and references and takes the ratios; the reports (bench_report.cpp) print and
// write the records; the config file (bench_config.cpp) is read into a BenchConfig; a baseline
// (bench_baseline.cpp) is read from an earlier run's JSON and compared (bench_compare.cpp).
#pragma once

#include <deque>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gjklab/experiment/bench/bench.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/shapes.hpp"

namespace gjklab::experiment::bench {

// ---- cases ------------------------------------------------------------------------------------

/// Names and shapes of the classic demo, in the order of the published table.
struct DemoShape {
  const char* name;
  Polytope (*make)();
};
inline Polytope make_box() {
  return shapes::box();
}
inline Polytope make_cone() {
  return shapes::cone();
}
inline Polytope make_cylinder() {
  return shapes::cylinder();
}
inline Polytope make_sphere() {
  return shapes::uv_sphere();
}
inline constexpr DemoShape kDemoShapes[] = {
    {"box", make_box}, {"cone", make_cone}, {"cylinder", make_cylinder}, {"sphere", make_sphere}};
/// The ten pairs of the published per-pair table (indices into kDemoShapes), in its order.
inline constexpr std::pair<int, int> kSeedPairs[] = {{0, 0}, {0, 1}, {0, 2}, {0, 3}, {1, 1},
                                                     {1, 2}, {1, 3}, {3, 2}, {3, 3}, {2, 2}};

inline constexpr double kSeedOverlapDistance = 0.5;
inline constexpr double kSeedSeparatedDistance = 2.5;
inline constexpr double kRandomGap = 0.1;
inline constexpr int kRandomSizes[] = {8, 32, 128, 512, 2048, 8192};
inline constexpr int kSceneMaxObjects = 72;
inline constexpr int kSceneStep = 8;
/// Scene objects' centres are uniform in a ball of this radius: "near one point" for shapes of
/// size 1, so most pairs overlap and the rest are close.
inline constexpr double kSceneRadius = 0.5;

/// The inputs of one case: shapes (owned, stable addresses) and the pairs to query.
struct Case {
  std::string suite, name, pair, placement;
  int objects = 0;
  std::vector<BenchPair> pairs;     ///< full-scan shapes
  std::vector<BenchPair> hc_pairs;  ///< the same shapes with hill climbing
};

/// Owns every polytope of the run; deque keeps addresses stable as it grows.
struct ShapeStore {
  std::deque<Polytope> shapes;
  const Polytope* add(Polytope p) {
    shapes.push_back(std::move(p));
    return &shapes.back();
  }
};

/// The cases of one suite ("seed", "random" or "scene") that the config's filter keeps, with
/// hill-climbing copies of the shapes when asked; the shapes go to `store`.
std::vector<Case> suite_cases(std::string_view suite, const BenchConfig& config, ShapeStore& store,
                              bool hill_climbing);

// ---- measurement ------------------------------------------------------------------------------

/// One row of a case: an algorithm of the registry, possibly with hill climbing.
struct Entry {
  std::string name;  ///< as printed ("gjk-johnson+hc")
  const AlgorithmInfo* info = nullptr;
  bool hill_climbing = false;
  BenchLoop loop = nullptr;  ///< nullptr: through the registry
  /// The precision of the query (BenchConfig::precision for the queries that take one).
  ScalarPrecision precision = ScalarPrecision::double_float;
};

/// The registry's algorithm named `name` (with the "+hc" suffix for hill climbing); throws
/// BenchError naming the valid names for another.
Entry make_entry(const std::string& name);
/// Whether the registry's algorithm wraps another library.
bool is_peer(std::string_view name);

/// Times every entry on the case: interleaved samples, medians and quantiles, and each
/// full-scan row's cost floor (ratios to references are the run's).
std::vector<BenchRecord> measure_case(const Case& c, const std::vector<Entry>& entries,
                                      const BenchConfig& config, const AlgorithmOptions& options);

// ---- comparison -------------------------------------------------------------------------------

/// The comparison as the "compare" block of the JSON report.
nlohmann::ordered_json comparison_json(const BenchComparison& comparison);

}  // namespace gjklab::experiment::bench
