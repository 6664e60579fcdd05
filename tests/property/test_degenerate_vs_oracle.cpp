// Every gjklab algorithm against the exact oracle on the degenerate and near-contact families
// (exact contact of every type, ε = 1e-15 … 1e-3 of the size, parallel edges, flat, collinear
// and duplicate clouds, slivers, scale disparity, offsets up to 1e9, tiny shapes), classified
// as `gjklab run` classifies them. The failures that are known and accepted are listed, each
// with its reason, in tests/property/data/known_failures.txt: a failure not in that list fails
// the suite, and so does a listed one that no longer fails (remove it from the list).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include "gjklab/experiment/config.hpp"
#include "gjklab/experiment/driver.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

namespace {

constexpr std::uint64_t kCases = 12000;

constexpr const char* kExperiment = R"(
name = "degenerate-ci"
seed = 20261123
cases = 12000
touching_band = 1e-10
[placement]
mode = "mixed"
gap = [1e-15, 1e-3]
depth = [1e-15, 1e-3]
[[family]]
name = "touching"
shape = "contact"
contact = "any"
[family.placement]
mode = "touching"
[[family]]
name = "contact-eps"
shape = "contact"
contact = "any"
weight = 2
[[family]]
name = "parallel-edges"
shape = "contact"
contact = "parallel-edges"
angle = [1e-9, 1e-2]
[[family]]
name = "flat-vs-box"
shape_a = "flat_points"
shape_b = "box"
vertices_a = [3, 64]
rotate = "axes"
[[family]]
name = "flat-vs-flat"
shape = "flat_points"
vertices = [3, 64]
rotate = "axes"
[[family]]
name = "collinear-vs-box"
shape_a = "collinear_points"
shape_b = "box"
vertices_a = [2, 16]
rotate = "axes"
[[family]]
name = "collinear-vs-collinear"
shape = "collinear_points"
vertices = [2, 16]
rotate = "random"
[[family]]
name = "duplicates"
shape = "duplicate_points"
vertices = [4, 32]
[[family]]
name = "point-vs-sphere"
shape_a = "single_point"
shape_b = "sphere_points"
vertices_b = [4, 128]
[[family]]
name = "slivers"
shape = "sliver"
aspect = [10, 1e6]
[[family]]
name = "scale-disparity"
shape = "sphere_points"
vertices = [8, 64]
scale = 1e4
scale_b = 1e-8
[[family]]
name = "large-offsets"
shape = "sphere_points"
vertices = [8, 64]
offset = [1e3, 1e9]
[[family]]
name = "tiny"
shape = "cube_points"
vertices = [8, 64]
scale = 1e-9
[[algorithm]]
name = "gjk-bool"
[[algorithm]]
name = "gjk-johnson"
[[algorithm]]
name = "gjk-johnson-backup"
[[algorithm]]
name = "gjk-sv"
[[algorithm]]
name = "gjk-voronoi"
[[algorithm]]
name = "gjk-nesterov"
[[algorithm]]
name = "epa"
[[algorithm]]
name = "gjk-certified"
)";

/// (family, algorithm, case id) → failure class name.
using Failures = std::map<std::tuple<std::string, std::string, std::uint64_t>, std::string>;

/// The list: one failure a line, "family algorithm case failure  # reason"; '#' lines and blank
/// lines are comments. Every entry must give a reason.
Failures known_failures() {
  const std::string path = std::string(GJKLAB_TESTS_DIR) + "/property/data/known_failures.txt";
  std::ifstream in(path);
  REQUIRE(in.good());
  Failures out;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto hash = line.find('#');
    const std::string body = line.substr(0, hash);
    std::istringstream fields(body);
    std::string family, algorithm, failure;
    std::uint64_t id = 0;
    if (!(fields >> family)) continue;  // a comment or a blank line
    INFO(path << ":" << number << ": " << line);
    REQUIRE((fields >> algorithm >> id >> failure));
    REQUIRE(hash != std::string::npos);  // the reason
    REQUIRE(line.find_first_not_of(" #", hash) != std::string::npos);
    out[{family, algorithm, id}] = failure;
  }
  return out;
}

}  // namespace

TEST_CASE("every gjklab algorithm on the degenerate families: only the listed failures",
          "[property][degenerate]") {
  const ExperimentConfig config = parse_experiment(kExperiment, "degenerate CI families");
  const Failures known = known_failures();
  Failures seen;
  std::map<std::tuple<std::string, std::string, std::uint64_t>, std::string> details;
  std::map<std::string, int> cases_per_family;
  int touching_band = 0;
  for (std::uint64_t id = 0; id < kCases; ++id) {
    const CaseResult r = evaluate_case(config, id);
    const std::string& family = config.families[r.record.family].name;
    ++cases_per_family[family];
    REQUIRE(r.exact.has_value());
    touching_band += r.exact->contact == ContactClass::touching_band;
    for (std::size_t k = 0; k < r.algorithms.size(); ++k) {
      const FailureClass f = r.algorithms[k].failure;
      if (f == FailureClass::none || f == FailureClass::touching_band) continue;
      const AlgorithmRecord& a = r.algorithms[k];
      seen[{family, config.algorithms[k].label, id}] = std::string(to_string(f));
      std::ostringstream d;
      d << "boolean " << (a.boolean_correct ? "right" : "WRONG") << ", error " << a.rel_error
        << " x size";
      details[{family, config.algorithms[k].label, id}] = d.str();
    }
  }
  // GJKLAB_KNOWN_FAILURES_OUT=FILE writes what failed in the list's format, with the measured
  // details as the reason, for a maintainer to review and annotate.
  if (const char* out_path = std::getenv("GJKLAB_KNOWN_FAILURES_OUT")) {
    std::ofstream out(out_path);
    for (const auto& [key, failure] : seen) {
      const auto& [family, algorithm, id] = key;
      out << family << " " << algorithm << " " << id << " " << failure << "  # " << details[key]
          << "\n";
    }
  }
  for (const auto& [key, failure] : seen) {
    const auto& [family, algorithm, id] = key;
    const auto listed = known.find(key);
    if (listed == known.end() || listed->second != failure)
      FAIL_CHECK("new failure: " << family << " " << algorithm << " " << id << " " << failure
                                 << " # " << details[key]
                                 << " (fix it, or list it with its reason)");
  }
  for (const auto& [key, failure] : known) {
    const auto& [family, algorithm, id] = key;
    if (!seen.count(key))
      FAIL_CHECK("listed failure no longer fails: " << family << " " << algorithm << " " << id
                                                    << " " << failure
                                                    << " (remove it from known_failures.txt)");
  }
  // The sample reaches every family and the touching band.
  for (const FamilySpec& f : config.families) {
    INFO(f.name);
    CHECK(cases_per_family[f.name] > 40);
  }
  CHECK(touching_band > 100);
  WARN(seen.size() << " listed failures over " << kCases << " cases × " << config.algorithms.size()
                   << " algorithms; " << touching_band << " pairs in the touching band");
}
