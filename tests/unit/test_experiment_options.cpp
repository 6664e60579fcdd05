// Algorithms' options in experiment files: each algorithm's own keys, described and read
// back, the GJK variants' convergence criteria and start, depth algorithms, placement and
// trace modes.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "../support/experiment_files.hpp"

using namespace gjklab;
using namespace gjklab::experiment;
using Catch::Contains;
using namespace gjklab::testing;

TEST_CASE("describe_options lists each algorithm's own options, round-trippable",
          "[unit][config]") {
  const ExperimentConfig c = parse(kHead + kFamily + R"(
[[algorithm]]
name = "gjk-bool"
max_iterations = 17
[[algorithm]]
name = "gjk-johnson"
relative_gap = 0.1
[[algorithm]]
name = "libccd-gjk"
mpr_tolerance = 3.3e-7
)");
  REQUIRE(c.algorithms.size() == 3);
  const auto bool_options = as_map(describe_options(c.algorithms[0]));
  CHECK(bool_options == std::map<std::string, std::string>{{"max_iterations", "17"},
                                                           {"start", "centre_point"},
                                                           {"initial_direction", "1 0 0"},
                                                           {"recenter", "true"},
                                                           {"precision", "double"}});

  const auto johnson = as_map(describe_options(c.algorithms[1]));
  CHECK(johnson.size() == 11);
  CHECK(johnson.at("recenter") == "true");
  CHECK(johnson.at("warm_start") == "false");
  CHECK(johnson.at("precision") == "double");
  CHECK(johnson.at("max_iterations") == std::to_string(GjkDistanceDefaults::max_iterations));
  CHECK(johnson.at("convergence") == "relative");
  CHECK(std::stod(johnson.at("relative_gap")) == 0.1);
  CHECK(std::stod(johnson.at("relative_contact")) == GjkDistanceDefaults::relative_contact);
  CHECK(std::stod(johnson.at("absolute_gap_squared")) == 0.0);
  CHECK(std::stod(johnson.at("duality_gap_tolerance")) == 0.0);

  const auto ccd = as_map(describe_options(c.algorithms[2]));
  CHECK(ccd.size() == 2);
  CHECK(ccd.at("max_iterations") == std::to_string(peers::LibccdDefaults::max_iterations));
  CHECK(std::stod(ccd.at("mpr_tolerance")) == 3.3e-7);

  // The archived text rebuilds the same options.
  for (const AlgorithmSpec& spec : c.algorithms) {
    const AlgorithmSpec back = spec_from_description(spec.name, describe_options(spec));
    CHECK(describe_options(back) == describe_options(spec));
  }
  CHECK(ccd.count("relative_gap") == 0);
}

TEST_CASE("gjk-bool start: parsed, described, and fixed for archives that predate it",
          "[unit][config]") {
  const ExperimentConfig c = parse(kHead + kFamily + R"(
[[algorithm]]
name = "gjk-bool"
label = "fixed"
start = "fixed_direction"
[[algorithm]]
name = "gjk-bool"
label = "centre"
start = "centre_direction"
[[algorithm]]
name = "gjk-bool"
)");
  REQUIRE(c.algorithms.size() == 3);
  CHECK(c.algorithms[0].options.gjk_boolean.start == GjkBooleanStart::fixed_direction);
  CHECK(c.algorithms[1].options.gjk_boolean.start == GjkBooleanStart::centre_direction);
  CHECK(c.algorithms[2].options.gjk_boolean.start == GjkBooleanDefaults::start);
  for (const AlgorithmSpec& spec : c.algorithms) {
    const AlgorithmSpec back = spec_from_description(spec.name, describe_options(spec));
    CHECK(back.options.gjk_boolean.start == spec.options.gjk_boolean.start);
  }
  // An archive without the key was written by the fixed start, the only one there was.
  const AlgorithmSpec old = spec_from_description("gjk-bool", {{"max_iterations", "64"}});
  CHECK(old.options.gjk_boolean.start == GjkBooleanStart::fixed_direction);
  CHECK_THROWS_WITH(
      parse(kHead + kFamily + "\n[[algorithm]]\nname = \"gjk-bool\"\nstart = \"origin\"\n"),
      Contains("key 'algorithm[0].start'") &&
          Contains("unknown start 'origin'; valid: fixed_direction, centre_direction, "
                   "centre_point"));
}

