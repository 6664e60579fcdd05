#include "gjklab/experiment/bench.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <ctime>
#include <deque>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <ostream>
#include <random>
#include <set>
#include <sstream>

#include "gjklab/build_info.hpp"
#include "gjklab/exact/hull_adjacency.hpp"
#include "gjklab/experiment/algorithms.hpp"
#include "gjklab/experiment/seeded_random.hpp"
#include "gjklab/geometry/shapes.hpp"

namespace gjklab::experiment::bench {

namespace {

/// Timestamps for the batches: the calling thread's CPU time, which does not advance while the
/// thread waits for a core. On a shared machine that removes most of the noise of other
/// processes (what remains is their effect on caches and clocks).
struct ThreadClock {
  using time_point = double;
  static double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
};
using Clock = ThreadClock;

// ---- seeded generation ---------------------------------------------------------------------

using Rng = SeededRandom;

/// Names and shapes of the classic demo, in the order of the published table.
struct DemoShape {
  const char* name;
  Polytope (*make)();
};
Polytope make_box() {
  return shapes::box();
}
Polytope make_cone() {
  return shapes::cone();
}
Polytope make_cylinder() {
  return shapes::cylinder();
}
Polytope make_sphere() {
  return shapes::uv_sphere();
}
constexpr DemoShape kDemoShapes[] = {
    {"box", make_box}, {"cone", make_cone}, {"cylinder", make_cylinder}, {"sphere", make_sphere}};
/// The ten pairs of the published per-pair table (indices into kDemoShapes), in its order.
constexpr std::pair<int, int> kSeedPairs[] = {{0, 0}, {0, 1}, {0, 2}, {0, 3}, {1, 1},
                                              {1, 2}, {1, 3}, {3, 2}, {3, 3}, {2, 2}};

constexpr double kSeedOverlapDistance = 0.5;
constexpr double kSeedSeparatedDistance = 2.5;
constexpr double kRandomGap = 0.1;
constexpr int kRandomSizes[] = {8, 32, 128, 512, 2048, 8192};
constexpr int kSceneMaxObjects = 72;
constexpr int kSceneStep = 8;
/// Scene objects' centres are uniform in a ball of this radius: "near one point" for shapes of
/// size 1, so most pairs overlap and the rest are close.
constexpr double kSceneRadius = 0.5;

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

// ---- algorithms ------------------------------------------------------------------------------

struct Entry {
  std::string name;  ///< as printed ("gjk-johnson+hc")
  const AlgorithmInfo* info = nullptr;
  bool hill_climbing = false;
  BenchLoop loop = nullptr;  ///< nullptr: through the registry
  /// The precision of the query (BenchConfig::precision for the queries that take one).
  ScalarPrecision precision = ScalarPrecision::double_float;
};

bool is_peer(std::string_view name) {
  // Algorithms that wrap another library, as the registry says.
  const AlgorithmInfo* info = find_algorithm(name);
  return info && info->peer;
}

Entry make_entry(const std::string& name) {
  Entry e;
  e.name = name;
  std::string base = name;
  if (name.ends_with(kHillClimbingSuffix)) {
    base = name.substr(0, name.size() - std::string_view(kHillClimbingSuffix).size());
    e.hill_climbing = true;
  }
  e.info = find_algorithm(base);
  if (!e.info)
    throw BenchError("unknown algorithm '" + name + "'; valid names: " + algorithm_names() +
                     " (each optionally with the suffix " + kHillClimbingSuffix + ")");
  e.loop = find_bench_loop(base);
  return e;
}

double seconds_since(Clock::time_point start) {
  return Clock::now() - start;
}

/// A sink the optimiser cannot see through.
volatile double g_sink = 0;

BenchTally run_loop(const Entry& e, std::span<const BenchPair> pairs,
                    const AlgorithmOptions& shared_options, int repetitions) {
  AlgorithmOptions options = shared_options;  // per batch, not per query
  options.precision = e.precision;
  BenchTally t = e.loop ? e.loop(pairs, options, repetitions)
                        : run_bench_loop_via_registry(*e.info, pairs, options, repetitions);
  g_sink = g_sink + t.distance_sum + static_cast<double>(t.iterations);
  return t;
}

/// Linear interpolation between order statistics (q in [0, 1]).
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

/// The cost of one full-scan support call on a shape (ns per call), sampled in rounds of 64
/// random directions that are timed between the queries' batches (see measure_case), so that
/// the floor and the queries it is compared with see the machine in the same state.
class SupportCostSampler {
 public:
  SupportCostSampler(const Polytope& shape, double budget_seconds) : shape_(&shape) {
    dependent_reps_ = calibrated_reps(&SupportCostSampler::dependent_round, budget_seconds);
    independent_reps_ = calibrated_reps(&SupportCostSampler::independent_round, budget_seconds);
  }

  /// One timed round of each kind, each after an untimed one (as the queries' batches: the
  /// shape's data as warm as the caches allow, whatever ran before).
  void sample() {
    seconds_of(&SupportCostSampler::dependent_round, 1);
    seconds_of(&SupportCostSampler::independent_round, 1);
    dependent_ns_.push_back(ns_per_call(&SupportCostSampler::dependent_round, dependent_reps_));
    independent_ns_.push_back(
        ns_per_call(&SupportCostSampler::independent_round, independent_reps_));
  }

