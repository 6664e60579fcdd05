#include "gjklab/hunt.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/hunt/hunt.hpp"
#include "gjklab/experiment/run/driver.hpp"
#include "gjklab/experiment/run/ranks.hpp"

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

/// A TOML string literal (basic string) holding `text`.
std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

/// The experiment that archives the found cases: one `file` family reading FOUND.jsonl, the
/// hunted algorithm with default options, and the exact oracle with depths, so that the
/// archive holds each case's geometry, the algorithm's answer and the exact one.
experiment::ExperimentConfig found_cases_experiment(const HuntArgs& args, const fs::path& found,
                                                    std::size_t count) {
  const std::string text = "name = " + toml_string("hunt-" + args.algorithm) +
                           "\nseed = 1\ncases = " + std::to_string(count) +
                           "\nthreads = 1\noutput = " + toml_string(args.archive) +
                           "\n[oracle]\nenabled = true\ndepth = true\n"
                           "[[family]]\nname = \"found\"\nshape = \"file\"\npath = " +
                           toml_string(fs::absolute(found).string()) +
                           "\n[[algorithm]]\nname = " + toml_string(args.algorithm) + "\n";
  return experiment::parse_experiment(text, "the found cases of " + found.string());
}

/// Runs the found cases into args.archive (replacing it only with --force).
void write_found_archive(const HuntArgs& args, const fs::path& found, std::size_t count) {
  experiment::RunOptions options;
  options.force = args.force;
  experiment::run_experiment(found_cases_experiment(args, found, count), options);
}

}  // namespace

CLI::App* add_hunt_command(CLI::App& app, HuntArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "hunt", "search an experiment's poses for failures of one algorithm (judged exactly)");
  cmd->add_option("experiment", args.experiment, "experiment file (families and placements)")
      ->required();
  cmd->add_option("--algorithm", args.algorithm,
                  "the algorithm to hunt: a registry name, or for nonconvex families the "
                  "experiment's label (e.g. gjk-johnson@decomposition=hull)")
      ->required();
  cmd->add_option("--queries", args.queries, "the search's budget of judged queries")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
  cmd->add_option("--objective", args.objective,
                  "wrong_boolean (default), error, iterations, not_converged or "
                  "false_convergence")
      ->check(CLI::IsMember(experiment::hunt_objective_names()));
  cmd->add_option("--seed", args.seed, "seed of the search (default 1)");
  cmd->add_option("--restart-queries", args.restart_queries,
                  "the most queries one restart's local search spends (default 6)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--out", args.out, "FOUND.jsonl: the failures as a gjklab query --cases file")
      ->required();
  cmd->add_option("--archive", args.archive,
                  "FILE.h5: also run the found cases as an experiment (the algorithm and the "
                  "exact oracle with depths) into an archive");
  cmd->add_flag("--force", args.force, "replace existing output files");
  cmd->add_flag("--no-random", args.no_random,
                "skip the random-sampling baseline (the same budget of queries)");
  return cmd;
}

int run_hunt_command(const HuntArgs& args, std::ostream& out, std::ostream& err) {
  const fs::path found = args.out, summary = summary_path(args.out);
  std::vector<fs::path> outputs = {found, summary};
  if (!args.archive.empty()) outputs.emplace_back(args.archive);
  for (const fs::path& p : outputs) {
    if (!args.force && fs::exists(p)) {
      err << "gjklab hunt: " << p.string() << " exists (use --force to replace it)\n";
      return 2;
    }
    if (fs::absolute(p) == fs::absolute(args.experiment)) {
      err << "gjklab hunt: " << p.string() << " is the experiment file\n";
      return 2;
    }
  }
  if (!args.archive.empty() && fs::absolute(args.archive) == fs::absolute(found)) {
    err << "gjklab hunt: --archive and --out are the same file\n";
    return 2;
  }
  // Under mpirun each rank searches with its share of the budget; rank 0 gathers the found
  // lines and summaries and writes the files.
  std::unique_ptr<experiment::Ranks> ranks;
  try {
    const int launched = experiment::launched_ranks();
    if (launched > 1 || (launched == 1 && experiment::built_with_mpi()))
      ranks = experiment::join_mpi_job();
    const int rank = ranks ? ranks->rank() : 0, size = ranks ? ranks->size() : 1;
    const experiment::ExperimentConfig config = experiment::load_experiment(args.experiment);
    if (!args.archive.empty() && config.has_nonconvex_families()) {
      err << "gjklab hunt: --archive archives found convex pairs only; the non-convex pairs "
             "found are in "
          << found.string() << " (gjklab query --cases answers them)\n";
      return 2;
    }
    experiment::HuntOptions options;
    options.algorithm = args.algorithm;
    options.queries = experiment::rank_queries(args.queries, rank, size);
    options.objective = *experiment::hunt_objective_from_string(args.objective);
    options.seed = args.seed;
    options.restart_queries = args.restart_queries;
    options.random_baseline = !args.no_random;
    options.rank = rank;
    options.ranks = size;
    const experiment::HuntReport report = experiment::hunt(config, options);
    std::string lines;
    for (const experiment::FoundCase& f : report.found)
      lines += experiment::found_case_line(f, report) + "\n";
    std::string line = experiment::hunt_summary_json(report);
    std::size_t found_count = report.found.size();
    if (ranks) {
      const std::vector<std::string> all_lines = ranks->gather(lines);
      const std::vector<std::string> summaries = ranks->gather(line);
      if (rank != 0) return 0;
      lines.clear();
      for (const std::string& part : all_lines)
        lines += part;
      line = experiment::merge_hunt_summaries(summaries);
      found_count = static_cast<std::size_t>(std::count(lines.begin(), lines.end(), '\n'));
    }
    write_file(found, lines);
    write_file(summary, line + "\n");
    out << line << "\n";
    if (!args.archive.empty()) {
      if (found_count == 0) {
        err << "gjklab hunt: no failures found, so no archive written to " << args.archive << "\n";
      } else {
        write_found_archive(args, found, found_count);
        err << "gjklab hunt: " << found_count << " found cases archived in " << args.archive
            << "\n";
      }
    }
    return 0;
  } catch (const std::exception& e) {
    const bool config_error = dynamic_cast<const experiment::ConfigError*>(&e) != nullptr;
    err << (config_error ? "" : "gjklab hunt: ") << e.what() << "\n";
    // The other ranks would wait for this one in a collective: end the job.
    if (ranks && ranks->size() > 1) ranks->abort(1);
    return 1;
  }
}

}  // namespace gjklab::cli