TEST_CASE("GJK distance variants: options, convergence criteria and their errors",
          "[unit][config]") {
  const ExperimentConfig c = parse(kHead + kFamily + R"(
[[algorithm]]
name = "gjk-sv"
convergence = "duality_gap"
duality_gap_tolerance = 1e-20
max_iterations = 40
[[algorithm]]
name = "gjk-nesterov"
convergence = "absolute"
absolute_gap_squared = 1e-18
normalize_direction = true
[[algorithm]]
name = "gjk-voronoi"
[[algorithm]]
name = "gjk-johnson-backup"
relative_gap = 1e-9
)");
  REQUIRE(c.algorithms.size() == 4);
  const GjkDistanceOptions& sv = c.algorithms[0].options.gjk_distance;
  CHECK(sv.convergence == GjkConvergence::duality_gap);
  CHECK(sv.duality_gap_tolerance == 1e-20);
  CHECK(sv.max_iterations == 40);
  const GjkNesterovOptions& nesterov = c.algorithms[1].options.gjk_nesterov;
  CHECK(nesterov.convergence == GjkConvergence::absolute);
  CHECK(nesterov.absolute_gap_squared == 1e-18);
  CHECK(nesterov.normalize_direction);
  CHECK(nesterov.max_iterations == GjkDistanceDefaults::max_iterations);
  CHECK(c.algorithms[2].options.gjk_distance.convergence == GjkConvergence::relative);
  CHECK(c.algorithms[3].options.gjk_distance.relative_gap == 1e-9);

  const auto described = as_map(describe_options(c.algorithms[1]));
  CHECK(described.at("convergence") == "absolute");
  CHECK(described.at("normalize_direction") == "true");
  CHECK(std::stod(described.at("absolute_gap_squared")) == 1e-18);
  CHECK(as_map(describe_options(c.algorithms[0])).at("convergence") == "duality_gap");

  CHECK_THROWS_WITH(
      parse(kHead + kFamily + "\n[[algorithm]]\nname = \"gjk-sv\"\nconvergence = \"hybrid\"\n"),
      Contains("exp.toml:10:") && Contains("key 'algorithm[0].convergence'") &&
          Contains("unknown criterion 'hybrid'; valid: relative, absolute, duality_gap"));
  CHECK_THROWS_WITH(parse(kHead + kFamily +
                          "\n[[algorithm]]\nname = \"gjk-voronoi\"\nnormalize_direction = false\n"),
                    Contains("exp.toml:10:") &&
                        Contains("key 'algorithm[0].normalize_direction'") &&
                        Contains("applies to gjk-nesterov, not to gjk-voronoi"));
}

TEST_CASE("depth algorithms take their options from the experiment file", "[unit][config]") {
  const ExperimentConfig c = parse(kHead + kFamily + R"(
[[algorithm]]
name = "sat"
early_exit = false
[[algorithm]]
name = "epa"
max_iterations = 77
max_faces = 300
[[algorithm]]
name = "libccd-gjk-epa"
max_depth_iterations = 9
)");
  REQUIRE(c.algorithms.size() == 3);
  CHECK_FALSE(c.algorithms[0].options.sat.early_exit);
  CHECK(c.algorithms[1].options.epa.max_iterations == 77);
  CHECK(c.algorithms[1].options.epa.max_faces == 300);
  CHECK(c.algorithms[2].options.libccd.max_depth_iterations == 9);
  for (const AlgorithmSpec& spec : c.algorithms) {
    const AlgorithmSpec back = spec_from_description(spec.name, describe_options(spec));
    CHECK(describe_options(back) == describe_options(spec));
  }
#ifdef GJKLAB_HAVE_FCL
  const ExperimentConfig f = parse(kHead + kFamily +
                                   "[[algorithm]]\nname = \"fcl-indep\"\n"
                                   "epa_max_faces = 64\n");
  CHECK(f.algorithms[0].options.fcl.epa_max_faces == 64);
#endif
  CHECK_THROWS_WITH(
      parse(kHead + kFamily + "[[algorithm]]\nname = \"sat\"\nearly_exit = 3\n"),
      Contains("key 'algorithm[0].early_exit'") && Contains("expected true or false"));
}

TEST_CASE("GJK distance start: key, default, archived text and errors", "[unit][config]") {
  const ExperimentConfig c = parse(kHead + kFamily + R"(
[[algorithm]]
name = "gjk-sv"
start = "fixed_direction"
[[algorithm]]
name = "gjk-johnson"
[[algorithm]]
name = "epa"
gjk_start = "fixed_direction"
)");
  CHECK(c.algorithms[0].options.gjk_distance.start == GjkDistanceStart::fixed_direction);
  CHECK(c.algorithms[1].options.gjk_distance.start == GjkDistanceStart::centre_direction);
  CHECK(c.algorithms[2].options.gjk_distance.start == GjkDistanceStart::fixed_direction);
  CHECK(as_map(describe_options(c.algorithms[1])).at("start") == "centre_direction");
  // An archive written before the key existed ran (and replays) the fixed direction.
  const AlgorithmSpec old = spec_from_description("gjk-johnson", {{"max_iterations", "128"}});
  CHECK(old.options.gjk_distance.start == GjkDistanceStart::fixed_direction);
  CHECK_THROWS_WITH(parse(kHead + kFamily +
                          "[[algorithm]]\nname = \"gjk-johnson\"\n"
                          "start = \"sideways\"\n"),
                    Contains("exp.toml:") && Contains("unknown start 'sideways'") &&
                        Contains("centre_direction"));
}

TEST_CASE("placement and trace modes are read by their names", "[unit][config]") {
  for (const PlacementMode mode : values_of(kPlacementModeNames)) {
    if (mode == PlacementMode::touching) continue;  // needs a contact family
    const std::string text = kHead + "[placement]\nmode = \"" + std::string(to_string(mode)) +
                             "\"\n" + kFamily + kAlgorithm;
    CHECK(parse(text).families.at(0).placement.mode == mode);
  }
  for (const TraceMode mode : values_of(kTraceModeNames)) {
    const std::string text = kHead + kFamily + kAlgorithm + "\n[trace]\nmode = \"" +
                             std::string(to_string(mode)) + "\"\n";
    CHECK(parse(text).trace == mode);
  }
  CHECK(parse(kHead + kFamily + kAlgorithm).trace == TraceMode::none);
  CHECK_THROWS_WITH(parse(kHead + kFamily + kAlgorithm + "\n[trace]\nmode = \"some\"\n"),
                    Contains("key 'trace.mode'") &&
                        Contains("unknown trace mode 'some'; valid: none, failing, all"));
}
