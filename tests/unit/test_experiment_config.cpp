// Experiment files: a full file parses to the expected values, defaults apply, and every kind of
// mistake is reported with the file, the line and the key (and the valid choices).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/families.hpp"

using namespace gjklab;
using namespace gjklab::experiment;
using Catch::Contains;

namespace {

ExperimentConfig parse(const std::string& text) {
  return parse_experiment(text, "exp.toml");
}

// A minimal valid file; tests append or replace lines to make one mistake at a time.
const std::string kHead = R"(name = "t"
seed = 1
cases = 10
)";
const std::string kFamily = R"(
[[family]]
shape = "sphere_points"
)";
const std::string kAlgorithm = R"(
[[algorithm]]
name = "gjk-johnson"
)";

std::map<std::string, std::string> as_map(
    const std::vector<std::pair<std::string, std::string>>& v) {
  return {v.begin(), v.end()};
}

}  // namespace

TEST_CASE("a full experiment file parses to the values it states", "[unit][config]") {
  const std::string text = R"(# every key, once
name = "full"
seed = 12345
cases = 2500
threads = 3
output = "out/full.h5"
touching_band = 2.5e-11

[oracle]
enabled = true
depth = true

[timing]
enabled = true
repetitions = 7

[placement]
mode = "separated"
gap = [1e-4, 0.5]
depth = [1e-5, 0.25]
overlapping_fraction = 0.3
spread = 2

[[family]]
name = "clouds"
shape = "sphere_points"
vertices = [4, 256]
scale = 1e3
rotate = false
weight = 3

[family.placement]
mode = "mixed"
depth = 0.125

[[family]]
shape_a = "box"
shape_b = "uv_sphere"
vertices_b = 200

[[family]]
shape = "cylinder"
vertices_a = 12
vertices_b = [6, 40]

[[algorithm]]
name = "gjk-bool"
max_iterations = 40

[[algorithm]]
name = "gjk-johnson"
max_iterations = 300
relative_gap = 1e-10
absolute_gap_squared = 0
relative_contact = 3e-14

[[algorithm]]
name = "libccd-mpr"
mpr_tolerance = 1e-6
)";
  const ExperimentConfig c = parse(text);
  CHECK(c.source == "exp.toml");
  CHECK(c.text == text);
  CHECK(c.name == "full");
  CHECK(c.seed == 12345);
  CHECK(c.cases == 2500);
  CHECK(c.threads == 3);
  CHECK(c.output == "out/full.h5");
  CHECK(c.touching_band == 2.5e-11);
  CHECK(c.oracle);
  CHECK(c.depth);
  CHECK(c.timing);
  CHECK(c.repetitions == 7);

  REQUIRE(c.families.size() == 3);
  const FamilySpec& f0 = c.families[0];
  CHECK(f0.name == "clouds");
  CHECK(f0.shape_a == ShapeKind::sphere_points);
  CHECK(f0.shape_b == ShapeKind::sphere_points);
  CHECK(f0.vertices_a.lo == 4);
  CHECK(f0.vertices_a.hi == 256);
  CHECK(f0.vertices_b.lo == 4);
  CHECK(f0.vertices_b.hi == 256);
  CHECK(f0.scale == 1e3);
  CHECK(f0.rotation == Rotation::none);
  CHECK(f0.weight == 3);
  // [family.placement] overrides mode and depth; the rest comes from [placement].
  CHECK(f0.placement.mode == PlacementMode::mixed);
  CHECK(f0.placement.depth.lo == 0.125);
  CHECK(f0.placement.depth.hi == 0.125);
  CHECK(f0.placement.gap.lo == 1e-4);
  CHECK(f0.placement.gap.hi == 0.5);
  CHECK(f0.placement.overlapping_fraction == 0.3);
  CHECK(f0.placement.spread == 2);

  const FamilySpec& f1 = c.families[1];
  CHECK(f1.name == "box/uv_sphere");
  CHECK(f1.shape_a == ShapeKind::box);
  CHECK(f1.shape_b == ShapeKind::uv_sphere);
  CHECK(f1.vertices_a.lo == 8);  // the box's own count
  CHECK(f1.vertices_b.lo == 200);
  CHECK(f1.vertices_b.hi == 200);
  CHECK(f1.scale == 1);
  CHECK(f1.rotation == Rotation::random);
  CHECK(f1.weight == 1);
  CHECK(f1.placement.mode == PlacementMode::separated);
  CHECK(f1.placement.depth.lo == 1e-5);
  CHECK(f1.placement.spread == 2);

  const FamilySpec& f2 = c.families[2];
  CHECK(f2.name == "cylinder");
  CHECK(f2.vertices_a.lo == 12);
  CHECK(f2.vertices_a.hi == 12);
  CHECK(f2.vertices_b.lo == 6);
  CHECK(f2.vertices_b.hi == 40);

  REQUIRE(c.algorithms.size() == 3);
  CHECK(c.algorithms[0].name == "gjk-bool");
  CHECK(c.algorithms[0].options.gjk_boolean.max_iterations == 40);
  CHECK(c.algorithms[1].name == "gjk-johnson");
  CHECK(c.algorithms[1].options.gjk_distance.max_iterations == 300);
  CHECK(c.algorithms[1].options.gjk_distance.relative_gap == 1e-10);
  CHECK(c.algorithms[1].options.gjk_distance.absolute_gap_squared == 0);
  CHECK(c.algorithms[1].options.gjk_distance.relative_contact == 3e-14);
  CHECK(c.algorithms[2].name == "libccd-mpr");
  CHECK(c.algorithms[2].options.libccd.mpr_tolerance == 1e-6);
  CHECK(c.algorithms[2].options.libccd.max_iterations == peers::LibccdDefaults::max_iterations);
  CHECK(c.algorithms[2].options.oracle.depth);
}

