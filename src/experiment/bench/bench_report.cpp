// The benchmark's reports: the console table, the JSON records and the Markdown seed tables with
// the config's published figures.
#include <algorithm>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "bench_parts.hpp"
#include "gjklab/build_info.hpp"

namespace gjklab::experiment::bench {

namespace {

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
  meta["precision"] = std::string(to_string(report.config.precision));
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
  if (report.comparison) doc["compare"] = comparison_json(*report.comparison);
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
  out << "Generated by `gjklab bench --config experiments/bench/seed_tables.toml --markdown "
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

}  // namespace gjklab::experiment::bench
