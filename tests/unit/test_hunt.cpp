// gjklab hunt: a search of an experiment's poses for failures of one algorithm. What it finds
// must fail again when rerun as a cases file, the search must be deterministic for a seed, and
// the random-sampling baseline must spend the same budget.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../support/cli_run.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/hunt/hunt.hpp"

using namespace gjklab;
using namespace gjklab::experiment;
using testing::run_cli;
using testing::ScratchDir;

namespace {

// Near-contact pairs: where libccd-gjk's tolerance answers "intersecting" for pairs 1e-9 of
// their size apart (the hard study's wrong booleans of that peer).
constexpr const char* kExperiment = R"(name = "hunt"
seed = 3
cases = 100
[placement]
mode = "mixed"
gap = [1e-6, 1e-1]
depth = [1e-6, 1e-1]
[[family]]
name = "near-contact"
shape = "contact"
contact = "any"
[[family]]
name = "parallel-edges"
shape = "contact"
contact = "parallel-edges"
angle = [1e-9, 1e-2]
[[algorithm]]
name = "libccd-gjk"
)";

HuntReport hunt_libccd(std::uint64_t seed) {
  const ExperimentConfig config = parse_experiment(kExperiment, "hunt.toml");
  HuntOptions options;
  options.algorithm = "libccd-gjk";
  options.queries = 1500;
  options.seed = seed;
  return hunt(config, options);
}

}  // namespace

TEST_CASE("hunt finds libccd-gjk's wrong booleans near contact, and each fails again",
          "[unit][hunt]") {
  const HuntReport report = hunt_libccd(1);
  CHECK(report.queries == 1500);
  CHECK(report.random_queries == 1500);
  REQUIRE(report.found.size() >= 2);
  // Every found line, read back as a cases file line, is still a wrong boolean outside the band
  // against the exact answer (the shrinking kept only failing pairs).
  const AlgorithmInfo& libccd = *find_algorithm("libccd-gjk");
  for (const FoundCase& f : report.found) {
    const auto line = nlohmann::json::parse(found_case_line(f, report));
    INFO(line.dump());
    std::vector<Vec3> a, b;
    for (const auto& p : line["a"])
      a.emplace_back(p[0], p[1], p[2]);
    for (const auto& p : line["b"])
      b.emplace_back(p[0], p[1], p[2]);
    const auto answer = run_algorithm(libccd, Polytope(a), Polytope(b), {}, {});
    const auto exact = exact::solve(a, b, {.depth = true});
    const double size = pair_size(a, b);
    CHECK(answer.intersect != exact.intersect);
    const double measure = exact.intersect ? exact.depth.value() : exact.distance;
    CHECK(measure > 1e-10 * size);
    CHECK(line["found_by"]["exact"]["intersect"] == exact.intersect);
    // Shrunk: no more than the points that make the configuration.
    CHECK(a.size() + b.size() <= 8);
  }
}

TEST_CASE("hunt is deterministic for a seed", "[unit][hunt]") {
  const HuntReport first = hunt_libccd(7), second = hunt_libccd(7);
  REQUIRE(first.found.size() == second.found.size());
  for (std::size_t i = 0; i < first.found.size(); ++i)
    CHECK(found_case_line(first.found[i], first) == found_case_line(second.found[i], second));
  CHECK(hunt_summary_json(first) == hunt_summary_json(second));
}

TEST_CASE("gjklab hunt writes FOUND.jsonl and FOUND.summary.json, refuses to replace them",
          "[unit][hunt]") {
  ScratchDir dir("hunt");
  const std::string experiment = dir.file("hunt.toml");
  std::ofstream(experiment) << kExperiment;
  const std::string found = dir.file("found.jsonl");
  auto r = run_cli({"hunt", experiment, "--algorithm", "libccd-gjk", "--queries", "300", "--out",
                    found, "--no-random"});
  REQUIRE(r.status == 0);
  const auto summary = nlohmann::json::parse(r.out);
  CHECK(summary["queries"] == 300);
  CHECK(summary["random_queries"] == 0);
  std::ifstream in(dir.file("found.summary.json"));
  std::stringstream text;
  text << in.rdbuf();
  CHECK(nlohmann::json::parse(text.str()) == summary);
  // Every line of FOUND.jsonl is a valid cases line that gjklab query answers.
  r = run_cli({"query", "--cases", found, "--algorithms", "libccd-gjk"});
  CHECK(r.status == 0);
  r = run_cli(
      {"hunt", experiment, "--algorithm", "libccd-gjk", "--queries", "300", "--out", found});
  CHECK(r.status == 2);
  CHECK(r.err.find("exists (use --force") != std::string::npos);
  r = run_cli({"hunt", experiment, "--algorithm", "gjk-nothing", "--queries", "10", "--out",
               dir.file("x.jsonl")});
  CHECK(r.status == 1);
  CHECK(r.err.find("unknown algorithm 'gjk-nothing'") != std::string::npos);
}

TEST_CASE("gjklab hunt --archive runs the found cases into an archive, every one wrong",
          "[unit][hunt]") {
  ScratchDir dir("hunt-archive");
  const std::string experiment = dir.file("hunt.toml");
  std::ofstream(experiment) << kExperiment;
  const std::string found = dir.file("found.jsonl"), archive = dir.file("found.h5");
  auto r = run_cli({"hunt", experiment, "--algorithm", "libccd-gjk", "--queries", "1500", "--out",
                    found, "--archive", archive, "--no-random"});
  REQUIRE(r.status == 0);
  std::ifstream in(found);
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);)
    ++lines;
  REQUIRE(lines >= 2);
  r = run_cli({"inspect", archive});
  REQUIRE(r.status == 0);
  CHECK(r.out.find(std::to_string(lines) + " of " + std::to_string(lines) + " cases, complete") !=
        std::string::npos);
  CHECK(r.out.find("libccd-gjk: wrong_boolean=" + std::to_string(lines)) != std::string::npos);
  r = run_cli({"hunt", experiment, "--algorithm", "libccd-gjk", "--queries", "10", "--out",
               dir.file("y.jsonl"), "--archive", dir.file("y.jsonl")});
  CHECK(r.status == 2);
  CHECK(r.err.find("same file") != std::string::npos);
}

TEST_CASE("hunt's false_convergence: a peer's wrong converged answers, none of gjk-johnson's",
          "[unit][hunt]") {
  // Without a bracket (libccd-gjk reports none), a converged answer that is wrong counts; with
  // one (gjk-johnson), only a converged answer whose bracket misses the exact distance does.
  const ExperimentConfig config = parse_experiment(kExperiment, "hunt.toml");
  HuntOptions options;
  options.objective = HuntObjective::false_convergence;
  options.queries = 1500;
  options.seed = 1;
  options.algorithm = "libccd-gjk";
  CHECK(hunt(config, options).found.size() >= 2);
  options.algorithm = "gjk-johnson";
  const HuntReport johnson = hunt(config, options);
  CHECK(johnson.queries == 1500);
  CHECK(johnson.found.empty());
  CHECK(hunt_objective_from_string("false_convergence") == HuntObjective::false_convergence);
}