  /// Each call's direction chosen by the previous call's answer, as in a GJK iteration, whose
  /// next direction needs the support point just found: calls cannot overlap (latency).
  /// Median over the samples.
  double dependent_ns() const { return quantile(dependent_ns_, 0.5); }
  /// Independent calls, which the processor overlaps (throughput): a lower bound that no
  /// query whose directions depend on its support points can reach. Median over the samples.
  double independent_ns() const { return quantile(independent_ns_, 0.5); }

 private:
  static constexpr std::size_t kDirections = 64;  // a power of two: the next index is a mask
  using Round = std::size_t (SupportCostSampler::*)(int) const;

  static const std::vector<Vec3>& directions() {
    static const std::vector<Vec3> d = [] {
      Rng rng(12345);
      std::vector<Vec3> out;
      for (std::size_t i = 0; i < kDirections; ++i)
        out.push_back(rng.unit_vector());
      return out;
    }();
    return d;
  }
  std::size_t independent_round(int reps) const {
    std::size_t sum = 0;
    for (int r = 0; r < reps; ++r)
      for (const Vec3& d : directions())
        sum += shape_->scan_support_index(d);
    return sum;
  }
  std::size_t dependent_round(int reps) const {
    std::size_t last = 0;
    for (int r = 0; r < reps; ++r)
      for (std::size_t k = 0; k < kDirections; ++k)
        last = shape_->scan_support_index(directions()[(k + last) & (kDirections - 1)]);
    return last;
  }
  double seconds_of(Round round, int reps) const {
    const auto start = Clock::now();
    g_sink = g_sink + static_cast<double>((this->*round)(reps));
    return seconds_since(start);
  }
  int calibrated_reps(Round round, double budget_seconds) const {
    const double once = std::max(seconds_of(round, 1), 1e-9);
    return std::clamp(static_cast<int>(budget_seconds / once), 1, 1 << 20);
  }
  double ns_per_call(Round round, int reps) const {
    return seconds_of(round, reps) * 1e9 / (reps * static_cast<double>(kDirections));
  }

