#include "gjklab/hunt.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <ostream>

#include "gjklab/experiment/config.hpp"
#include "gjklab/experiment/hunt.hpp"

namespace gjklab::cli {

namespace fs = std::filesystem;

namespace {

/// FOUND.summary.json beside FOUND.jsonl (the extension, whatever it is, replaced).
fs::path summary_path(const fs::path& out) {
  fs::path p = out;
  p.replace_extension(".summary.json");
  return p;
}

/// Writes `text` to `path` through PATH.tmp and a rename, so that no half-written file is
/// left under the final name.
void write_file(const fs::path& path, const std::string& text) {
  const fs::path temporary = path.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + temporary.string());
  }
  fs::rename(temporary, path);
}

}  // namespace

CLI::App* add_hunt_command(CLI::App& app, HuntArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "hunt", "search an experiment's poses for failures of one algorithm (judged exactly)");
  cmd->add_option("experiment", args.experiment, "experiment file (families and placements)")
      ->required();
  cmd->add_option("--algorithm", args.algorithm, "the algorithm to hunt (registry name)")
      ->required();
  cmd->add_option("--queries", args.queries, "the search's budget of judged queries")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
  cmd->add_option("--objective", args.objective,
                  "wrong_boolean (default), error, iterations or not_converged")
      ->check(CLI::IsMember({"wrong_boolean", "error", "iterations", "not_converged"}));
  cmd->add_option("--seed", args.seed, "seed of the search (default 1)");
  cmd->add_option("--out", args.out, "FOUND.jsonl: the failures as a gjklab query --cases file")
      ->required();
  cmd->add_flag("--force", args.force, "replace existing output files");
  cmd->add_flag("--no-random", args.no_random,
                "skip the random-sampling baseline (the same budget of queries)");
  return cmd;
}

int run_hunt_command(const HuntArgs& args, std::ostream& out, std::ostream& err) {
  const fs::path found = args.out, summary = summary_path(args.out);
  for (const fs::path& p : {found, summary})
    if (!args.force && fs::exists(p)) {
      err << "gjklab hunt: " << p.string() << " exists (use --force to replace it)\n";
      return 2;
    }
  if (fs::absolute(found) == fs::absolute(args.experiment)) {
    err << "gjklab hunt: --out is the experiment file\n";
    return 2;
  }
  try {
    const experiment::ExperimentConfig config = experiment::load_experiment(args.experiment);
    experiment::HuntOptions options;
    options.algorithm = args.algorithm;
    options.queries = args.queries;
    options.objective = *experiment::hunt_objective_from_string(args.objective);
    options.seed = args.seed;
    options.random_baseline = !args.no_random;
    const experiment::HuntReport report = experiment::hunt(config, options);
    std::string lines;
    for (const experiment::FoundCase& f : report.found)
      lines += experiment::found_case_line(f, report) + "\n";
    write_file(found, lines);
    const std::string line = experiment::hunt_summary_json(report);
    write_file(summary, line + "\n");
    out << line << "\n";
    return 0;
  } catch (const experiment::ConfigError& e) {
    err << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    err << "gjklab hunt: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gjklab::cli
