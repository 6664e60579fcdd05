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
#include "../support/experiment_files.hpp"

using namespace gjklab;
using namespace gjklab::experiment;
using Catch::Contains;
using namespace gjklab::testing;

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
