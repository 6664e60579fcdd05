#include "gjklab/run.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <ostream>
#include <sstream>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/run/driver.hpp"
#include "gjklab/experiment/run/ranks.hpp"
#include "gjklab/experiment/run/summary.hpp"
#include "gjklab/stop_signals.hpp"

namespace gjklab::cli {

namespace {

/// Prints the end of a run: the summary, or where an incomplete archive was left.
int report_run(const experiment::RunReport& report, const std::string& what, std::ostream& out,
               std::ostream& err) {
  if (!report.complete) {
    err << "gjklab run: stopped: " << report.cases << " finished cases written to "
        << report.output.string() << " (marked incomplete; continue with gjklab run --resume "
        << report.output.string() << ")\n";
    return stop_requested() ? 130 : 0;
  }
  out << what << ": " << report.cases << " cases in " << report.seconds << " s ("
      << static_cast<double>(report.cases - report.resumed_cases) / report.seconds
      << " cases/s), archive " << report.output.string() << "\n\n";
  experiment::print_summary(out, report.summary);
  if (!report.families.empty()) {
    out << "\nper family:\n";
    experiment::print_family_table(out, report.families);
  }
  return 0;
}

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunArgs& args) {
  CLI::App* cmd = app.add_subcommand("run", "run an experiment file and write its HDF5 archive");
  cmd->add_option("experiment", args.experiment, "experiment file (TOML)");
  cmd->add_option("--out", args.output, "archive path (default: the file's `output`)");
  cmd->add_option("--threads", args.threads, "worker threads (default: the file's `threads`)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--cases", args.cases, "number of cases (default: the file's `cases`)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
  cmd->add_flag("--force", args.force, "overwrite an existing archive");
  cmd->add_option("--resume", args.resume,
                  "continue an interrupted run (FILE.h5.tmp) from its last checkpoint");
  cmd->add_option("--stop-after", args.stop_after,
                  "stop, resumable, once this many cases are written")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
  cmd->add_option("--checkpoint", args.checkpoint,
                  "cases between checkpoints (default " +
                      std::to_string(experiment::kDefaultCheckpointCases) + ", " +
                      std::to_string(experiment::kDistributedRoundCases) +
                      " under mpirun): at most this much work is lost if the run is killed")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 30));
  return cmd;
}

namespace {

/// The MPI job this process was started in (mpirun, srun), or none: a process started alone
/// runs as before. A launcher starting several copies of a build without MPI is refused
/// (each would run the whole experiment into the same archive).
std::unique_ptr<experiment::Ranks> join_launched_job() {
  const int launched = experiment::launched_ranks();
  if (launched == 0 || (launched == 1 && !experiment::built_with_mpi())) return nullptr;
  return experiment::join_mpi_job();
}

int run_or_resume(const RunArgs& args, experiment::RunOptions& options, std::ostream& out,
                  std::ostream& err) {
  if (!args.resume.empty()) {
    if (!args.output.empty() || args.cases > 0 || args.force) {
      err << "gjklab run: --resume continues the archived run as it was planned; --out, "
             "--cases and --force do not apply\n";
      return 2;
    }
    const StopSignals stop_signals;
    const experiment::RunReport report = experiment::resume_experiment(args.resume, options);
    return report_run(report,
                      "resumed run (" + std::to_string(report.resumed_cases) + " cases taken over)",
                      out, err);
  }
  const experiment::ExperimentConfig config = experiment::load_experiment(args.experiment);
  if (!args.output.empty()) options.output = args.output;
  if (args.cases > 0) options.cases = args.cases;
  options.force = args.force;
  const std::filesystem::path output = options.output.value_or(config.output);
  std::error_code ec;
  if (std::filesystem::equivalent(output, args.experiment, ec)) {
    err << "gjklab run: the archive " << output.string()
        << " would overwrite the experiment file itself; choose another --out\n";
    return 2;
  }
  const StopSignals stop_signals;
  const experiment::RunReport report = experiment::run_experiment(config, options);
  return report_run(report, "experiment '" + config.name + "'", out, err);
}

}  // namespace

int run_experiment_command(const RunArgs& args, std::ostream& out, std::ostream& err) {
  if (args.experiment.empty() == args.resume.empty()) {
    err << "gjklab run: give an experiment file, or --resume FILE (not both)\n";
    return 2;
  }
  std::unique_ptr<experiment::Ranks> ranks;
  // Rank 0 speaks for the job: the others print only errors of their own.
  bool speaks = true;
  std::ostringstream quiet;
  try {
    ranks = join_launched_job();
    speaks = !ranks || ranks->rank() == 0;
    experiment::RunOptions options;
    if (args.stop_after > 0) options.stop_after = args.stop_after;
    if (args.checkpoint > 0)
      options.checkpoint_cases = args.checkpoint;
    else if (ranks)
      options.checkpoint_cases = experiment::kDistributedRoundCases;
    if (args.threads > 0) options.threads = args.threads;
    options.progress = speaks ? &err : nullptr;
    options.live_progress = &err == &std::cerr && isatty(STDERR_FILENO);
    options.ranks = ranks.get();
    stop_requested() = false;
    options.stop = &stop_requested();
    const int status = run_or_resume(args, options, speaks ? out : quiet, speaks ? err : quiet);
    // Only the ranks a signal reached report it; the job's status is the worst rank's.
    return status;
  } catch (const experiment::PeerFailure&) {
    return 1;  // rank 0 reported it
  } catch (const experiment::ConfigError& e) {
    if (speaks) err << "gjklab run: " << e.what() << "\n";  // the same on every rank
    return 2;
  } catch (const std::exception& e) {
    err << "gjklab run: " << (speaks ? "" : "rank " + std::to_string(ranks->rank()) + ": ")
        << e.what() << "\n";
    // The other ranks would wait for this one in the next round: end the job.
    if (ranks && ranks->size() > 1 && !ranks->failure_shared) ranks->abort(1);
    return 1;
  }
}

}  // namespace gjklab::cli
