// Per-algorithm summary of a run: what `gjklab run` prints at the end and `gjklab inspect`
// prints for an archive.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "gjklab/experiment/cases/records.hpp"
#include "gjklab/experiment/run/table.hpp"

namespace gjklab::experiment {

struct AlgorithmSummary {
  std::string name;
  std::uint64_t cases = 0;
  std::uint64_t wrong_booleans = 0;  ///< !boolean_correct (outside the touching band)
  std::uint64_t distances = 0;       ///< cases with a distance error (distance algorithms)
  double rel_error_median = 0, rel_error_p99 = 0, rel_error_max = 0;  ///< relative to size
  std::array<std::uint64_t, kAllTerminations.size()> terminations{};  ///< by Termination value
  std::array<std::uint64_t, 9> failures{};                            ///< by FailureClass value
  std::uint64_t depths = 0;  ///< cases with a depth error (depth algorithms)
  double depth_error_median = 0, depth_error_max = 0;  ///< |depth − exact depth| / size
  double iterations_mean = 0;
  std::int32_t iterations_max = 0;
  std::uint64_t timed = 0;    ///< cases with a time
  double time_ns_median = 0;  ///< median over cases of the per-case median time
};

struct RunSummary {
  std::uint64_t cases = 0;
  std::array<std::uint64_t, 3> contact{};  ///< cases per ContactClass (oracle on)
  std::vector<AlgorithmSummary> algorithms;
};

/// Accumulates results case by case (memory: a few numbers per case and algorithm).
class SummaryBuilder {
 public:
  explicit SummaryBuilder(std::vector<std::string> algorithm_names);
  void add(const CaseResult& result);
  RunSummary build() const;

 private:
  struct Column {
    std::vector<double> rel_errors;
    std::vector<double> depth_errors;
    std::vector<double> times;
    double iteration_sum = 0;
    AlgorithmSummary counts;
  };
  std::uint64_t cases_ = 0;
  std::array<std::uint64_t, 3> contact_{};
  std::vector<Column> columns_;
};

/// The summary's table: per algorithm, cases, wrong booleans, the median, 99th percentile and
/// largest distance error relative to size, mean and largest iterations, median time.
Table summary_table(const RunSummary& summary);

/// Prints the summary: its table as aligned text, then each algorithm's terminations, depth
/// errors and failure classes.
void print_summary(std::ostream& out, const RunSummary& summary);

/// One summary per family (index = CaseRecord::family), accumulated case by case.
class FamilySummaryBuilder {
 public:
  FamilySummaryBuilder(std::vector<std::string> family_names,
                       std::vector<std::string> algorithm_names);
  void add(const CaseResult& result);
  /// (family name, its summary) for every family with at least one case.
  std::vector<std::pair<std::string, RunSummary>> build() const;

 private:
  std::vector<std::string> family_names_;
  std::vector<SummaryBuilder> builders_;
};

/// One row per family and algorithm, a family's rows a group: cases, wrong booleans, the
/// largest distance error relative to size, and every termination other than converged.
Table family_table(const std::vector<std::pair<std::string, RunSummary>>& families);

/// Prints family_table as aligned text.
void print_family_table(std::ostream& out,
                        const std::vector<std::pair<std::string, RunSummary>>& families);

/// How one family's exact answers were obtained (see ExactRecord::method and depth_method).
struct OracleMethodCounts {
  std::string family;
  std::uint64_t cases = 0;             ///< cases with an exact answer
  std::uint64_t certified = 0;         ///< distances certified (the rest by the QP)
  std::uint64_t depths = 0;            ///< exact depths computed
  std::uint64_t depths_certified = 0;  ///< of those, certified (the rest by the Minkowski hull)
};

/// Counts of the oracle's methods, one entry per family (index = CaseRecord::family) that has
/// at least one exact answer.
std::vector<OracleMethodCounts> oracle_method_counts(std::span<const CaseResult> results,
                                                     const std::vector<std::string>& family_names);

/// Prints one row per family: cases, certified fraction of distances and of depths, and a total.
void print_oracle_methods(std::ostream& out, const std::vector<OracleMethodCounts>& families);

}  // namespace gjklab::experiment
