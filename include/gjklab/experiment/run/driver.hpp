// The experiment driver: generates every case, runs the oracle and each algorithm on it,
// computes the metrics and streams the records to the archive, on several threads.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/records.hpp"
#include "gjklab/experiment/run/summary.hpp"

namespace gjklab::experiment {

class Ranks;

/// Default checkpoint interval, in cases.
inline constexpr std::uint64_t kDefaultCheckpointCases = 512;

/// Command-line overrides and where progress goes.
struct RunOptions {
  std::optional<std::string> output;
  std::optional<int> threads;
  std::optional<std::uint64_t> cases;
  bool force = false;                ///< overwrite an existing output file
  std::ostream* progress = nullptr;  ///< progress lines (stderr), or none
  bool live_progress = false;        ///< rewrite one line in place (a terminal)
  /// Set (e.g. by a SIGINT handler) to stop cleanly: the cases already started are finished,
  /// written, and the archive is closed as incomplete under its temporary name.
  const std::atomic<bool>* stop = nullptr;
  /// Cases evaluated between two checkpoints (appended and flushed together): the work a
  /// kill can lose.
  std::uint64_t checkpoint_cases = kDefaultCheckpointCases;
  /// Stop (incomplete, resumable) once this many cases are written: a long run in parts.
  std::optional<std::uint64_t> stop_after;
  /// The ranks of a distributed run (ranks.hpp), or none: each rank evaluates its share of
  /// every round of cases and rank 0 writes the one archive (its output, progress and report;
  /// the other ranks' reports hold no summary).
  Ranks* ranks = nullptr;
};

struct RunReport {
  std::filesystem::path output;
  RunSummary summary;
  std::vector<std::pair<std::string, RunSummary>> families;  ///< per family, when several
  double seconds = 0;
  std::uint64_t cases = 0;          ///< cases written
  bool complete = false;            ///< false when stopped early (the archive keeps its .tmp name)
  std::uint64_t resumed_cases = 0;  ///< cases taken over from the interrupted run
};

/// Everything the run records about case `case_id`: a pure function of (config, case_id)
/// apart from the timing columns.
CaseResult evaluate_case(const ExperimentConfig& config, std::uint64_t case_id);

/// Runs the experiment and writes the archive. Throws ArchiveError before any work when the
/// output exists (without force) or cannot be written.
RunReport run_experiment(const ExperimentConfig& config, const RunOptions& options);

/// Continues an interrupted run (FILE.h5.tmp, or FILE.h5 for its temporary file) from its
/// last checkpoint with the archived experiment, and finishes it under the final name. The
/// finished archive equals an uninterrupted run's, timing columns and end time aside.
RunReport resume_experiment(const std::filesystem::path& path, const RunOptions& options);

/// The current UTC time as ISO 8601 ("2026-01-31T12:00:00Z").
std::string utc_now();

}  // namespace gjklab::experiment
