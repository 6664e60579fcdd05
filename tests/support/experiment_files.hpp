// What the experiment-file tests share: the parser on a named text, a minimal valid file's
// pieces (tests append or replace lines to make one mistake at a time), and files in a scratch
// folder.
#pragma once

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gjklab/experiment/config/config.hpp"

namespace gjklab::testing {

inline experiment::ExperimentConfig parse(const std::string& text) {
  return experiment::parse_experiment(text, "exp.toml");
}

inline const std::string kHead = R"(name = "t"
seed = 1
cases = 10
)";
inline const std::string kFamily = R"(
[[family]]
shape = "sphere_points"
)";
inline const std::string kAlgorithm = R"(
[[algorithm]]
name = "gjk-johnson"
)";

inline std::map<std::string, std::string> as_map(
    const std::vector<std::pair<std::string, std::string>>& v) {
  return {v.begin(), v.end()};
}

/// Writes files into a fresh folder (removed at the end of the scope).
struct ExperimentFolder {
  std::filesystem::path path;
  explicit ExperimentFolder(const char* name)
      : path(std::filesystem::temp_directory_path() / ("gjklab-config-" + std::string(name))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~ExperimentFolder() { std::filesystem::remove_all(path); }
  std::filesystem::path write(const char* file, const std::string& text) const {
    std::ofstream(path / file) << text;
    return path / file;
  }
};

}  // namespace gjklab::testing