  const Polytope* shape_;
  int dependent_reps_ = 1, independent_reps_ = 1;
  std::vector<double> dependent_ns_, independent_ns_;
};

/// The distinct shapes of the full-scan rows' pairs, each with its support-cost sampler; a
/// round lasts about a tenth of a batch.
std::map<const Polytope*, SupportCostSampler> floor_samplers(const Case& c,
                                                             const BenchConfig& config) {
  std::map<const Polytope*, SupportCostSampler> out;
  for (const BenchPair& p : c.pairs)
    for (const Polytope* s : {p.a, p.b})
      if (!out.count(s)) out.emplace(s, SupportCostSampler(*s, 0.1 * config.batch_seconds));
  return out;
}

/// Each entry's pairs: the hill-climbing copies for hill-climbing rows, the plain ones else.
std::vector<std::span<const BenchPair>> entry_inputs(const Case& c,
                                                     const std::vector<Entry>& entries) {
  std::vector<std::span<const BenchPair>> inputs;
  for (const Entry& entry : entries)
    inputs.push_back(entry.hill_climbing ? std::span<const BenchPair>(c.hc_pairs)
                                         : std::span<const BenchPair>(c.pairs));
  return inputs;
}

/// The rows' identifying columns (case, algorithm, pair, placement, query count).
std::vector<BenchRecord> record_heads(const Case& c, const std::vector<Entry>& entries,
                                      const std::vector<std::span<const BenchPair>>& inputs) {
  std::vector<BenchRecord> records(entries.size());
  for (std::size_t e = 0; e < entries.size(); ++e) {
    BenchRecord& r = records[e];
    r.suite = c.suite;
    r.case_name = c.name;
    r.algorithm = entries[e].name;
    r.pair = c.pair;
    r.placement = c.placement;
    r.objects = c.objects;
    r.queries = static_cast<long long>(inputs[e].size());
    r.via_registry = entries[e].loop == nullptr;
  }
  return records;
}

/// Warm-up: one pass of each row, which also gives its tallies (the per-query means); then the
/// batch size, as many repetitions as fill config.batch_seconds.
std::vector<int> warm_up_and_calibrate(const std::vector<Entry>& entries,
                                       const std::vector<std::span<const BenchPair>>& inputs,
                                       const BenchConfig& config, const AlgorithmOptions& options,
                                       std::vector<BenchRecord>& records) {
  std::vector<int> reps(entries.size(), 1);
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const auto start = Clock::now();
    const BenchTally t = run_loop(entries[e], inputs[e], options, 1);
    const double once = std::max(seconds_since(start), 1e-9);
    reps[e] = std::clamp(static_cast<int>(config.batch_seconds / once), 1, 1 << 24);
    BenchRecord& r = records[e];
    const double q = static_cast<double>(std::max(t.queries, 1LL));
    r.iterations_mean = static_cast<double>(t.iterations) / q;
    r.support_calls_mean = static_cast<double>(t.support_calls) / q;
    r.intersect_fraction = static_cast<double>(t.intersections) / q;
    r.repetitions = reps[e];
  }
  return reps;
}

/// Support calls of each full-scan row's queries, pair by pair, for its cost floor (empty for
/// hill-climbing rows).
std::vector<std::vector<double>> support_calls_per_pair(
    const std::vector<Entry>& entries, const std::vector<std::span<const BenchPair>>& inputs,
    const AlgorithmOptions& options) {
  std::vector<std::vector<double>> calls(entries.size());
  for (std::size_t e = 0; e < entries.size(); ++e) {
    if (entries[e].hill_climbing) continue;
    for (const BenchPair& p : inputs[e]) {
      const BenchTally t = run_loop(entries[e], std::span<const BenchPair>(&p, 1), options, 1);
      calls[e].push_back(static_cast<double>(t.support_calls));
    }
  }
  return calls;
}

/// Interleaved samples, nanoseconds per query: A B C A B C … Each timed batch follows one
/// untimed pass over the same inputs, so that it starts with its data as warm as the caches
/// allow, whatever ran before it (without it, on clouds larger than the caches, the row after a
/// peer that builds its own copy of the shapes paid for that peer's evictions: up to 3× on
/// 8192-point clouds). The support-cost rounds take their turn in the same rotation.
std::vector<std::vector<double>> interleaved_samples(
    const std::vector<Entry>& entries, const std::vector<std::span<const BenchPair>>& inputs,
    const std::vector<int>& reps, const BenchConfig& config, const AlgorithmOptions& options,
    std::map<const Polytope*, SupportCostSampler>& samplers) {
  std::vector<std::vector<double>> samples(entries.size());
  for (int s = 0; s < config.samples; ++s) {
    for (std::size_t e = 0; e < entries.size(); ++e) {
      run_loop(entries[e], inputs[e], options, 1);
      const auto start = Clock::now();
      run_loop(entries[e], inputs[e], options, reps[e]);
      const double seconds = seconds_since(start);
      samples[e].push_back(seconds * 1e9 /
                           (static_cast<double>(reps[e]) * static_cast<double>(inputs[e].size())));
    }
    for (auto& [shape, sampler] : samplers)
      sampler.sample();
  }
  return samples;
}

/// Cost floor of full-scan rows: each pair's support calls times its shapes' support cost
/// (each shape's medians taken once).
void set_cost_floors(const std::vector<Entry>& entries,
                     const std::vector<std::span<const BenchPair>>& inputs,
                     const std::vector<std::vector<double>>& calls,
                     const std::map<const Polytope*, SupportCostSampler>& samplers,
                     std::vector<BenchRecord>& records) {
  struct SupportCost {
    double dependent_ns, independent_ns;
  };
  std::map<const Polytope*, SupportCost> costs;
  for (const auto& [shape, sampler] : samplers)
    costs[shape] = {sampler.dependent_ns(), sampler.independent_ns()};
  for (std::size_t e = 0; e < entries.size(); ++e) {
    if (entries[e].hill_climbing) continue;
    double floor = 0, floor_independent = 0;
    for (std::size_t k = 0; k < inputs[e].size(); ++k) {
      const SupportCost& a = costs.at(inputs[e][k].a);
      const SupportCost& b = costs.at(inputs[e][k].b);
      floor += calls[e][k] * (a.dependent_ns + b.dependent_ns);
      floor_independent += calls[e][k] * (a.independent_ns + b.independent_ns);
    }
    const auto queries = static_cast<double>(std::max<std::size_t>(inputs[e].size(), 1));
    records[e].floor_ns = floor / queries;
    records[e].floor_independent_ns = floor_independent / queries;
  }
}

/// The time columns: quantiles of the samples and their ratios to the floors.
void set_time_quantiles(const std::vector<std::vector<double>>& samples,
                        std::vector<BenchRecord>& records) {
  for (std::size_t e = 0; e < records.size(); ++e) {
    BenchRecord& r = records[e];
    r.ns_median = quantile(samples[e], 0.5);
    r.ns_p10 = quantile(samples[e], 0.1);
    r.ns_p90 = quantile(samples[e], 0.9);
    if (r.floor_ns) r.ratio_to_floor = r.ns_median / *r.floor_ns;
    if (r.floor_independent_ns)
      r.ratio_to_floor_independent = r.ns_median / *r.floor_independent_ns;
  }
}

std::vector<BenchRecord> measure_case(const Case& c, const std::vector<Entry>& entries,
                                      const BenchConfig& config, const AlgorithmOptions& options) {
  const auto inputs = entry_inputs(c, entries);
  std::vector<BenchRecord> records = record_heads(c, entries, inputs);
  const std::vector<int> reps = warm_up_and_calibrate(entries, inputs, config, options, records);
  for (std::size_t e = 0; e < entries.size(); ++e)
    run_loop(entries[e], inputs[e], options, reps[e]);

  const auto calls = support_calls_per_pair(entries, inputs, options);
  const bool any_full_scan =
      std::any_of(entries.begin(), entries.end(), [](const Entry& e) { return !e.hill_climbing; });
  std::map<const Polytope*, SupportCostSampler> samplers;
  if (any_full_scan) samplers = floor_samplers(c, config);

  const auto samples = interleaved_samples(entries, inputs, reps, config, options, samplers);
  set_cost_floors(entries, inputs, calls, samplers, records);
  set_time_quantiles(samples, records);
  return records;
}

std::string pad(const std::string& s, std::size_t width, bool right = false) {
  if (s.size() >= width) return s;
  return right ? std::string(width - s.size(), ' ') + s : s + std::string(width - s.size(), ' ');
}

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

/// Time with a unit that keeps three significant digits or so.
std::string format_ns(double ns) {
  if (ns < 10) return fixed(ns, 2) + " ns";
  if (ns < 1000) return fixed(ns, 1) + " ns";
  if (ns < 1e6) return fixed(ns / 1e3, ns < 1e4 ? 2 : 1) + " us";
  return fixed(ns / 1e6, 2) + " ms";
}

std::string format_ratio(const std::optional<double>& r) {
  return r ? fixed(*r, 2) + "x" : "-";
}

}  // namespace

