// `gjklab bench --compare FILE`: this run's records against a baseline's (bench_baseline.cpp
// reads it), row by row through each row's ratio to its reference within its own run. Times of
// two runs are never divided: another machine, or the same one busier, changes them all, while a
// ratio within a run moves only when one algorithm got slower or faster than the other.
#include <algorithm>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bench_parts.hpp"

namespace gjklab::experiment::bench {

namespace {

using Key = std::tuple<std::string, std::string, std::string>;  // suite, case, algorithm

Key key_of(const BenchRecord& r) {
  return {r.suite, r.case_name, r.algorithm};
}

std::optional<double> median(std::vector<double> values) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// Why two records of the same row cannot be compared; empty when they can.
std::string mismatch(const BenchRecord& now, const BenchRecord& then) {
  if (now.reference != then.reference)
    return "reference " + now.reference + " here, " + then.reference + " in the baseline";
  if (!now.ratio_to_reference) return "no ratio to " + now.reference + " in this run";
  if (!then.ratio_to_reference) return "no ratio to " + now.reference + " in the baseline";
  return {};
}

BenchComparisonRow compare_row(const BenchRecord& now, const BenchRecord& then, double threshold) {
  BenchComparisonRow row;
  row.suite = now.suite;
  row.case_name = now.case_name;
  row.algorithm = now.algorithm;
  row.reference = now.reference;
  row.ratio_now = *now.ratio_to_reference;
  row.ratio_baseline = *then.ratio_to_reference;
  // The reference's own ratio is 1 in both runs: a change of 1 would say nothing and pull the
  // median towards 1.
  if (now.algorithm != now.reference) row.change = row.ratio_now / row.ratio_baseline;
  if (now.ratio_to_floor && then.ratio_to_floor) {
    row.floor_now = now.ratio_to_floor;
    row.floor_baseline = then.ratio_to_floor;
    row.floor_change = *now.ratio_to_floor / *then.ratio_to_floor;
  }
  row.over_threshold = row.change && *row.change > threshold;
  return row;
}

/// Slowdowns first: the largest change first, then the references' own rows by their floor
/// change; equal figures in the order of the names, so that the order never depends on input.
bool slower_first(const BenchComparisonRow& a, const BenchComparisonRow& b) {
  if (a.change.has_value() != b.change.has_value()) return a.change.has_value();
  const std::optional<double> ka = a.change ? a.change : a.floor_change;
  const std::optional<double> kb = b.change ? b.change : b.floor_change;
  if (ka != kb) return ka > kb;  // an empty key (no floor) sorts last
  return std::tie(a.suite, a.case_name, a.algorithm) < std::tie(b.suite, b.case_name, b.algorithm);
}

/// The baseline's records that this run has no record of: listed when this run measured their
/// case and their algorithm (that row went missing), counted otherwise (the run measured less:
/// another --suite, --cases or --algorithms), with the algorithms it did not run named.
void add_baseline_only(const BenchReport& report, const BenchBaseline& baseline,
                       const std::set<Key>& matched, BenchComparison& c) {
  std::set<std::pair<std::string, std::string>> cases_run;
  std::set<std::string> algorithms_run;
  for (const BenchRecord& r : report.records) {
    cases_run.insert({r.suite, r.case_name});
    algorithms_run.insert(r.algorithm);
  }
  for (const BenchRecord& r : baseline.records) {
    if (matched.count(key_of(r))) continue;
    const bool algorithm_run = algorithms_run.count(r.algorithm) > 0;
    if (algorithm_run && cases_run.count({r.suite, r.case_name})) {
      c.unmatched.push_back({r.suite, r.case_name, r.algorithm, "only in the baseline"});
      continue;
    }
    ++c.baseline_records_not_run;
    auto& names = c.baseline_algorithms_not_run;
    if (!algorithm_run && std::find(names.begin(), names.end(), r.algorithm) == names.end())
      names.push_back(r.algorithm);
  }
}

/// The medians and counts of the rows `c.rows[i]` for each i in `rows`.
BenchAlgorithmChange summarize_rows(const BenchComparison& c,
                                    const std::vector<std::size_t>& rows) {
  BenchAlgorithmChange s;
  s.rows = static_cast<int>(rows.size());
  std::vector<double> changes, floor_changes;
  for (const std::size_t i : rows) {
    const BenchComparisonRow& row = c.rows[i];
    if (row.change) changes.push_back(*row.change);
    if (row.floor_change) floor_changes.push_back(*row.floor_change);
    s.over_threshold += row.over_threshold ? 1 : 0;
  }
  s.median_change = median(changes);
  s.median_floor_change = median(floor_changes);
  return s;
}

/// The summary of every row, and of each algorithm's rows.
void summarize(BenchComparison& c) {
  std::vector<std::size_t> all(c.rows.size());
  std::map<std::string, std::vector<std::size_t>> of_algorithm;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    all[i] = i;
    of_algorithm[c.rows[i].algorithm].push_back(i);
  }
  const BenchAlgorithmChange total = summarize_rows(c, all);
  c.median_change = total.median_change;
  c.median_floor_change = total.median_floor_change;
  c.over_threshold = total.over_threshold;
  c.by_algorithm.clear();
  for (const auto& [algorithm, rows] : of_algorithm) {
    c.by_algorithm.push_back(summarize_rows(c, rows));
    c.by_algorithm.back().algorithm = algorithm;
  }
  std::stable_sort(c.by_algorithm.begin(), c.by_algorithm.end(),
                   [](const BenchAlgorithmChange& a, const BenchAlgorithmChange& b) {
                     return a.median_change > b.median_change;  // empty (the reference) last
                   });
}

/// Notes on what makes this run's inputs or machine differ from the baseline's: a change can
/// then come from them rather than from the code.
std::vector<std::string> input_notes(const BenchReport& report, const BenchBaseline& baseline) {
  std::vector<std::string> notes;
  auto differs = [&](const std::string& key, const std::string& now, const std::string& what) {
    const auto it = baseline.meta.find(key);
    if (it != baseline.meta.end() && it->second != now)
      notes.push_back("the baseline's " + what + " is " + it->second + ", this run's " + now +
                      ": a change can come from that rather than from the code");
  };
  differs("configurations", std::to_string(report.config.configurations), "configurations");
  differs("seed", std::to_string(report.config.seed), "seed");
  differs("precision", std::string(to_string(report.config.precision)), "precision");
  std::map<std::string, std::string> env = bench_environment();
  differs("cpu", env["cpu"], "processor");
  differs("compiler", env["compiler"], "compiler");
  return notes;
}

}  // namespace

