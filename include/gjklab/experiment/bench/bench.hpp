// `gjklab bench`: every algorithm on identical inputs, timed in one process.
//
// Suites (all seeded, so a run measures the same inputs every time):
//   seed    the classic demo shapes (box 8, cone 33, cylinder 64, UV sphere 482 vertices), every
//           unordered pair, overlapping (centres 0.5 apart) and separated (centres 2.5 apart),
//           each case `configurations` random rotations and directions;
//   random  n points on the unit sphere (n = 8, 32, …, 8192), B moved along a random axis so
//           that the pair's extents along it are 0.1 apart (separated) or overlap by 0.1;
//   scene   N demo shapes (N = 8, 16, …, 72), randomly rotated, centres uniform in a ball of
//           radius 0.5 (near one point: the shapes have size 1), every pair through the narrow
//           phase; reported as milliseconds per full pass.
//
// Method. For each case, every algorithm first runs once (warm-up, and the tallies of
// iterations and support calls), then its repetition count is set so that one batch takes
// about `batch_seconds`. Then `samples` rounds run the batches interleaved, A B C A B C …; a
// batch's time divided by its queries is one sample of ns per query. Times are the thread's CPU
// time (CLOCK_THREAD_CPUTIME_ID), so time spent waiting for a core on a shared machine is not
// counted. Reported: the median, the
// 10th and 90th percentiles, and ratios of medians measured in the same run. Hill-climbing rows
// (name suffix "+hc") run the same algorithm on copies of the shapes with hill-climbing
// support enabled (Polytope::enable_hill_climbing); hull adjacency is computed before timing.
//
// Cost floor of a query: support_calls × (c_A + c_B), with c_X the measured time of one full-scan
// support call on shape X (random directions): what the query would cost if nothing but its
// support calls took time. c_X is measured with each call's direction depending on the
// previous call's answer, as in GJK, where a direction needs the support point before it (the
// latency of a call). The same floor with independent calls, which the processor overlaps
// (throughput, 2-3x lower on 8-vertex shapes), is reported beside it. c_X is sampled in the
// same rotation as the queries' batches (a round of about a tenth of a batch per shape after
// each rotation, itself after an untimed round) and its median taken, so that the floor and
// the queries see the machine in the same state.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjklab/experiment/registry/algorithms.hpp"