// ---- the run --------------------------------------------------------------------------------

void set_case_ratios(std::vector<BenchRecord>& rows, std::span<const RatioRole> roles,
                     const References& references) {
  auto median_of = [&](const std::string& n) -> std::optional<double> {
    for (const BenchRecord& r : rows)
      if (r.algorithm == n) return r.ns_median;
    return std::nullopt;
  };
  std::string fastest_peer;
  for (const std::string& n : references.peer_distances)
    if (auto t = median_of(n); t && (fastest_peer.empty() || *t < *median_of(fastest_peer)))
      fastest_peer = n;
  for (std::size_t e = 0; e < rows.size(); ++e) {
    BenchRecord& r = rows[e];
    std::string ref = references.fixed;
    if (ref.empty())
      ref = roles[e].kind == AnswerKind::boolean ? references.boolean_reference
            : references.peer_distances.empty()  ? references.distance_reference
                                                 : fastest_peer;
    r.reference = ref;
    if (auto t = median_of(ref)) r.ratio_to_reference = r.ns_median / *t;
    if (roles[e].full_scan)
      if (auto t = median_of(*roles[e].full_scan)) r.ratio_to_full_scan = r.ns_median / *t;
  }
}

namespace {

void check_bench_config(const BenchConfig& config) {
  if (config.samples < 1) throw BenchError("samples must be at least 1");
  if (config.configurations < 1) throw BenchError("configurations must be at least 1");
  if (!(config.batch_seconds >= 0)) throw BenchError("batch time must be non-negative");
  for (const std::string& s : config.suites)
    if (s != "seed" && s != "random" && s != "scene")
      throw BenchError("unknown suite '" + s + "'; valid suites: seed, random, scene, all");
}

bool has_entry(const std::vector<Entry>& entries, const std::string& name) {
  return std::any_of(entries.begin(), entries.end(),
                     [&](const Entry& e) { return e.name == name; });
}

/// The algorithms measured: the requested ones, or every boolean and distance algorithm but
/// sat, whose cost grows with the cube of the vertex count (hours on the random suite's largest
/// clouds; it runs when named).
std::vector<Entry> requested_entries(const BenchConfig& config) {
  std::vector<std::string> names = config.algorithms;
  if (names.empty())
    for (const AlgorithmInfo& a : algorithms())
      if (a.kind != AnswerKind::exact && a.name != "sat") names.emplace_back(a.name);
  std::vector<Entry> entries;
  for (const std::string& n : names)
    entries.push_back(make_entry(n));
  return entries;
}

/// Adds the reference algorithms the ratios are taken to, and says which they are in the
/// report; returns the peer distance queries whose fastest is the distance reference.
std::vector<std::string> add_references(const BenchConfig& config, std::vector<Entry>& entries,
                                        BenchReport& report) {
  auto add = [&](const std::string& n) {
    if (!has_entry(entries, n)) entries.push_back(make_entry(n));
  };
  auto any_of_kind = [&](AnswerKind kind) {
    return std::any_of(entries.begin(), entries.end(),
                       [&](const Entry& e) { return e.info->kind == kind; });
  };
  const bool any_boolean = any_of_kind(AnswerKind::boolean);
  const bool any_distance = any_of_kind(AnswerKind::distance) || config.algorithms.empty();
  std::vector<std::string> peer_distances;
  if (!config.reference.empty()) {
    make_entry(config.reference);  // validates
    add(config.reference);
    report.boolean_reference = report.distance_reference = config.reference;
    return peer_distances;
  }
  if (any_boolean && find_algorithm("libccd-mpr")) {
    report.boolean_reference = "libccd-mpr";
    add("libccd-mpr");
  }
  if (any_distance)
    for (const AlgorithmInfo& a : algorithms())
      if (a.kind == AnswerKind::distance && is_peer(a.name)) peer_distances.emplace_back(a.name);
  if (!any_distance) {
    // no distance algorithm: no distance reference
  } else if (!peer_distances.empty()) {
    for (const std::string& n : peer_distances)
      add(n);
    report.distance_reference = "fastest peer distance";
    std::string list;
    for (const std::string& n : peer_distances)
      list += (list.empty() ? "" : ", ") + n;
    report.notes.push_back(
        "distance algorithms: ratios to the fastest peer distance query in "
        "each case (of " +
        list + ")");
  } else if (find_algorithm("libccd-gjk")) {
    report.distance_reference = "libccd-gjk";
    add("libccd-gjk");
    report.notes.push_back(
        "no peer distance query is installed (libccd 2.1 has none): distance algorithms are "
        "compared with libccd-gjk's boolean intersection test, a query that answers less");
  }
  if (!report.boolean_reference.empty())
    report.notes.push_back("boolean algorithms: ratios to " + report.boolean_reference);
  return peer_distances;
}

/// Runs the GJK queries in the configured precision, when it is not double.
void apply_precision(const BenchConfig& config, std::vector<Entry>& entries, BenchReport& report) {
  if (config.precision == ScalarPrecision::double_float) return;
  for (Entry& e : entries) {
    if (!takes_precision(*e.info)) continue;
    if (e.hill_climbing)
      throw BenchError(e.name + ": hill climbing runs in double only, not in " +
                       std::string(to_string(config.precision)));
    e.precision = config.precision;
  }
  report.notes.push_back("GJK queries (gjk-bool, the distance variants, epa) in " +
                         std::string(to_string(config.precision)) +
                         ", on inputs rounded before the timed loop; peers in double");
}

/// Measures every case of one suite and appends its rows, with their ratios, to the report.
void run_suite(const std::string& suite, std::vector<Entry> suite_entries,
               const BenchConfig& config, const std::vector<std::string>& peer_distances,
               ShapeStore& store, BenchReport& report, std::ostream* progress) {
  AlgorithmOptions options;
  const bool hc = std::any_of(suite_entries.begin(), suite_entries.end(),
                              [](const Entry& e) { return e.hill_climbing; });
  std::vector<Case> cases = suite == "seed"     ? seed_cases(config, store, hc)
                            : suite == "random" ? random_cases(config, store, hc)
                                                : scene_cases(config, store, hc);
  std::vector<RatioRole> roles;
  for (const Entry& e : suite_entries)
    roles.push_back(
        {e.info->kind, e.hill_climbing ? std::optional<std::string>(e.info->name) : std::nullopt});
  for (const Case& c : cases) {
    if (progress) *progress << "bench: " << suite << " / " << c.name << "\n" << std::flush;
    std::vector<BenchRecord> rows = measure_case(c, suite_entries, config, options);
    set_case_ratios(
        rows, roles,
        {config.reference, report.boolean_reference, report.distance_reference, peer_distances});
    for (BenchRecord& r : rows)
      report.records.push_back(std::move(r));
  }
}

}  // namespace

