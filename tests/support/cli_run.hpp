// Drives the `gjklab` command line in-process, and scratch folders for the files it reads and
// writes.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gjklab/cli.hpp"

namespace gjklab::testing {

struct CliResult {
  int status = 0;
  std::string out, err;
};

/// Runs `gjklab ARGS...` with `input` as standard input.
inline CliResult run_cli(const std::vector<std::string>& args, const std::string& input = "") {
  std::vector<const char*> argv{"gjklab"};
  for (const auto& a : args)
    argv.push_back(a.c_str());
  std::istringstream in(input);
  std::ostringstream out, err;
  const int status = cli::run(static_cast<int>(argv.size()), argv.data(), in, out, err);
  return {status, out.str(), err.str()};
}

/// The same, returning the exit status and leaving the outputs in out and err.
inline int run_cli(const std::vector<std::string>& args, std::string& out, std::string& err) {
  CliResult r = run_cli(args);
  out = std::move(r.out);
  err = std::move(r.err);
  return r.status;
}

/// A fresh folder under the system's temporary directory, removed at the end of the scope.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag) {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("gjklab-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace gjklab::testing