namespace gjklab::experiment::bench {

inline constexpr const char* kHillClimbingSuffix = "+hc";

/// Every suite, in the order a full run measures them (the default of BenchConfig::suites).
std::vector<std::string> all_suites();
/// "seed, random, scene": the suites, for messages.
std::string suite_list();

struct BenchConfig {
  std::vector<std::string> suites = all_suites();
  /// Algorithm names (registry names, optionally with "+hc"); empty: every registered boolean
  /// and distance algorithm, plus hill-climbing rows of gjk-bool and gjk-johnson in the random
  /// suite.
  std::vector<std::string> algorithms;
  /// Reference of every ratio; empty: libccd-mpr for boolean algorithms and the fastest
  /// installed peer distance query for distance algorithms (libccd-gjk's boolean if none).
  std::string reference;
  int samples = 31;
  double batch_seconds = 5e-4;
  /// Seeded configurations (rotations, clouds) per case of the seed and random suites.
  int configurations = 8;
  std::uint64_t seed = 1;
  /// Only cases whose name contains this text (empty: all).
  std::string case_filter;
  /// Published figures to print beside the seed suite (µs per query, by pair name such as
  /// "box-cone") and the scene suite (ms per pass, by object count).
  std::map<std::string, double> published_pair_us;
  std::map<int, double> published_scene_ms;
  std::string published_source;  ///< where the published figures come from
  /// Floating-point type of the GJK queries (gjk-bool, the distance variants, epa); the peers
  /// and the oracle run in double whatever it is. Inputs are rounded before the timed loop.
  ScalarPrecision precision = ScalarPrecision::double_float;
};

struct BenchRecord {
  std::string suite;
  std::string case_name;
  std::string algorithm;
  std::string pair;       ///< seed suite: "box-cone"; random: "n=512"; scene: "N=72"
  std::string placement;  ///< "overlap", "separated" or "scene"
  int objects = 0;        ///< scene suite: number of objects
  long long queries = 0;  ///< queries per pass over the case (pairs × configurations)
  double ns_median = 0, ns_p10 = 0, ns_p90 = 0;  ///< per query
  double iterations_mean = 0;
  double support_calls_mean = 0;
  double intersect_fraction = 0;
  std::string reference;
  std::optional<double> ratio_to_reference;
  std::optional<double> floor_ns;  ///< cost floor per query (full-scan rows only)
  std::optional<double> ratio_to_floor;
  /// The floor with independent support calls (throughput): see the note at the top.
  std::optional<double> floor_independent_ns;
  std::optional<double> ratio_to_floor_independent;
  std::optional<double> ratio_to_full_scan;  ///< "+hc" rows: against the same algorithm's scan
  int repetitions = 0;                       ///< passes per batch
  bool via_registry = false;                 ///< timed through AlgorithmInfo::run (no direct loop)
};

// ---- comparison with a baseline (`--compare FILE`) ----------------------------------------
//
// Times from different runs are never compared: a row of this run is compared with the same
// row of an earlier run's JSON through its ratio to its reference, measured within each run.
// change = ratio now / ratio in the baseline: 1.00 is as fast against the reference as in the
// baseline, 1.25 is 25 % slower against it.

/// Rows whose change exceeds this are marked, unless another threshold is given. Two runs of the
/// same build on one shared machine differ by more than 10 % on about one row in eight, by more
/// than 20 % on about one in twenty-five, the short queries of the seed suite most
/// (results/bench/README.md): a lower default would mark noise.
inline constexpr double kDefaultCompareThreshold = 1.20;

/// An earlier run's records, read from its `--json` output: of each record only what a
/// comparison needs (suite, case_name, algorithm, reference, ratio_to_reference,
/// ratio_to_floor).
struct BenchBaseline {
  std::string path;
  std::vector<BenchRecord> records;
  /// The meta block's scalar fields as text (gjklab, cpu, configurations, seed, …), for the
  /// header of the comparison and its notes on inputs that differ.
  std::map<std::string, std::string> meta;
};

/// A record of this run and the baseline's record of the same suite, case, algorithm and
/// reference.
struct BenchComparisonRow {
  std::string suite, case_name, algorithm, reference;
  double ratio_now = 0, ratio_baseline = 0;  ///< ratio_to_reference
  /// ratio_now / ratio_baseline; empty on the reference's own row, whose ratio is 1 by
  /// definition (its floor change is then the only sign of the reference itself slowing).
  std::optional<double> change;
  std::optional<double> floor_now, floor_baseline, floor_change;  ///< ratio_to_floor, both sides
  bool over_threshold = false;                                    ///< change > threshold
};

/// A record that could not be compared, and why ("only in this run", "only in the baseline",
/// a different reference, no ratio to its reference).
struct BenchUnmatched {
  std::string suite, case_name, algorithm, why;
};

/// One algorithm's rows together: a slowdown of the algorithm itself moves most of its rows,
/// where the noise of a run moves single rows either way.
struct BenchAlgorithmChange {
  std::string algorithm;
  int rows = 0;
  std::optional<double> median_change;  ///< empty for the reference (no change of its own)
  std::optional<double> median_floor_change;
  int over_threshold = 0;
};

struct BenchComparison {
  std::string baseline_path;
  std::map<std::string, std::string> baseline_meta;
  double threshold = kDefaultCompareThreshold;
  /// Largest change first; the references' own rows last, largest floor change first.
  std::vector<BenchComparisonRow> rows;
  std::vector<BenchUnmatched> unmatched;
  /// Baseline records of a case or an algorithm this run did not measure at all (another
  /// --suite, --cases or --algorithms): counted, not listed, so that a partial run is not
  /// drowned in them; the algorithms are named.
  int baseline_records_not_run = 0;
  std::vector<std::string> baseline_algorithms_not_run;
  std::optional<double> median_change, median_floor_change;
  int over_threshold = 0;
  /// Per algorithm, the largest median change first, the reference last.
  std::vector<BenchAlgorithmChange> by_algorithm;
  std::vector<std::string> notes;  ///< inputs that differ from the baseline's
};

struct BenchReport {
  std::vector<BenchRecord> records;
  std::vector<std::string> notes;  ///< what the reader must know (reference choices, …)
  std::string boolean_reference;
  std::string distance_reference;
  BenchConfig config;
  /// Set when the run is compared with a baseline; written into the JSON as "compare".
  std::optional<BenchComparison> comparison;
};

/// Thrown for an unknown suite or algorithm name or an invalid setting (message says which).
class BenchError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How one row of a case is compared: its answer kind and, for a hill-climbing row, the name
/// of the same algorithm's full-scan row.
struct RatioRole {
  AnswerKind kind = AnswerKind::distance;
  std::optional<std::string> full_scan;
};

/// The references of the ratios: `fixed` (--reference) when set; else `boolean_reference` for
/// boolean rows, and for the others the fastest of `peer_distances` in the case, or
/// `distance_reference` when no peer distance query is installed.
struct References {
  std::string fixed;
  std::string boolean_reference;
  std::string distance_reference;
  std::vector<std::string> peer_distances;
};

/// Sets each row's reference and ratios from the medians of the same case (rows[i] has role
/// roles[i]): ratio_to_reference = median / the reference's median, and for a hill-climbing
/// row ratio_to_full_scan = median / its full scan's median. A missing reference leaves the
/// ratio empty.
void set_case_ratios(std::vector<BenchRecord>& rows, std::span<const RatioRole> roles,
                     const References& references);

/// Runs the benchmark. Progress lines (one per case) go to `progress` when it is not null.
BenchReport run_bench(const BenchConfig& config, std::ostream* progress = nullptr);

/// The readable table, one block per suite.
void print_table(const BenchReport& report, std::ostream& out);
/// {"meta": {...}, "records": [{suite, case, algorithm, ns_median, ns_p10, ns_p90,
/// iterations_mean, ratio_to_reference, …}, …]}, and "compare": {...} when the report has a
/// comparison.
void write_json(const BenchReport& report, std::ostream& out);
/// Markdown with the seed and scene suites beside the published figures of the config.
void write_seed_tables_markdown(const BenchReport& report, std::ostream& out);

/// Reads the records of a `--json` output as a baseline. Throws BenchError naming the file and
/// the problem (unreadable, not JSON, not a bench report, a record without a field it needs).
BenchBaseline read_baseline(const std::string& path);
/// Compares this run's records with the baseline's (see BenchComparison); rows whose change
/// exceeds `threshold` are marked.
BenchComparison compare_to_baseline(const BenchReport& report, const BenchBaseline& baseline,
                                    double threshold = kDefaultCompareThreshold);
/// The comparison's table, the records not compared and a summary line.
void print_comparison(const BenchComparison& comparison, std::ostream& out);

/// Reads a bench config file (TOML; format in experiments/README.md). Throws BenchError.
BenchConfig load_bench_config(const std::string& path);

/// Processor, compiler and commit, for the report headers.
std::map<std::string, std::string> bench_environment();

}  // namespace gjklab::experiment::bench