BenchReport run_bench(const BenchConfig& config, std::ostream* progress) {
  check_bench_config(config);
  BenchReport report;
  report.config = config;
  const bool default_list = config.algorithms.empty();
  std::vector<Entry> entries = requested_entries(config);
  const std::vector<std::string> peer_distances = add_references(config, entries, report);
  apply_precision(config, entries, report);
  const bool other_precision = config.precision != ScalarPrecision::double_float;
  for (const Entry& e : entries)
    if (e.loop == nullptr)
      report.notes.push_back(e.name +
                             " has no direct benchmark loop and is timed through the "
                             "registry's run() (includes building its Outcome)");
  ShapeStore store;
  for (const std::string& suite : config.suites) {
    std::vector<Entry> suite_entries = entries;
    // Default list: the random suite also measures hill climbing on the GJK queries.
    if (default_list && suite == "random" && !other_precision)
      for (const char* n : {"gjk-bool+hc", "gjk-johnson+hc"})
        if (!has_entry(entries, n)) suite_entries.push_back(make_entry(n));
    run_suite(suite, std::move(suite_entries), config, peer_distances, store, report, progress);
  }
  return report;
}

// ---- output ---------------------------------------------------------------------------------

void print_table(const BenchReport& report, std::ostream& out) {
  // The name columns widen to the longest name (plus a space), so that long names such as
  // gjk-johnson-backup keep the columns after them aligned.
  std::size_t case_width = 28, algorithm_width = 16;
  for (const BenchRecord& r : report.records) {
    case_width = std::max(case_width, r.case_name.size() + 1);
    algorithm_width = std::max(algorithm_width, r.algorithm.size() + (r.via_registry ? 2 : 1));
  }
  std::string suite;
  for (const BenchRecord& r : report.records) {
    if (r.suite != suite) {
      suite = r.suite;
      const bool scene = suite == "scene";
      out << "\n== " << suite
          << (scene ? "  (time per full pass over all pairs)" : "  (time per query)") << "\n";
      out << pad("case", case_width) << pad("algorithm", algorithm_width) << pad("median", 11, true)
          << pad("p10", 11, true) << pad("p90", 11, true) << pad("iters", 7, true)
          << pad("supports", 9, true) << pad("x ref", 8, true) << pad("x floor", 8, true)
          << pad("x scan", 8, true) << "  reference\n";
    }
    const double scale = r.suite == "scene" ? static_cast<double>(r.queries) : 1.0;
    out << pad(r.case_name, case_width)
        << pad(r.algorithm + (r.via_registry ? "*" : ""), algorithm_width)
        << pad(format_ns(r.ns_median * scale), 11, true)
        << pad(format_ns(r.ns_p10 * scale), 11, true) << pad(format_ns(r.ns_p90 * scale), 11, true)
        << pad(fixed(r.iterations_mean, 1), 7, true) << pad(fixed(r.support_calls_mean, 1), 9, true)
        << pad(format_ratio(r.ratio_to_reference), 8, true)
        << pad(format_ratio(r.ratio_to_floor), 8, true)
        << pad(format_ratio(r.ratio_to_full_scan), 8, true) << "  " << r.reference << "\n";
  }
  out << "\n";
  out << "x ref: median time / the reference's median in the same case; x floor: median / "
         "(support calls x full-scan support cost of both shapes, each call waiting for the one "
         "before, as in GJK; the floor with overlapping calls is in the JSON); x scan: hill "
         "climbing / the same algorithm's full scan.\n";
  for (const std::string& n : report.notes)
    out << "note: " << n << "\n";
}

