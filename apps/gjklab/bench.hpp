// `gjklab bench`: every algorithm on identical inputs, interleaved in one process (see
// gjklab/experiment/bench/bench.hpp for the suites and the method).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct BenchArgs {
  std::string suite = "all";            ///< seed, random, scene or all
  std::vector<std::string> algorithms;  ///< empty: the suite's default
  std::string reference;                ///< empty: the default references
  std::string json;                     ///< JSON output file (empty: none)
  std::string markdown;                 ///< seed-tables Markdown output file (empty: none)
  std::string config;                   ///< bench config file (TOML)
  std::string cases;                    ///< only cases whose name contains this
  int samples = 0;                      ///< 0: the config's (31)
  int configurations = 0;               ///< 0: the config's (8)
  double batch_us = -1;                 ///< < 0: the config's (500 µs)
  long long seed = -1;                  ///< < 0: the config's (1)
  bool quiet = false;
  std::string precision;         ///< GJK queries' floating-point type; empty: the config's (double)
  std::string compare;           ///< baseline JSON to compare the ratios with (empty: none)
  double compare_threshold = 0;  ///< changes above this are marked; 0: the default (1.20)
};

CLI::App* add_bench_command(CLI::App& app, BenchArgs& args);

/// Returns 0, or 2 for a usage error (unknown suite, algorithm or file, or a baseline that is
/// not a bench report); 0 also when the comparison finds slowdowns, which are for review.
int run_bench_command(const BenchArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
