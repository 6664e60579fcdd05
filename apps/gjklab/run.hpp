// `gjklab run`: an experiment file to an HDF5 archive.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct RunArgs {
  std::string experiment;
  std::string output;       ///< empty: the file's `output`
  int threads = 0;          ///< 0: the file's `threads`
  std::uint64_t cases = 0;  ///< 0: the file's `cases`
  bool force = false;
  std::string resume;            ///< continue this interrupted run instead
  std::uint64_t stop_after = 0;  ///< 0: run to the end
  std::uint64_t checkpoint = 0;  ///< 0: the default interval
};

CLI::App* add_run_command(CLI::App& app, RunArgs& args);

int run_experiment_command(const RunArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
