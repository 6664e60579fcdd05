// The benchmark run: the algorithms measured and the references their ratios are taken to,
// suite by suite (the parts it drives: bench_parts.hpp).
#include "gjklab/experiment/bench/bench.hpp"

#include <algorithm>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bench_parts.hpp"

namespace gjklab::experiment::bench {

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

std::vector<std::string> all_suites() {
  return {"seed", "random", "scene"};
}

std::string suite_list() {
  std::string list;
  for (const std::string& s : all_suites())
    list += (list.empty() ? "" : ", ") + s;
  return list;
}

namespace {

void check_bench_config(const BenchConfig& config) {
  if (config.samples < 1) throw BenchError("samples must be at least 1");
  if (config.configurations < 1) throw BenchError("configurations must be at least 1");
  if (!(config.batch_seconds >= 0)) throw BenchError("batch time must be non-negative");
  const std::vector<std::string> valid = all_suites();
  for (const std::string& s : config.suites)
    if (std::find(valid.begin(), valid.end(), s) == valid.end())
      throw BenchError("unknown suite '" + s + "'; valid suites: " + suite_list() + ", all");
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
  std::vector<Case> cases = suite_cases(suite, config, store, hc);
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

}  // namespace gjklab::experiment::bench