TEST_CASE("omitted keys take their documented defaults", "[unit][config]") {
  const ExperimentConfig c = parse(kHead + kFamily + kAlgorithm);
  CHECK(c.threads == 1);
  CHECK(c.output == "results/t.h5");
  CHECK(c.touching_band == 1e-10);
  CHECK(c.oracle);
  CHECK_FALSE(c.depth);
  CHECK_FALSE(c.timing);
  CHECK(c.repetitions == 5);
  REQUIRE(c.families.size() == 1);
  const FamilySpec& f = c.families[0];
  CHECK(f.name == "sphere_points");
  CHECK(f.vertices_a.lo == 32);
  CHECK(f.vertices_a.hi == 32);
  CHECK(f.scale == 1);
  CHECK(f.rotation == Rotation::random);
  CHECK(f.weight == 1);
  const PlacementSpec defaults;
  CHECK(f.placement.mode == defaults.mode);
  CHECK(f.placement.gap.lo == defaults.gap.lo);
  CHECK(f.placement.gap.hi == defaults.gap.hi);
  CHECK(f.placement.depth.hi == defaults.depth.hi);
  CHECK(f.placement.overlapping_fraction == defaults.overlapping_fraction);
  CHECK(f.placement.spread == defaults.spread);
  REQUIRE(c.algorithms.size() == 1);
  CHECK(c.algorithms[0].options.gjk_distance.relative_gap == GjkDistanceDefaults::relative_gap);
  CHECK(c.algorithms[0].options.gjk_distance.max_iterations == GjkDistanceDefaults::max_iterations);

  // The demo shapes default to their own vertex counts.
  const ExperimentConfig d = parse(kHead + R"(
[[family]]
shape = "cone"
[[family]]
shape = "cylinder"
[[family]]
shape = "uv_sphere"
[[family]]
shape = "box"
)" + kAlgorithm);
  REQUIRE(d.families.size() == 4);
  CHECK(d.families[0].vertices_a.lo == 33);
  CHECK(d.families[1].vertices_a.lo == 64);
  CHECK(d.families[2].vertices_b.hi == 482);
  CHECK(d.families[3].vertices_a.lo == 8);
}

