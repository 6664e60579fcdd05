#include "gjklab/experiment/run/summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace gjklab::experiment {

namespace {

/// The q-quantile (0 ≤ q ≤ 1) by the nearest-rank method; 0 for an empty sample.
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  const std::size_t index = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

std::string format(const char* fmt, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, value);
  return buf;
}

}  // namespace

SummaryBuilder::SummaryBuilder(std::vector<std::string> algorithm_names) {
  for (std::string& name : algorithm_names) {
    Column c;
    c.counts.name = std::move(name);
    columns_.push_back(std::move(c));
  }
}

void SummaryBuilder::add(const CaseResult& result) {
  ++cases_;
  if (result.exact) ++contact_[static_cast<std::size_t>(result.exact->contact)];
  for (std::size_t i = 0; i < columns_.size() && i < result.algorithms.size(); ++i) {
    const AlgorithmRecord& r = result.algorithms[i];
    Column& c = columns_[i];
    ++c.counts.cases;
    if (!r.boolean_correct) ++c.counts.wrong_booleans;
    if (!std::isnan(r.rel_error)) c.rel_errors.push_back(r.rel_error);
    if (!std::isnan(r.depth_rel_error)) c.depth_errors.push_back(r.depth_rel_error);
    if (!std::isnan(r.time_ns)) c.times.push_back(r.time_ns);
    ++c.counts.terminations[static_cast<std::size_t>(r.termination)];
    ++c.counts.failures[static_cast<std::size_t>(r.failure)];
    c.iteration_sum += r.iterations;
    c.counts.iterations_max = std::max(c.counts.iterations_max, r.iterations);
  }
}

RunSummary SummaryBuilder::build() const {
  RunSummary s;
  s.cases = cases_;
  s.contact = contact_;
  for (const Column& c : columns_) {
    AlgorithmSummary a = c.counts;
    a.distances = c.rel_errors.size();
    a.rel_error_median = quantile(c.rel_errors, 0.5);
    a.rel_error_p99 = quantile(c.rel_errors, 0.99);
    a.rel_error_max =
        c.rel_errors.empty() ? 0 : *std::max_element(c.rel_errors.begin(), c.rel_errors.end());
    a.depths = c.depth_errors.size();
    a.depth_error_median = quantile(c.depth_errors, 0.5);
    a.depth_error_max = c.depth_errors.empty()
                            ? 0
                            : *std::max_element(c.depth_errors.begin(), c.depth_errors.end());
    a.iterations_mean = a.cases ? c.iteration_sum / static_cast<double>(a.cases) : 0;
    a.timed = c.times.size();
    a.time_ns_median = quantile(c.times, 0.5);
    s.algorithms.push_back(std::move(a));
  }
  return s;
}

namespace {

/// The summary table's row of one algorithm.
std::vector<std::string> summary_cells(const AlgorithmSummary& a) {
  auto error = [&](double e) { return a.distances > 0 ? format("%.2e", e) : std::string("-"); };
  return {a.name,
          std::to_string(a.cases),
          std::to_string(a.wrong_booleans),
          error(a.rel_error_median),
          error(a.rel_error_p99),
          error(a.rel_error_max),
          format("%.2f", a.iterations_mean),
          std::to_string(a.iterations_max),
          a.timed ? format("%.0f", a.time_ns_median) : std::string("-")};
}

void print_terminations(std::ostream& out, const RunSummary& s) {
  out << "\nterminations:\n";
  for (const AlgorithmSummary& a : s.algorithms) {
    out << "  " << a.name << ":";
    for (Termination t : kAllTerminations) {
      const auto n = a.terminations[static_cast<std::size_t>(t)];
      if (n > 0) out << " " << to_string(t) << "=" << n;
    }
    out << "\n";
  }
}

void print_depth_errors(std::ostream& out, const RunSummary& s) {
  const bool any_depth = std::any_of(s.algorithms.begin(), s.algorithms.end(),
                                     [](const AlgorithmSummary& a) { return a.depths > 0; });
  if (!any_depth) return;
  out << "penetration depth error / size (intersecting pairs, against the exact depth):\n";
  for (const AlgorithmSummary& a : s.algorithms)
    if (a.depths > 0)
      out << "  " << a.name << ": " << a.depths << " pairs, median "
          << format("%.2e", a.depth_error_median) << ", max " << format("%.2e", a.depth_error_max)
          << "\n";
}

void print_failure_classes(std::ostream& out, const RunSummary& s) {
  out << "failure classes (other than none):\n";
  for (const AlgorithmSummary& a : s.algorithms) {
    out << "  " << a.name << ":";
    bool any = false;
    for (std::size_t f = 1; f < a.failures.size(); ++f) {
      if (a.failures[f] == 0) continue;
      out << " " << to_string(static_cast<FailureClass>(f)) << "=" << a.failures[f];
      any = true;
    }
    out << (any ? "\n" : " -\n");
  }
}

}  // namespace

Table summary_table(const RunSummary& s) {
  // The widths the text form has always had; the name column grows with the longest name.
  Table t;
  t.columns = {{"algorithm", false, 14}, {"cases", true, 8},    {"wrong", true, 8},
               {"err_med", true, 10},    {"err_p99", true, 10}, {"err_max", true, 10},
               {"it_mean", true, 8},     {"it_max", true, 6},   {"ns/query", true, 10}};
  for (const AlgorithmSummary& a : s.algorithms)
    t.rows.push_back({summary_cells(a)});
  return t;
}