void write_json(const BenchReport& report, std::ostream& out) {
  using Json = nlohmann::ordered_json;
  Json meta;
  for (const auto& [k, v] : bench_environment())
    meta[k] = v;
  meta["samples"] = report.config.samples;
  meta["batch_seconds"] = report.config.batch_seconds;
  meta["configurations"] = report.config.configurations;
  meta["seed"] = report.config.seed;
  meta["boolean_reference"] = report.boolean_reference;
  meta["distance_reference"] = report.distance_reference;
  meta["notes"] = report.notes;
  Json records = Json::array();
  auto opt = [](const std::optional<double>& v) -> Json { return v ? Json(*v) : Json(nullptr); };
  for (const BenchRecord& r : report.records) {
    Json j;
    j["suite"] = r.suite;
    j["case"] = r.case_name;
    j["algorithm"] = r.algorithm;
    j["ns_median"] = r.ns_median;
    j["ns_p10"] = r.ns_p10;
    j["ns_p90"] = r.ns_p90;
    j["iterations_mean"] = r.iterations_mean;
    j["support_calls_mean"] = r.support_calls_mean;
    j["reference"] = r.reference;
    j["ratio_to_reference"] = opt(r.ratio_to_reference);
    j["floor_ns"] = opt(r.floor_ns);
    j["ratio_to_floor"] = opt(r.ratio_to_floor);
    j["floor_independent_ns"] = opt(r.floor_independent_ns);
    j["ratio_to_floor_independent"] = opt(r.ratio_to_floor_independent);
    j["ratio_to_full_scan"] = opt(r.ratio_to_full_scan);
    j["intersect_fraction"] = r.intersect_fraction;
    j["queries_per_pass"] = r.queries;
    if (r.suite == "scene") {
      j["objects"] = r.objects;
      j["pass_ms_median"] = r.ns_median * static_cast<double>(r.queries) / 1e6;
      j["pass_ms_p10"] = r.ns_p10 * static_cast<double>(r.queries) / 1e6;
      j["pass_ms_p90"] = r.ns_p90 * static_cast<double>(r.queries) / 1e6;
    }
    j["repetitions"] = r.repetitions;
    j["timed_via"] = r.via_registry ? "registry" : "direct";
    records.push_back(std::move(j));
  }
  Json doc;
  doc["meta"] = std::move(meta);
  doc["records"] = std::move(records);
  out << doc.dump(1) << "\n";
}