TEST_CASE("unknown keys are reported with file, line and dotted key path", "[unit][config]") {
  CHECK_THROWS_AS(parse(kHead + "colour = 3\n" + kFamily + kAlgorithm), ConfigError);
  CHECK_THROWS_WITH(parse(kHead + "colour = 3\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:4:") && Contains("key 'colour'") &&
                        Contains("unknown key") && Contains("valid: name, seed, cases"));
  // In [[family]]: line 7 (kHead is 3 lines, kFamily starts with a blank line).
  CHECK_THROWS_WITH(parse(kHead + kFamily + "vertex = 12\n" + kAlgorithm),
                    Contains("exp.toml:7:") && Contains("key 'family[0].vertex'") &&
                        Contains("unknown key") && Contains("vertices"));
  // In a family's placement sub-table.
  CHECK_THROWS_WITH(
      parse(kHead + kFamily + kFamily + "[family.placement]\nwidth = 1\n" + kAlgorithm),
      Contains("exp.toml:11:") && Contains("key 'family[1].placement.width'"));
  CHECK_THROWS_WITH(parse(kHead + "[oracle]\nenable = true\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:5:") && Contains("key 'oracle.enable'") &&
                        Contains("valid: enabled, depth"));
  // A key of another algorithm names the algorithms it belongs to.
  CHECK_THROWS_WITH(parse(kHead + kFamily + kAlgorithm + "mpr_tolerance = 1e-5\n"),
                    Contains("exp.toml:10:") && Contains("key 'algorithm[0].mpr_tolerance'") &&
                        Contains("applies to libccd-gjk, libccd-mpr") &&
                        Contains("not to gjk-johnson"));
  CHECK_THROWS_WITH(
      parse(kHead + kFamily + "\n[[algorithm]]\nname = \"gjk-bool\"\nrelative_gap = 1e-9\n"),
      Contains("exp.toml:10:") && Contains("key 'algorithm[0].relative_gap'") &&
          Contains("applies to gjk-johnson"));
}

TEST_CASE("values of the wrong type are reported", "[unit][config]") {
  CHECK_THROWS_WITH(parse("name = \"t\"\nseed = \"one\"\ncases = 10\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:2:") && Contains("key 'seed'") &&
                        Contains("expected an integer, got a string"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + "rotate = 1\n" + kAlgorithm),
                    Contains("exp.toml:7:") && Contains("key 'family[0].rotate'") &&
                        Contains("expected true, false"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + "vertices = [4, 8.5]\n" + kAlgorithm),
                    Contains("exp.toml:7:") && Contains("key 'family[0].vertices'") &&
                        Contains("expected an integer, got a float"));
  CHECK_THROWS_WITH(
      parse(kHead + "placement = 3\n" + kFamily + kAlgorithm),
      Contains("exp.toml:4:") && Contains("key 'placement'") && Contains("expected a table"));
  CHECK_THROWS_WITH(parse(kHead + "[family]\nshape = \"box\"\n" + kAlgorithm),
                    Contains("exp.toml:4:") && Contains("key 'family'") &&
                        Contains("expected an array of tables ([[family]])"));
  CHECK_THROWS_WITH(parse(kHead + "[placement]\ngap = \"wide\"\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:5:") && Contains("key 'placement.gap'") &&
                        Contains("expected a number or [lo, hi]"));
}

TEST_CASE("out-of-range values are reported", "[unit][config]") {
  CHECK_THROWS_WITH(
      parse("name = \"t\"\nseed = 1\ncases = 0\n" + kFamily + kAlgorithm),
      Contains("exp.toml:3:") && Contains("key 'cases'") && Contains("must be between 1 and"));
  CHECK_THROWS_WITH(
      parse("name = \"t\"\nseed = -4\ncases = 3\n" + kFamily + kAlgorithm),
      Contains("exp.toml:2:") && Contains("key 'seed'") && Contains("must be at least 0"));
  CHECK_THROWS_WITH(parse(kHead + "threads = 0\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:4:") && Contains("key 'threads'"));
  CHECK_THROWS_WITH(
      parse(kHead + "touching_band = 0.0\n" + kFamily + kAlgorithm),
      Contains("exp.toml:4:") && Contains("key 'touching_band'") && Contains("must be > 0"));
  CHECK_THROWS_WITH(parse(kHead + "touching_band = nan\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:4:") && Contains("must be finite"));
  CHECK_THROWS_WITH(parse(kHead + "[timing]\nrepetitions = 0\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:5:") && Contains("key 'timing.repetitions'"));
  CHECK_THROWS_WITH(parse(kHead + "[placement]\ngap = [0.5, 0.1]\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:5:") && Contains("key 'placement.gap'") &&
                        Contains("exceeds upper bound"));
  CHECK_THROWS_WITH(
      parse(kHead + "[placement]\noverlapping_fraction = 1.5\n" + kFamily + kAlgorithm),
      Contains("exp.toml:5:") && Contains("key 'placement.overlapping_fraction'") &&
          Contains("between 0 and 1"));
  CHECK_THROWS_WITH(
      parse(kHead + kFamily + "weight = -1\n" + kAlgorithm),
      Contains("exp.toml:7:") && Contains("key 'family[0].weight'") && Contains("must be > 0"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + "vertices = 0\n" + kAlgorithm),
                    Contains("exp.toml:7:") && Contains("key 'family[0].vertices'"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + "\n[family.placement]\ngap = [0, 1]\n" + kAlgorithm),
                    Contains("exp.toml:9:") && Contains("key 'family[0].placement.gap'") &&
                        Contains("lower bound must be > 0"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + kAlgorithm + "max_iterations = 0\n"),
                    Contains("exp.toml:10:") && Contains("key 'algorithm[0].max_iterations'"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + kAlgorithm + "relative_gap = -1e-3\n"),
                    Contains("exp.toml:10:") && Contains("key 'algorithm[0].relative_gap'") &&
                        Contains("must be >= 0"));
  CHECK_THROWS_WITH(
      parse(kHead + kFamily + "\n[[algorithm]]\nname = \"libccd-gjk\"\nmpr_tolerance = 0\n"),
      Contains("exp.toml:10:") && Contains("key 'algorithm[0].mpr_tolerance'"));
}