void print_summary(std::ostream& out, const RunSummary& s) {
  out << s.cases << " cases";
  if (s.contact[0] + s.contact[1] + s.contact[2] > 0) {
    out << " (exact: " << s.contact[0] << " separated, " << s.contact[1] << " touching band, "
        << s.contact[2] << " intersecting)";
  }
  out << "\n\n";
  render_text(out, summary_table(s));
  print_terminations(out, s);
  print_depth_errors(out, s);
  print_failure_classes(out, s);
  out << "(errors are |distance − exact| / size, size = larger bounding-box diagonal; "
         "wrong = boolean differs from the exact one outside the touching band)\n";
}

FamilySummaryBuilder::FamilySummaryBuilder(std::vector<std::string> family_names,
                                           std::vector<std::string> algorithm_names)
    : family_names_(std::move(family_names)) {
  builders_.assign(family_names_.size(), SummaryBuilder(algorithm_names));
}

void FamilySummaryBuilder::add(const CaseResult& result) {
  if (result.record.family < builders_.size()) builders_[result.record.family].add(result);
}

std::vector<std::pair<std::string, RunSummary>> FamilySummaryBuilder::build() const {
  std::vector<std::pair<std::string, RunSummary>> out;
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    RunSummary s = builders_[i].build();
    if (s.cases > 0) out.emplace_back(family_names_[i], std::move(s));
  }
  return out;
}

namespace {

/// "step_limit=3 no_progress=1": the terminations other than converged, or "-".
std::string stops_text(const AlgorithmSummary& a) {
  std::string stops;
  for (Termination t : kAllTerminations) {
    const auto n = a.terminations[static_cast<std::size_t>(t)];
    if (t != Termination::converged && n > 0)
      stops += std::string(stops.empty() ? "" : " ") + std::string(to_string(t)) + "=" +
               std::to_string(n);
  }
  return stops.empty() ? "-" : stops;
}

std::vector<std::string> family_cells(const std::string& family, const AlgorithmSummary& a) {
  return {family,
          a.name,
          std::to_string(a.cases),
          std::to_string(a.wrong_booleans),
          a.distances ? format("%.2e", a.rel_error_max) : std::string("-"),
          stops_text(a)};
}

}  // namespace

Table family_table(const std::vector<std::pair<std::string, RunSummary>>& families) {
  Table t;
  t.columns = {{"family", false, 24}, {"algorithm", false, 14}, {"cases", true, 7},
               {"wrong", true, 7},    {"err_max", true, 10},    {"not converged", false, 0, 2}};
  for (const auto& [family, s] : families)
    for (std::size_t i = 0; i < s.algorithms.size(); ++i)
      t.rows.push_back({family_cells(family, s.algorithms[i]), i == 0});
  return t;
}

void print_family_table(std::ostream& out,
                        const std::vector<std::pair<std::string, RunSummary>>& families) {
  render_text(out, family_table(families));
}

std::vector<OracleMethodCounts> oracle_method_counts(std::span<const CaseResult> results,
                                                     const std::vector<std::string>& family_names) {
  std::vector<OracleMethodCounts> counts(family_names.size());
  for (std::size_t i = 0; i < family_names.size(); ++i)
    counts[i].family = family_names[i];
  for (const CaseResult& r : results) {
    if (!r.exact || r.record.family >= counts.size()) continue;
    OracleMethodCounts& c = counts[r.record.family];
    ++c.cases;
    c.certified += r.exact->method == exact::AnswerMethod::certified;
    c.depths += r.exact->depth_method != exact::AnswerMethod::none;
    c.depths_certified += r.exact->depth_method == exact::AnswerMethod::certified;
  }
  std::erase_if(counts, [](const OracleMethodCounts& c) { return c.cases == 0; });
  return counts;
}

void print_oracle_methods(std::ostream& out, const std::vector<OracleMethodCounts>& families) {
  auto percent = [](std::uint64_t part, std::uint64_t whole) {
    return whole ? format("%.2f%%", 100.0 * static_cast<double>(part) / static_cast<double>(whole))
                 : std::string("-");
  };
  char line[256];
  std::snprintf(line, sizeof line, "%-24s %7s %10s %7s %10s\n", "family", "cases", "certified",
                "depths", "certified");
  out << line;
  OracleMethodCounts total{"all"};
  auto row = [&](const OracleMethodCounts& c) {
    std::snprintf(line, sizeof line, "%-24s %7llu %10s %7llu %10s\n", c.family.c_str(),
                  static_cast<unsigned long long>(c.cases), percent(c.certified, c.cases).c_str(),
                  static_cast<unsigned long long>(c.depths),
                  percent(c.depths_certified, c.depths).c_str());
    out << line;
  };
  for (const OracleMethodCounts& c : families) {
    row(c);
    total.cases += c.cases;
    total.certified += c.certified;
    total.depths += c.depths;
    total.depths_certified += c.depths_certified;
  }
  if (families.size() > 1) row(total);
}

}  // namespace gjklab::experiment
