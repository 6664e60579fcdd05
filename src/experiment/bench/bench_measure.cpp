// The benchmark's measurement: calibrated batches of the registry's benchmark loops, timed in
// the thread's CPU time and interleaved across the algorithms of a case, and each full-scan
// row's cost floor from the support calls its queries make.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "bench_parts.hpp"
#include "gjklab/experiment/cases/seeded_random.hpp"

namespace gjklab::experiment::bench {

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

namespace {

using Rng = SeededRandom;

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

}  // namespace

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

}  // namespace gjklab::experiment::bench