namespace {

/// The record of this suite, case and algorithm, or nullptr.
const BenchRecord* find_record(const BenchReport& report, const std::string& suite,
                               const std::string& case_name, const std::string& algorithm) {
  for (const BenchRecord& r : report.records)
    if (r.suite == suite && r.case_name == case_name && r.algorithm == algorithm) return &r;
  return nullptr;
}

/// The report's algorithms in order of first appearance.
std::vector<std::string> algorithms_in_order(const BenchReport& report) {
  std::vector<std::string> algs;
  for (const BenchRecord& r : report.records)
    if (std::find(algs.begin(), algs.end(), r.algorithm) == algs.end()) algs.push_back(r.algorithm);
  return algs;
}

bool has_suite(const BenchReport& report, std::string_view suite) {
  return std::any_of(report.records.begin(), report.records.end(),
                     [&](const BenchRecord& r) { return r.suite == suite; });
}

/// A table's head: the leading columns, one right-aligned column per algorithm, the speed-up.
void write_table_head(std::ostream& out, std::string_view leading, std::string_view leading_rule,
                      const std::vector<std::string>& algs, std::string_view speed_up) {
  out << leading;
  for (const std::string& a : algs)
    out << " " << a << " |";
  out << " " << speed_up << " |\n" << leading_rule;
  for (std::size_t i = 0; i < algs.size(); ++i)
    out << "---:|";
  out << "---:|\n";
}

/// The title, the environment and the sampling of the seed tables.
void write_seed_tables_preamble(const BenchConfig& cfg, std::ostream& out) {
  out << "# Seed tables: the classic demo's timings, reproduced\n\n";
  out << "Generated by `gjklab bench --config experiments/seed_tables.toml --markdown "
         "results/seed_tables.md`.\n";
  if (!cfg.published_source.empty()) out << "Published figures: " << cfg.published_source << "\n";
  out << "\n| | |\n|---|---|\n";
  for (const auto& [k, v] : bench_environment())
    out << "| " << k << " | " << v << " |\n";
  out << "| samples x configurations | " << cfg.samples << " x " << cfg.configurations << " |\n";
}

/// The per-pair table: µs per query of each algorithm, overlapping / separated, beside the
/// published figure.
void write_per_pair_table(const BenchReport& report, const std::vector<std::string>& algs,
                          std::ostream& out) {
  const BenchConfig& cfg = report.config;
  out << "\n## Per pair (µs per query, median of " << cfg.samples
      << " interleaved samples; each cell: overlapping / separated)\n\n";
  write_table_head(out, "| pair | published |", "|---|---:|", algs,
                   "speed-up of gjk-johnson (mean of both placements)");
  for (const auto& [ia, ib] : kSeedPairs) {
    const std::string pair = std::string(kDemoShapes[ia].name) + "-" + kDemoShapes[ib].name;
    const std::string overlap = pair + " overlap", separated = pair + " separated";
    if (!find_record(report, "seed", overlap, algs[0]) &&
        !find_record(report, "seed", separated, algs[0]))
      continue;
    const auto pub = cfg.published_pair_us.find(pair);
    out << "| " << pair << " | "
        << (pub != cfg.published_pair_us.end() ? fixed(pub->second, 1) : "-") << " |";
    for (const std::string& a : algs) {
      const BenchRecord* o = find_record(report, "seed", overlap, a);
      const BenchRecord* s = find_record(report, "seed", separated, a);
      out << " " << (o ? fixed(o->ns_median / 1e3, 3) : "-") << " / "
          << (s ? fixed(s->ns_median / 1e3, 3) : "-") << " |";
    }
    const BenchRecord* o = find_record(report, "seed", overlap, "gjk-johnson");
    const BenchRecord* s = find_record(report, "seed", separated, "gjk-johnson");
    if (pub != cfg.published_pair_us.end() && o && s)
      out << " " << fixed(pub->second * 1e3 / (0.5 * (o->ns_median + s->ns_median)), 0) << "x |\n";
    else
      out << " - |\n";
  }
}

/// The scene table: ms per pass over all pairs of N objects, beside the published figure.
void write_scene_table(const BenchReport& report, const std::vector<std::string>& algs,
                       std::ostream& out) {
  const BenchConfig& cfg = report.config;
  out << "\n## All pairs of N objects (ms per full pass, median of " << cfg.samples
      << " samples)\n\n";
  write_table_head(out, "| objects | pairs | published |", "|---:|---:|---:|", algs,
                   "speed-up of gjk-johnson");
  for (int n = kSceneStep; n <= kSceneMaxObjects; n += kSceneStep) {
    const std::string name = std::to_string(n) + " objects";
    const BenchRecord* any = find_record(report, "scene", name, algs[0]);
    if (!any) continue;
    const auto pub = cfg.published_scene_ms.find(n);
    out << "| " << n << " | " << any->queries << " | "
        << (pub != cfg.published_scene_ms.end() ? fixed(pub->second, 1) : "-") << " |";
    for (const std::string& a : algs) {
      const BenchRecord* r = find_record(report, "scene", name, a);
      out << " " << (r ? fixed(r->ns_median * static_cast<double>(r->queries) / 1e6, 3) : "-")
          << " |";
    }
    const BenchRecord* j = find_record(report, "scene", name, "gjk-johnson");
    if (pub != cfg.published_scene_ms.end() && j)
      out << " " << fixed(pub->second * 1e6 / (j->ns_median * static_cast<double>(j->queries)), 0)
          << "x |\n";
    else
      out << " - |\n";
  }
}

}  // namespace

void write_seed_tables_markdown(const BenchReport& report, std::ostream& out) {
  write_seed_tables_preamble(report.config, out);
  const std::vector<std::string> algs = algorithms_in_order(report);
  if (has_suite(report, "seed")) write_per_pair_table(report, algs, out);
  if (has_suite(report, "scene")) write_scene_table(report, algs, out);
  if (!report.notes.empty()) {
    out << "\n";
    for (const std::string& n : report.notes)
      out << "- " << n << "\n";
  }
}

// ---- config file ----------------------------------------------------------------------------

namespace {

/// A parsed bench configuration file and its typed readers. Every value is checked for its
/// type and range (the command line's ranges): a value of the wrong type is an error, never
/// ignored, and no value is narrowed.
class BenchFile {
 public:
  explicit BenchFile(const std::string& path) : path_(path) {
    try {
      table_ = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
      std::ostringstream msg;
      msg << path << ":" << e.source().begin.line << ": " << e.description();
      throw BenchError(msg.str());
    }
  }

