// Where a result came from: tool version, build and library versions.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace gjklab::experiment {

/// (name, version) of gjklab itself, its git commit, compiler, flags and every library used.
std::vector<std::pair<std::string, std::string>> build_provenance();

}  // namespace gjklab::experiment
