// `gjklab hunt`: searches an experiment's pose space for failures of one algorithm, shrinks
// them and writes them as a cases file, with the same budget spent on random sampling for
// comparison (experiment/hunt.hpp).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct HuntArgs {
  std::string experiment;
  std::string algorithm;
  std::uint64_t queries = 10000;
  std::string objective = "wrong_boolean";
  std::uint64_t seed = 1;
  int restart_queries = 6;  ///< see experiment::HuntOptions::restart_queries
  std::string out;          ///< FOUND.jsonl; the summary goes to FOUND.summary.json
  std::string archive;      ///< FILE.h5: the found cases run as an experiment (empty: none)
  bool force = false;
  bool no_random = false;
};

CLI::App* add_hunt_command(CLI::App& app, HuntArgs& args);

/// Returns 0 (failures found or not), 1 for an experiment or file error, 2 for a usage error.
int run_hunt_command(const HuntArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
