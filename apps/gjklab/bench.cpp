#include "gjklab/bench.hpp"

#include <CLI/CLI.hpp>
#include <fstream>
#include <optional>
#include <ostream>

#include "gjklab/experiment/bench/bench.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

namespace gjklab::cli {

namespace bench = experiment::bench;

CLI::App* add_bench_command(CLI::App& app, BenchArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "bench", "time every algorithm on identical inputs (interleaved, medians and ratios)");
  std::vector<std::string> suites = bench::all_suites();
  suites.emplace_back("all");
  cmd->add_option("--suite", args.suite, bench::suite_list() + " or all (default: all)")
      ->check(CLI::IsMember(suites));
  cmd->add_option(
         "--algorithms", args.algorithms,
         "comma-separated names, each optionally with +hc for hill-climbing support "
         "(default: every boolean and distance algorithm but sat, which runs when named): " +
             experiment::algorithm_names())
      ->delimiter(',');
  cmd->add_option("--reference", args.reference,
                  "reference of every ratio (default: libccd-mpr for booleans, the fastest peer "
                  "distance query for distances)");
  cmd->add_option("--json", args.json, "also write the records as JSON to this file");
  cmd->add_option("--markdown", args.markdown,
                  "also write the seed tables (with the config's published figures) as Markdown");
  cmd->add_option("--config", args.config,
                  "bench config file (TOML), e.g. experiments/bench/seed_tables.toml");
  cmd->add_option("--cases", args.cases, "only cases whose name contains this text");
  cmd->add_option("--samples", args.samples, "interleaved samples per case (default 31)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--configurations", args.configurations,
                  "seeded configurations per seed/random case (default 8)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--batch-us", args.batch_us, "target time of one batch in µs (default 500)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_option("--seed", args.seed, "seed of the inputs (default 1)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quiet", args.quiet, "no progress lines on stderr");
  cmd->add_option("--precision", args.precision,
                  "floating-point type of the GJK queries (gjk-bool, the distance variants, "
                  "epa): float, double (default) or long double; peers run in double")
      ->check(CLI::IsMember({"float", "double", "long double"}));
  CLI::Option* compare =
      cmd->add_option("--compare", args.compare,
                      "baseline: an earlier run's --json file; prints each row's ratio to its "
                      "reference divided by the baseline's (e.g. results/bench/baseline.json)");
  cmd->add_option("--compare-threshold", args.compare_threshold,
                  "mark rows whose change exceeds this (default 1.20: 20% slower against the "
                  "reference than in the baseline)")
      ->check(CLI::Range(1.0, 1000.0))
      ->needs(compare);
  return cmd;
}

int run_bench_command(const BenchArgs& args, std::ostream& out, std::ostream& err) {
  bench::BenchConfig config;
  std::optional<bench::BenchBaseline> baseline;
  try {
    if (!args.config.empty()) config = bench::load_bench_config(args.config);
    // Read before the run, so that a bad baseline does not cost one.
    if (!args.compare.empty()) baseline = bench::read_baseline(args.compare);
  } catch (const bench::BenchError& e) {
    err << "gjklab bench: " << e.what() << "\n";
    return 2;
  }
  // Command-line settings override the file's.
  if (args.suite != "all" || args.config.empty()) {
    if (args.suite == "all")
      config.suites = bench::all_suites();
    else
      config.suites = {args.suite};
  }
  if (!args.algorithms.empty()) config.algorithms = args.algorithms;
  if (!args.reference.empty()) config.reference = args.reference;
  if (!args.cases.empty()) config.case_filter = args.cases;
  if (args.samples > 0) config.samples = args.samples;
  if (args.configurations > 0) config.configurations = args.configurations;
  if (args.batch_us >= 0) config.batch_seconds = args.batch_us * 1e-6;
  if (args.seed >= 0) config.seed = static_cast<std::uint64_t>(args.seed);
  if (!args.precision.empty()) config.precision = *precision_from_string(args.precision);

  bench::BenchReport report;
  try {
    report = bench::run_bench(config, args.quiet ? nullptr : &err);
  } catch (const bench::BenchError& e) {
    err << "gjklab bench: " << e.what() << "\n";
    return 2;
  }
  out << "gjklab bench";
  for (const auto& [k, v] : bench::bench_environment())
    out << "\n  " << k << ": " << v;
  out << "\n  samples: " << config.samples << ", configurations: " << config.configurations
      << ", batch: " << config.batch_seconds * 1e6 << " us, seed: " << config.seed << "\n";
  if (baseline)
    report.comparison = bench::compare_to_baseline(
        report, *baseline,
        args.compare_threshold > 0 ? args.compare_threshold : bench::kDefaultCompareThreshold);
  bench::print_table(report, out);
  if (report.comparison) bench::print_comparison(*report.comparison, out);
  auto write = [&](const std::string& path, auto&& writer) {
    std::ofstream file(path);
    if (!file) {
      err << "gjklab bench: cannot write " << path << "\n";
      return false;
    }
    writer(file);
    return static_cast<bool>(file);
  };
  if (!args.json.empty() &&
      !write(args.json, [&](std::ostream& o) { bench::write_json(report, o); }))
    return 1;
  if (!args.markdown.empty() &&
      !write(args.markdown, [&](std::ostream& o) { bench::write_seed_tables_markdown(report, o); }))
    return 1;
  return 0;
}

}  // namespace gjklab::cli