BenchComparison compare_to_baseline(const BenchReport& report, const BenchBaseline& baseline,
                                    double threshold) {
  BenchComparison c;
  c.baseline_path = baseline.path;
  c.baseline_meta = baseline.meta;
  c.threshold = threshold;
  std::map<Key, const BenchRecord*> then;
  for (const BenchRecord& r : baseline.records)
    then[key_of(r)] = &r;
  std::set<Key> matched;
  for (const BenchRecord& r : report.records) {
    const auto it = then.find(key_of(r));
    if (it == then.end()) {
      c.unmatched.push_back({r.suite, r.case_name, r.algorithm, "only in this run"});
      continue;
    }
    matched.insert(it->first);
    if (std::string why = mismatch(r, *it->second); !why.empty())
      c.unmatched.push_back({r.suite, r.case_name, r.algorithm, std::move(why)});
    else
      c.rows.push_back(compare_row(r, *it->second, threshold));
  }
  add_baseline_only(report, baseline, matched, c);
  std::sort(c.rows.begin(), c.rows.end(), slower_first);
  summarize(c);
  c.notes = input_notes(report, baseline);
  return c;
}

// ---- output ---------------------------------------------------------------------------------

namespace {

std::string pad(const std::string& s, std::size_t width, bool right = false) {
  if (s.size() >= width) return s;
  return right ? std::string(width - s.size(), ' ') + s : s + std::string(width - s.size(), ' ');
}

std::string fixed(const std::optional<double>& v, const char* unit = "") {
  if (!v) return "-";
  std::ostringstream o;
  o << std::fixed << std::setprecision(2) << *v << unit;
  return o.str();
}

/// Widths of the name columns: the longest name of the rows and the unmatched records.
struct Widths {
  std::size_t suite = 7, case_name = 24, algorithm = 16;
  template <class Row>
  void fit(const Row& r) {
    suite = std::max(suite, r.suite.size() + 1);
    case_name = std::max(case_name, r.case_name.size() + 1);
    algorithm = std::max(algorithm, r.algorithm.size() + 1);
  }
};

void print_header(const BenchComparison& c, std::ostream& out) {
  out << "\n== compared with " << c.baseline_path;
  const auto version = c.baseline_meta.find("gjklab"), cpu = c.baseline_meta.find("cpu");
  if (version != c.baseline_meta.end())
    out << "  (gjklab " << version->second
        << (cpu != c.baseline_meta.end() ? ", " + cpu->second : "") << ")";
  out << "\n";
}

void print_rows(const BenchComparison& c, const Widths& w, std::ostream& out) {
  out << pad("suite", w.suite) << pad("case", w.case_name) << pad("algorithm", w.algorithm)
      << pad("x ref", 8, true) << pad("baseline", 10, true) << pad("change", 8, true) << "  "
      << pad("x floor", 9, true) << pad("baseline", 10, true) << pad("change", 8, true)
      << "  reference\n";
  for (const BenchComparisonRow& r : c.rows)
    out << pad(r.suite, w.suite) << pad(r.case_name, w.case_name) << pad(r.algorithm, w.algorithm)
        << pad(fixed(r.ratio_now, "x"), 8, true) << pad(fixed(r.ratio_baseline, "x"), 10, true)
        << pad(r.change ? fixed(r.change) : "ref", 8, true) << (r.over_threshold ? " !" : "  ")
        << pad(fixed(r.floor_now, r.floor_now ? "x" : ""), 9, true)
        << pad(fixed(r.floor_baseline, r.floor_baseline ? "x" : ""), 10, true)
        << pad(fixed(r.floor_change), 8, true) << "  " << r.reference << "\n";
}

void print_by_algorithm(const BenchComparison& c, const Widths& w, std::ostream& out) {
  out << "\nper algorithm (medians over its rows):\n"
      << pad("algorithm", w.algorithm) << pad("rows", 6, true) << pad("change", 8, true)
      << pad("x floor change", 16, true) << pad("over " + fixed(c.threshold), 11, true) << "\n";
  for (const BenchAlgorithmChange& a : c.by_algorithm)
    out << pad(a.algorithm, w.algorithm) << pad(std::to_string(a.rows), 6, true)
        << pad(a.median_change ? fixed(a.median_change) : "ref", 8, true)
        << pad(fixed(a.median_floor_change), 16, true)
        << pad(std::to_string(a.over_threshold), 11, true) << "\n";
}

void print_summary(const BenchComparison& c, std::ostream& out) {
  const auto count = [&](const std::string& why) {
    return std::count_if(c.unmatched.begin(), c.unmatched.end(),
                         [&](const BenchUnmatched& u) { return u.why == why; });
  };
  const long only_now = count("only in this run"), only_baseline = count("only in the baseline");
  const long other = static_cast<long>(c.unmatched.size()) - only_now - only_baseline;
  out << "summary: " << c.rows.size() << " rows compared, median change " << fixed(c.median_change)
      << " (x floor: " << fixed(c.median_floor_change) << ")";
  if (!c.rows.empty() && c.rows.front().change) {
    const BenchComparisonRow& worst = c.rows.front();
    out << ", worst " << fixed(worst.change) << " (" << worst.suite << " " << worst.case_name
        << ", " << worst.algorithm << ")";
  }
  out << ", " << c.over_threshold << " over " << fixed(c.threshold)
      << "; not compared: " << only_now << " only in this run, " << only_baseline
      << " only in the baseline, " << other << " other";
  if (c.baseline_records_not_run > 0)
    out << "; " << c.baseline_records_not_run
        << " baseline rows of cases or algorithms this run did not measure";
  out << "\n";
  if (!c.baseline_algorithms_not_run.empty()) {
    out << "baseline algorithms not run:";
    for (const std::string& a : c.baseline_algorithms_not_run)
      out << " " << a;
    out << "\n";
  }
}

}  // namespace

