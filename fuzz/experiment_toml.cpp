// Experiment files: `gjklab run FILE` reads them with experiment::load_experiment, following
// `base = "FILE"` chains and reading the cases or mesh files that families name.
//
// Input: the experiment's text, optionally followed by more files, each introduced by a line
// "#%% NAME" (NAME: 1 to 32 of [A-Za-z0-9_.-]), all written to one scratch folder, so that
// bases, base cycles and `file` families can refer to each other. The main file is main.toml.
// Properties: loading gives an ExperimentConfig or a ConfigError, nothing else; an accepted
// experiment whose shapes are small generates its first cases without error and with finite
// coordinates (a value that fails only at run time should have been refused at load time).
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>

#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "support.hpp"

namespace {

using gjklab::experiment::ExperimentConfig;
using gjklab::fuzz::violated;

bool is_file_name(std::string_view name) {
  if (name.empty() || name.size() > 32 || name == "." || name == "..") return false;
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '.' || c == '-';
    if (!ok) return false;
  }
  return true;
}

/// Splits the input at "#%% NAME" lines and writes each part to the scratch folder.
void write_files(std::string_view text) {
  gjklab::fuzz::clear_scratch_folder();
  std::string name = "main.toml";
  std::string body;
  auto flush = [&] { gjklab::fuzz::write_scratch_file(name, body); };
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    if (line.starts_with("#%% ") && is_file_name(line.substr(4))) {
      flush();
      name = std::string(line.substr(4));
      body.clear();
    } else {
      body.append(line);
      if (end < text.size()) body.push_back('\n');
    }
    start = end + 1;
  }
  flush();
}

/// Largest vertex count any family may request (the generators' cost is linear in it).
double largest_vertex_count(const ExperimentConfig& config) {
  double most = 0;
  for (const auto& f : config.families)
    most = std::max({most, f.vertices_a.hi, f.vertices_b.hi});
  return most;
}

/// Generation is what `gjklab run` does next; bounded to small shapes so that one input stays
/// within milliseconds (the parser's limits, not the fuzzer's, bound the large ones).
constexpr double kGenerateUpToVertices = 2000;
constexpr std::uint64_t kCasesGenerated = 3;

void check_generation(const ExperimentConfig& config) {
  if (largest_vertex_count(config) > kGenerateUpToVertices) return;
  const std::uint64_t cases = std::min(config.cases, kCasesGenerated);
  for (std::uint64_t id = 0; id < cases; ++id) {
    try {
      const auto g = gjklab::experiment::generate_case(config, id);
      if (g.a.empty() || g.b.empty()) violated("an accepted experiment generates an empty cloud");
      for (const auto* cloud : {&g.a, &g.b})
        for (const auto& p : *cloud)
          if (!p.allFinite()) violated("an accepted experiment generates a non-finite point");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "generate_case(%llu): %s\n", static_cast<unsigned long long>(id),
                   e.what());
      violated("an accepted experiment fails when its cases are generated");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  write_files(std::string_view(reinterpret_cast<const char*>(data), size));
  ExperimentConfig config;
  try {
    config = gjklab::experiment::load_experiment(gjklab::fuzz::scratch_folder() / "main.toml");
  } catch (const gjklab::experiment::ConfigError&) {
    return 0;
  }
  check_generation(config);
  return 0;
}
