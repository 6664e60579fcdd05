#include "gjklab/cli.hpp"

#include <CLI/CLI.hpp>
#include <ostream>

#include "gjklab/bench.hpp"
#include "gjklab/experiment/run/provenance.hpp"
#include "gjklab/hunt.hpp"
#include "gjklab/inspect.hpp"
#include "gjklab/names.hpp"
#include "gjklab/query.hpp"
#include "gjklab/replay.hpp"
#include "gjklab/run.hpp"
#include "gjklab/schema.hpp"
#include "gjklab/simulate.hpp"

namespace gjklab::cli {

int run(int argc, const char* const* argv, std::istream& in, std::ostream& out, std::ostream& err) {
  CLI::App app{"gjklab: a research testbed for GJK-family collision and distance queries"};
  app.require_subcommand(1);
  auto* version = app.add_subcommand("version", "print the version, build and library versions");
  QueryArgs query_args;
  auto* query = add_query_command(app, query_args);
  RunArgs run_args;
  auto* run_cmd = add_run_command(app, run_args);
  InspectArgs inspect_args;
  auto* inspect = add_inspect_command(app, inspect_args);
  ReplayArgs replay_args;
  auto* replay = add_replay_command(app, replay_args);
  BenchArgs bench_args;
  auto* bench = add_bench_command(app, bench_args);
  HuntArgs hunt_args;
  auto* hunt = add_hunt_command(app, hunt_args);
  SimulateArgs simulate_args;
  auto* simulate = add_simulate_command(app, simulate_args);
  SchemaArgs schema_args;
  auto* schema = add_schema_command(app, schema_args);
  NamesArgs names_args;
  auto* names = add_names_command(app, names_args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    out << app.help();
    return 0;
  } catch (const CLI::ParseError& e) {
    err << "gjklab: " << e.what() << "\n"
        << "run 'gjklab --help' for usage\n";
    return 2;
  }
  if (query->parsed()) return run_query(query_args, in, out, err);
  if (run_cmd->parsed()) return run_experiment_command(run_args, out, err);
  if (inspect->parsed()) return run_inspect_command(inspect_args, out, err);
  if (replay->parsed()) return run_replay_command(replay_args, out, err);
  if (bench->parsed()) return run_bench_command(bench_args, out, err);
  if (hunt->parsed()) return run_hunt_command(hunt_args, out, err);
  if (simulate->parsed()) return run_simulate_command(simulate_args, out, err);
  if (schema->parsed()) return run_schema_command(schema_args, out, err);
  if (names->parsed()) return run_names_command(names_args, out);
  if (version->parsed()) {
    for (const auto& [name, value] : experiment::build_provenance())
      out << name << ": " << value << "\n";
  }
  return 0;
}

}  // namespace gjklab::cli