void print_comparison(const BenchComparison& c, std::ostream& out) {
  Widths w;
  for (const BenchComparisonRow& r : c.rows)
    w.fit(r);
  for (const BenchUnmatched& u : c.unmatched)
    w.fit(u);
  print_header(c, out);
  print_rows(c, w, out);
  if (!c.by_algorithm.empty()) print_by_algorithm(c, w, out);
  if (!c.unmatched.empty()) {
    out << "\nnot compared:\n";
    for (const BenchUnmatched& u : c.unmatched)
      out << pad(u.suite, w.suite) << pad(u.case_name, w.case_name) << pad(u.algorithm, w.algorithm)
          << u.why << "\n";
  }
  out << "\nchange: x ref now / x ref in the baseline, each the ratio to the row's reference "
         "within its own run (1.00: as fast against the reference as in the baseline; 1.25: 25% "
         "slower against it); the same for x floor; ref: the reference's own row; !: change over "
      << fixed(c.threshold) << ".\n";
  for (const std::string& n : c.notes)
    out << "note: " << n << "\n";
  print_summary(c, out);
}

nlohmann::ordered_json comparison_json(const BenchComparison& c) {
  using Json = nlohmann::ordered_json;
  auto opt = [](const std::optional<double>& v) -> Json { return v ? Json(*v) : Json(nullptr); };
  Json rows = Json::array();
  for (const BenchComparisonRow& r : c.rows)
    rows.push_back({{"suite", r.suite},
                    {"case", r.case_name},
                    {"algorithm", r.algorithm},
                    {"reference", r.reference},
                    {"ratio_to_reference", r.ratio_now},
                    {"baseline_ratio_to_reference", r.ratio_baseline},
                    {"change", opt(r.change)},
                    {"ratio_to_floor", opt(r.floor_now)},
                    {"baseline_ratio_to_floor", opt(r.floor_baseline)},
                    {"floor_change", opt(r.floor_change)},
                    {"over_threshold", r.over_threshold}});
  Json unmatched = Json::array();
  for (const BenchUnmatched& u : c.unmatched)
    unmatched.push_back(
        {{"suite", u.suite}, {"case", u.case_name}, {"algorithm", u.algorithm}, {"why", u.why}});
  Json by_algorithm = Json::array();
  for (const BenchAlgorithmChange& a : c.by_algorithm)
    by_algorithm.push_back({{"algorithm", a.algorithm},
                            {"rows", a.rows},
                            {"median_change", opt(a.median_change)},
                            {"median_floor_change", opt(a.median_floor_change)},
                            {"over_threshold", a.over_threshold}});
  Json j;
  j["baseline"] = c.baseline_path;
  j["threshold"] = c.threshold;
  j["median_change"] = opt(c.median_change);
  j["median_floor_change"] = opt(c.median_floor_change);
  j["over_threshold"] = c.over_threshold;
  j["by_algorithm"] = std::move(by_algorithm);
  j["rows"] = std::move(rows);
  j["not_compared"] = std::move(unmatched);
  j["baseline_records_not_run"] = c.baseline_records_not_run;
  j["baseline_algorithms_not_run"] = c.baseline_algorithms_not_run;
  j["notes"] = c.notes;
  return j;
}

}  // namespace gjklab::experiment::bench