TEST_CASE("unknown names list the valid choices", "[unit][config]") {
  CHECK_THROWS_WITH(parse(kHead + "\n[[family]]\nshape = \"torus\"\n" + kAlgorithm),
                    Contains("exp.toml:6:") && Contains("key 'family[0].shape'") &&
                        Contains("unknown shape 'torus'; valid: sphere_points, ball_points, "
                                 "cube_points, gaussian, box, cone, cylinder, uv_sphere"));
  CHECK_THROWS_WITH(
      parse(kHead + "\n[[family]]\nshape_a = \"box\"\nshape_b = \"blob\"\n" + kAlgorithm),
      Contains("exp.toml:7:") && Contains("key 'family[0].shape_b'") &&
          Contains("unknown shape 'blob'"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + "\n[[algorithm]]\nname = \"gjk-foo\"\n"),
                    Contains("exp.toml:9:") && Contains("key 'algorithm[0].name'") &&
                        Contains("unknown algorithm 'gjk-foo'; valid: gjk-bool, gjk-johnson, "
                                 "libccd-gjk, libccd-mpr"));
  CHECK_THROWS_WITH(parse(kHead + "[placement]\nmode = \"sideways\"\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:5:") && Contains("key 'placement.mode'") &&
                        Contains("valid: separated, overlapping, mixed, random, touching"));
  // Exact contact needs a contact family.
  CHECK_THROWS_WITH(
      parse(kHead + "[placement]\nmode = \"touching\"\n" + kFamily + kAlgorithm),
      Contains("key 'family[0].placement.mode'") && Contains("needs an exact contact family"));
}

TEST_CASE("'exact' as an algorithm is refused with an explanation", "[unit][config]") {
  CHECK_THROWS_WITH(parse(kHead + kFamily + kAlgorithm + "\n[[algorithm]]\nname = \"exact\"\n"),
                    Contains("exp.toml:12:") && Contains("key 'algorithm[1].name'") &&
                        Contains("[oracle]") &&
                        Contains("valid: gjk-bool, gjk-johnson, libccd-gjk, libccd-mpr"));
}

TEST_CASE("missing required keys are reported at their table", "[unit][config]") {
  CHECK_THROWS_WITH(parse("seed = 1\ncases = 10\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:1:") && Contains("key 'name'") && Contains("missing"));
  CHECK_THROWS_WITH(parse("name = \"t\"\ncases = 10\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:1:") && Contains("key 'seed'") && Contains("missing"));
  CHECK_THROWS_WITH(parse("name = \"t\"\nseed = 1\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:1:") && Contains("key 'cases'") && Contains("missing"));
  CHECK_THROWS_WITH(parse(kHead + kAlgorithm), Contains("exp.toml:1:") &&
                                                   Contains("key 'family'") &&
                                                   Contains("at least one [[family]]"));
  CHECK_THROWS_WITH(parse(kHead + kFamily), Contains("exp.toml:1:") &&
                                                Contains("key 'algorithm'") &&
                                                Contains("at least one [[algorithm]]"));
  // Inside an array-of-tables element: the line of its [[header]].
  CHECK_THROWS_WITH(parse(kHead + kFamily + "\n[[algorithm]]\nmax_iterations = 5\n"),
                    Contains("exp.toml:8:") && Contains("key 'algorithm[0].name'") &&
                        Contains("missing") && Contains("valid: gjk-bool"));
  CHECK_THROWS_WITH(
      parse(kHead + "\n[[family]]\nvertices = 5\n" + kAlgorithm),
      Contains("exp.toml:5:") && Contains("key 'family[0].shape'") && Contains("missing"));
  CHECK_THROWS_WITH(parse(kHead + "\n[[family]]\nshape_a = \"box\"\n" + kAlgorithm),
                    Contains("exp.toml:5:") && Contains("key 'family[0].shape_b'"));
}