  const toml::table& table() const { return table_; }

  [[noreturn]] void fail(const std::string& what) const { throw BenchError(path_ + ": " + what); }

  void allow_only(const std::set<std::string>& known) const {
    for (const auto& [key, node] : table_) {
      (void)node;
      if (!known.count(std::string(key.str())))
        fail("unknown key '" + std::string(key.str()) + "'");
    }
  }

  void strings(const char* key, std::vector<std::string>& out) const {
    if (const toml::node* n = table_.get(key)) {
      const toml::array* a = n->as_array();
      if (!a) fail(std::string(key) + " must be an array of strings");
      out.clear();
      for (const toml::node& e : *a) {
        if (!e.is_string()) fail(std::string(key) + " must be an array of strings");
        out.push_back(e.as_string()->get());
      }
    }
  }

  void text(const char* key, std::string& out) const {
    if (const toml::node* n = table_.get(key)) {
      if (!n->is_string()) fail(std::string(key) + " must be a string");
      out = n->as_string()->get();
    }
  }

  std::optional<std::int64_t> integer(const char* key, std::int64_t lo, std::int64_t hi) const {
    const toml::node* n = table_.get(key);
    if (!n) return std::nullopt;
    if (!n->is_integer() || n->as_integer()->get() < lo || n->as_integer()->get() > hi)
      fail(std::string(key) + " must be an integer in [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    return n->as_integer()->get();
  }

 private:
  std::string path_;
  toml::table table_;
};

/// `precision`, `samples`, `configurations`, `seed` and `batch_seconds`.
void read_measurement(const BenchFile& f, BenchConfig& c) {
  std::string precision;
  f.text("precision", precision);
  if (!precision.empty()) {
    const auto p = precision_from_string(precision);
    if (!p) f.fail("precision must be \"float\", \"double\" or \"long double\"");
    c.precision = *p;
  }
  if (auto v = f.integer("samples", 1, 100000)) c.samples = static_cast<int>(*v);
  if (auto v = f.integer("configurations", 1, 100000)) c.configurations = static_cast<int>(*v);
  if (auto v = f.integer("seed", 0, std::numeric_limits<std::int64_t>::max()))
    c.seed = static_cast<std::uint64_t>(*v);
  if (const toml::node* n = f.table().get("batch_seconds")) {
    const auto v = n->value<double>();  // integers convert exactly
    if (!v || !(*v >= 0 && *v <= 10)) f.fail("batch_seconds must be a number in [0, 10]");
    c.batch_seconds = *v;
  }
}

/// One published time (µs per pair or ms per scene): a finite number >= 0. TOML reads `inf`
/// and `nan` as numbers, and the tables print the figure and its ratio to the measured time.
double published_time(const BenchFile& f, const toml::node& v, const std::string& key) {
  const auto x = v.value<double>();  // integers convert exactly
  if (!x || !std::isfinite(*x) || *x < 0) f.fail(key + " must be a finite number >= 0");
  return *x;
}

/// [published]: the figures the seed tables are compared with (µs per pair, ms per scene).
void read_published(const BenchFile& f, const toml::table& pub, BenchConfig& c) {
  if (auto v = pub["source"].value<std::string>()) c.published_source = *v;
  if (const toml::table* pairs = pub["pair_us"].as_table())
    for (const auto& [k, v] : *pairs)
      c.published_pair_us[std::string(k.str())] =
          published_time(f, v, "published.pair_us." + std::string(k.str()));
  if (const toml::table* scene = pub["scene_ms"].as_table())
    for (const auto& [k, v] : *scene) {
      const double x = published_time(f, v, "published.scene_ms." + std::string(k.str()));
      int objects = 0;
      const std::string_view name = k.str();
      const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), objects);
      if (ec != std::errc() || end != name.data() + name.size() || objects < 1)
        f.fail("published.scene_ms: key '" + std::string(name) +
               "' must be an object count (an integer >= 1)");
      c.published_scene_ms[objects] = x;
    }
}

}  // namespace

BenchConfig load_bench_config(const std::string& path) {
  const BenchFile f(path);
  BenchConfig c;
  f.strings("suites", c.suites);
  // An empty list would measure nothing and still exit 0.
  if (c.suites.empty()) f.fail("suites must name at least one suite (seed, random, scene)");
  f.strings("algorithms", c.algorithms);
  f.allow_only({"suites", "algorithms", "reference", "samples", "batch_seconds", "configurations",
                "seed", "cases", "published", "description", "precision"});
  f.text("reference", c.reference);
  f.text("cases", c.case_filter);
  read_measurement(f, c);
  if (const toml::table* pub = f.table()["published"].as_table()) read_published(f, *pub, c);
  return c;
}

std::map<std::string, std::string> bench_environment() {
  std::map<std::string, std::string> env;
  env["gjklab"] = std::string(build_info::version) + " (" + build_info::git_commit + ")";
  env["compiler"] = std::string(build_info::compiler) + " " + build_info::cxx_flags;
  std::string cpu = "unknown";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  env["cpu"] = cpu;
  return env;
}

}  // namespace gjklab::experiment::bench
