// Experiment files over a base file: tables merged, arrays replaced, relative paths resolved
// against each file's own folder, and the errors of base and exclude_families.
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