TEST_CASE("TOML syntax errors carry the file and line", "[unit][config]") {
  CHECK_THROWS_WITH(parse(kHead + "threads = [1,\n 2,,]\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:5:") && Contains("TOML syntax error"));
  CHECK_THROWS_WITH(parse(kHead + "seed = 2\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:4:") && Contains("TOML syntax error"));
}

TEST_CASE("contradictions and duplicates are reported", "[unit][config]") {
  CHECK_THROWS_WITH(parse(kHead + kFamily + "shape_a = \"box\"\n" + kAlgorithm),
                    Contains("exp.toml:7:") && Contains("key 'family[0].shape_a'") &&
                        Contains("cannot be combined with 'shape'"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + "vertices = 4\nvertices_b = 5\n" + kAlgorithm),
                    Contains("exp.toml:8:") && Contains("key 'family[0].vertices_b'"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + kFamily + kAlgorithm),
                    Contains("exp.toml:8:") && Contains("key 'family[1].name'") &&
                        Contains("already used by family[0]"));
  CHECK_THROWS_WITH(parse(kHead + kFamily + kAlgorithm + kAlgorithm),
                    Contains("exp.toml:12:") && Contains("key 'algorithm[1].name'") &&
                        Contains("already used by algorithm[0]"));
  CHECK_THROWS_WITH(
      parse(kHead + "[oracle]\nenabled = false\ndepth = true\n" + kFamily + kAlgorithm),
      Contains("exp.toml:6:") && Contains("key 'oracle.depth'"));
  CHECK_THROWS_WITH(parse("name = \"../x\"\nseed = 1\ncases = 1\n" + kFamily + kAlgorithm),
                    Contains("exp.toml:1:") && Contains("key 'name'"));
  // Two families with the same shape are fine once named.
  const ExperimentConfig c =
      parse(kHead + kFamily + "name = \"small\"\n" + kFamily + "name = \"large\"\n" + kAlgorithm);
  CHECK(c.families.size() == 2);
}

TEST_CASE("load_experiment reads files and reports unreadable ones", "[unit][config]") {
  CHECK_THROWS_WITH(load_experiment("/nonexistent/dir/x.toml"),
                    Catch::Equals("/nonexistent/dir/x.toml: cannot read"));
  CHECK_THROWS_WITH(load_experiment(GJKLAB_TEST_DATA_DIR), Contains(": cannot read"));

  const std::filesystem::path quickstart = std::filesystem::path(GJKLAB_TEST_DATA_DIR) / ".." /
                                           ".." / "experiments" / "studies" / "quickstart.toml";
  const ExperimentConfig c = load_experiment(quickstart);
  CHECK(c.name == "quickstart");
  CHECK(c.source == quickstart.string());
  CHECK(c.output == "results/quickstart.h5");
  CHECK(c.threads == 2);
  CHECK(c.oracle);
  CHECK_FALSE(c.depth);
  CHECK_FALSE(c.timing);
  CHECK(c.cases >= 1000);
  CHECK(c.families.size() >= 7);
  // Every GJK variant and the libccd booleans (the optional FCL/Bullet peers are left out so
  // that the quickstart runs on any build; depth algorithms have their own study).
  REQUIRE(c.algorithms.size() == 8);
  for (const auto& a : c.algorithms)
    CHECK(find_algorithm(a.name) != nullptr);
  CHECK(c.algorithms[0].name == "gjk-bool");
  CHECK(c.algorithms[1].name == "gjk-johnson");
  CHECK(c.algorithms[2].name == "libccd-gjk");
  CHECK(c.algorithms[3].name == "libccd-mpr");
  CHECK(c.text.find("[[family]]") != std::string::npos);
}

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

namespace {

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

}  // namespace

