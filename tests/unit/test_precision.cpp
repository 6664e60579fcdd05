// Run-time precision: clouds rounded to float or long double, the `precision` option of the GJK
// queries in experiment files, sweeps, archives, `gjklab query` and `gjklab bench`, and the
// exact answer of the rounded inputs that tells input rounding from the query's own error.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../support/cli_run.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/bench/bench.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/run/driver.hpp"
#include "gjklab/geometry/scalar_cloud.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

using namespace gjklab;
using namespace gjklab::experiment;
using testing::run_cli;
using testing::ScratchDir;

TEST_CASE("ScalarCloud rounds each coordinate to nearest and scans like Polytope",
          "[unit][precision]") {
  const double third = 1.0 / 3.0;
  const std::vector<Vec3> cloud = {Vec3(third, 0, 0), Vec3(0, 1e39, 0), Vec3(0, 0, -2)};
  const ScalarCloud<float> f(cloud);
  CHECK(f.vertices()[0].x() == static_cast<float>(third));
  CHECK(std::isinf(f.vertices()[1].y()));  // beyond float's range: ±∞, a numerical failure
  const ScalarCloud<long double> l(cloud);
  CHECK(l.vertices()[0].x() == static_cast<long double>(third));  // exact
  // The first maximiser on ties, as Polytope's scan.
  const std::vector<Vec3> ties = {Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(1, -1, 0)};
  const ScalarCloud<float> t(ties);
  CHECK(t.support_index(Vec3T<float>(1, 0, 0)) == Polytope(ties).support_index(Vec3(1, 0, 0)));
  CHECK(t.support_index(Vec3T<float>(1, 0, 0)) == 0);
}

TEST_CASE("a pair beyond float's range is a numerical failure in float, never a converged NaN",
          "[unit][precision]") {
  const std::vector<Vec3> a = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  std::vector<Vec3> b;
  for (const Vec3& x : a)
    b.push_back(x + Vec3(1e39, 0, 0));
  const auto r = gjk_distance(ScalarCloud<float>(a), ScalarCloud<float>(b));
  CHECK(r.termination == Termination::numerical_failure);
}

TEST_CASE("precision is an option of the GJK queries, refused by the others with its name",
          "[unit][precision]") {
  for (const char* name : {"gjk-bool", "gjk-johnson", "gjk-johnson-backup", "gjk-sv", "gjk-voronoi",
                           "gjk-nesterov", "gjk-polyak", "epa"}) {
    INFO(name);
    AlgorithmSpec spec{name, name, {}};
    set_option(spec, "precision", "float");
    CHECK(spec.options.precision == ScalarPrecision::single_float);
    set_option(spec, "precision", "long double");
    CHECK(spec.options.precision == ScalarPrecision::long_double);
    // Archived with the other options, and read back.
    const auto described = describe_options(spec);
    CHECK(spec_from_description(name, described).options.precision == ScalarPrecision::long_double);
    CHECK(takes_precision(*find_algorithm(name)));
  }
  AlgorithmSpec johnson{"gjk-johnson", "gjk-johnson", {}};
  CHECK_THROWS_WITH(set_option(johnson, "precision", "half"),
                    Catch::Contains("unknown precision 'half'; valid: float, double, long double"));
  AlgorithmSpec peer{"libccd-gjk", "libccd-gjk", {}};
  CHECK_THROWS_WITH(set_option(peer, "precision", "float"),
                    Catch::Contains("does not apply to libccd-gjk"));
  // Archives written before the option read back as double.
  CHECK(spec_from_description("gjk-johnson", {}).options.precision ==
        ScalarPrecision::double_float);
  // A registry call in float on an algorithm that runs in double only names it.
  AlgorithmOptions options;
  options.precision = ScalarPrecision::single_float;
  const Polytope a({Vec3(0, 0, 0), Vec3(1, 0, 0)}), b({Vec3(3, 0, 0)});
  CHECK_THROWS_WITH(run_algorithm(*find_algorithm("sat"), a, b, {}, options),
                    Catch::Contains("'sat' runs in double only, not in float"));
}

TEST_CASE(
    "a precision sweep: one group per precision, with the exact answer of the rounded "
    "inputs",
    "[unit][precision]") {
  const ExperimentConfig c = parse_experiment(R"(name = "precision"
seed = 5
cases = 30
[placement]
mode = "mixed"
gap = [1e-9, 1e-2]
depth = [1e-9, 1e-2]
[[family]]
shape = "sphere_points"
vertices = [8, 32]
[[algorithm]]
name = "gjk-johnson"
[[algorithm]]
name = "libccd-gjk"
[sweep]
parameter = "precision"
values = ["float", "double", "long double"]
)",
                                              "precision.toml");
  REQUIRE(c.algorithms.size() == 4);
  CHECK(c.algorithms[0].label == "gjk-johnson@precision=float");
  CHECK(c.algorithms[2].label == "gjk-johnson@precision=long,double");
  CHECK(c.algorithms[3].label == "libccd-gjk");
  int float_moved = 0;
  for (std::uint64_t id = 0; id < 30; ++id) {
    const CaseResult r = evaluate_case(c, id);
    const AlgorithmRecord &in_float = r.algorithms[0], &in_double = r.algorithms[1],
                          &in_long = r.algorithms[2];
    // Recorded for the other precisions only: long double's inputs are the case's own.
    REQUIRE(std::isfinite(in_float.rounded_exact_distance));
    CHECK(std::isnan(in_double.rounded_exact_distance));
    CHECK(in_long.rounded_exact_distance == r.exact->distance);
    float_moved += in_float.rounded_exact_distance != r.exact->distance;
    // The float query's own error, against the exact answer of what it was given.
    CHECK(std::abs(in_float.distance - in_float.rounded_exact_distance) <= 1e-5 * r.record.size);
  }
  CHECK(float_moved > 20);  // rounding to float moves nearly every pair's exact distance
}

TEST_CASE("gjklab query --precision float: answers of the GJK queries in float, labelled",
          "[unit][precision]") {
  const std::string tetra = std::string(GJKLAB_TEST_DATA_DIR) + "/tetra.xyz";
  const std::string box = std::string(GJKLAB_TEST_DATA_DIR) + "/box_shifted.off";
  const auto r = run_cli({"query", tetra, box, "--precision", "float"});
  REQUIRE(r.status == 0);
  int lines = 0;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line); ++lines) {
    const auto j = nlohmann::json::parse(line);
    INFO(line);
    CHECK(j["precision"] == "float");  // only the queries that take it answer by default
    CHECK(takes_precision(*find_algorithm(j["algorithm"].get<std::string>())));
  }
  CHECK(lines == 8);
  const auto named = run_cli({"query", tetra, box, "--precision", "float", "--algorithms", "sat"});
  CHECK(named.out.find("runs in double only") != std::string::npos);
  const auto bad = run_cli({"query", tetra, box, "--precision", "half"});
  CHECK(bad.status != 0);
}

TEST_CASE("bench config: precision is read and checked", "[unit][precision]") {
  ScratchDir dir("precision-bench");
  auto write = [&](const std::string& name, const std::string& text) {
    const std::string path = dir.file(name);
    std::ofstream(path) << text;
    return path;
  };
  CHECK(bench::load_bench_config(write("bench_float.toml", "precision = \"float\"\n")).precision ==
        ScalarPrecision::single_float);
  CHECK_THROWS_WITH(bench::load_bench_config(write("bench_half.toml", "precision = \"half\"\n")),
                    Catch::Contains("bench_half.toml:1: key 'precision': must be"));
}
