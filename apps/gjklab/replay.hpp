// `gjklab replay`: reruns one archived case with its archived options, optionally with a
// per-iteration trace, and says whether the result equals the archived one.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct ReplayArgs {
  std::string archive;
  std::uint64_t case_id = 0;
  std::string algorithm;  ///< a result group label or registry name; empty: all
  bool trace = false;
};

CLI::App* add_replay_command(CLI::App& app, ReplayArgs& args);

/// Returns 0 when every rerun equals the archived result, 1 when one differs or the case or
/// algorithm is not in the archive.
int run_replay_command(const ReplayArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