TEST_CASE("base: an experiment over another, tables merged and arrays replaced", "[unit][config]") {
  ExperimentFolder dir("base");
  dir.write("base.toml", R"(name = "base"
seed = 7
cases = 20
threads = 2
touching_band = 1e-9
[oracle]
enabled = true
depth = false
[placement]
mode = "separated"
gap = [0.1, 0.3]
[[family]]
shape = "box"
[[family]]
name = "far"
shape = "cube_points"
vertices = 12
[[algorithm]]
name = "gjk-bool"
)");
  const auto derived = dir.write("derived.toml", R"(base = "base.toml"
name = "derived"
exclude_families = ["far"]
[oracle]
depth = true
[[algorithm]]
name = "epa"
[[algorithm]]
name = "gjk-sv"
)");
  const ExperimentConfig c = load_experiment(derived);
  CHECK(c.name == "derived");
  CHECK(c.seed == 7);  // from the base
  CHECK(c.touching_band == 1e-9);
  CHECK(c.oracle);  // [oracle] merged key by key
  CHECK(c.depth);
  REQUIRE(c.families.size() == 1);  // "far" excluded
  CHECK(c.families[0].name == "box");
  CHECK(c.families[0].placement.gap.lo == 0.1);
  REQUIRE(c.algorithms.size() == 2);  // [[algorithm]] replaced whole
  CHECK(c.algorithms[0].name == "epa");

  // The archived text is the merged experiment, which reads back alone to the same cases.
  CHECK(c.text.find("base =") == std::string::npos);
  const ExperimentConfig again = parse_experiment(c.text, "archived");
  CHECK(again.name == "derived");
  CHECK(again.families.size() == 1);
  CHECK(again.algorithms.size() == 2);
  CHECK(again.depth);
  for (std::uint64_t id : {0, 5, 19}) {
    const GeneratedCase x = generate_case(c, id), y = generate_case(again, id);
    CHECK(x.a == y.a);
    CHECK(x.b == y.b);
    CHECK(x.record.intended_gap == y.record.intended_gap);
  }
}

TEST_CASE("base: a base's relative mesh and case-file paths resolve against its own folder",
          "[unit][config]") {
  ExperimentFolder dir("base-paths");
  std::filesystem::create_directories(dir.path / "studies" / "meshes");
  std::filesystem::copy_file(std::filesystem::path(GJKLAB_TEST_DATA_DIR) / "box_shifted.off",
                             dir.path / "studies" / "meshes" / "box_shifted.off");
  dir.write("studies/base.toml", R"(name = "base"
seed = 3
cases = 4
[[family]]
name = "meshes"
shape = "mesh"
path = "meshes"
[[algorithm]]
name = "gjk-johnson"
)");
  std::filesystem::create_directories(dir.path / "elsewhere");
  const auto derived = dir.write("elsewhere/derived.toml", R"(base = "../studies/base.toml"
name = "derived"
)");
  const ExperimentConfig c = load_experiment(derived);  // failed: "meshes: no such folder"
  REQUIRE(c.families.size() == 1);
  CHECK(generate_case(c, 0).a.size() == 8);  // the box's vertices
  // The archived text names the folder relative to the derived file, and reads back from there.
  CHECK(c.text.find("../studies/meshes") != std::string::npos);
}

TEST_CASE("base and exclude_families errors name the file, line and key", "[unit][config]") {
  ExperimentFolder dir("base-errors");
  dir.write("base.toml",
            "name = \"b\"\nseed = 1\ncases = 3\n[[family]]\nshape = \"box\"\n"
            "[[algorithm]]\nname = \"gjk-bool\"\nbogus = 1\n");
  const auto bad_in_base = dir.write("d1.toml", "base = \"base.toml\"\n");
  CHECK_THROWS_WITH(load_experiment(bad_in_base), Contains("base.toml:8") && Contains("bogus"));
  const auto missing = dir.write("d2.toml", "base = \"nope.toml\"\n");
  CHECK_THROWS_WITH(load_experiment(missing),
                    Contains("d2.toml:1") && Contains("cannot read the base experiment"));
  const auto cycle = dir.write("d3.toml", "base = \"d3.toml\"\n");
  CHECK_THROWS_WITH(load_experiment(cycle), Contains("a cycle?"));
  CHECK_THROWS_WITH(parse(kHead + "exclude_families = [\"boxes\"]\n" + kFamily + kAlgorithm),
                    Contains("no family 'boxes'") && Contains("sphere_points"));
  CHECK_THROWS_WITH(
      parse(kHead + "exclude_families = [\"sphere_points\"]\n" + kFamily + kAlgorithm),
      Contains("excludes every family"));
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
