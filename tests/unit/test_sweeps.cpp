// Sweeps: an algorithm option swept over values gives each value its own result group, with
// the value applied; a geometry sweep reruns each base pair moved or scaled, as its own family.
#include <catch2/catch.hpp>

#include <string>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/run/driver.hpp"
#include "gjklab/experiment/cases/families.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

namespace {

constexpr const char* kPairs = R"(name = "sweep"
seed = 11
cases = 40
[placement]
mode = "mixed"
gap = [1e-3, 0.5]
depth = [1e-3, 0.5]
[[family]]
shape = "sphere_points"
vertices = [16, 64]
)";

}  // namespace

TEST_CASE("sweep of max_iterations: one group per value, each with its value applied",
          "[unit][sweep]") {
  const ExperimentConfig c = parse_experiment(std::string(kPairs) + R"(
[[algorithm]]
name = "gjk-johnson"
[[algorithm]]
name = "gjk-certified"
[sweep]
parameter = "max_iterations"
values = [1, 3, 128]
)",
                                              "sweep.toml");
  // gjk-certified takes no iteration bound: it runs once, under its own name.
  REQUIRE(c.algorithms.size() == 4);
  CHECK(c.algorithms[0].label == "gjk-johnson@max_iterations=1");
  CHECK(c.algorithms[1].label == "gjk-johnson@max_iterations=3");
  CHECK(c.algorithms[2].label == "gjk-johnson@max_iterations=128");
  CHECK(c.algorithms[3].label == "gjk-certified");
  CHECK(c.algorithms[0].options.gjk_distance.max_iterations == 1);
  CHECK(c.algorithms[2].options.gjk_distance.max_iterations == 128);

  const ExperimentConfig unswept =
      parse_experiment(std::string(kPairs) + "[[algorithm]]\nname = \"gjk-johnson\"\n", "plain");
  int stopped_by_one = 0;
  for (std::uint64_t id = 0; id < 40; ++id) {
    INFO("case " << id);
    const CaseResult r = evaluate_case(c, id);
    const CaseResult plain = evaluate_case(unswept, id);
    // The bound binds: never more iterations than the value, step_limit when it stopped there.
    CHECK(r.algorithms[0].iterations <= 1);
    CHECK(r.algorithms[1].iterations <= 3);
    stopped_by_one += r.algorithms[0].termination == Termination::step_limit;
    // The default bound is 128: that group is the unswept run, answer for answer.
    CHECK(r.algorithms[2].distance == plain.algorithms[0].distance);
    CHECK(r.algorithms[2].iterations == plain.algorithms[0].iterations);
    CHECK(r.algorithms[2].termination == plain.algorithms[0].termination);
    // gjk-certified is exact whatever the sweep.
    CHECK(r.algorithms[3].distance == r.exact->distance);
  }
  CHECK(stopped_by_one > 20);
}

TEST_CASE("sweep of scale: each base pair once per value, scaled exactly, as its own family",
          "[unit][sweep]") {
  const ExperimentConfig c = parse_experiment(std::string(kPairs) + R"(
[[algorithm]]
name = "gjk-johnson"
[sweep]
parameter = "scale"
values = [1, 0.0009765625, 1024]
)",
                                              "sweep.toml");
  CHECK(c.total_cases() == 120);
  const auto families = c.result_family_names();
  REQUIRE(families.size() == 3);
  for (std::uint64_t base = 0; base < 10; ++base) {
    INFO("base pair " << base);
    const GeneratedCase unit = generate_case(c, 3 * base);
    const double scale[] = {1, 0x1p-10, 0x1p10};
    for (std::uint64_t k = 1; k < 3; ++k) {
      const GeneratedCase scaled = generate_case(c, 3 * base + k);
      CHECK(scaled.record.family == k);  // (family, value) is its own result family
      REQUIRE(scaled.a.size() == unit.a.size());
      for (std::size_t i = 0; i < unit.a.size(); ++i)
        CHECK(scaled.a[i] == unit.a[i] * scale[k]);  // powers of two scale exactly
      // The exact squared distance scales by the square of the value, exactly.
      const auto d_unit = exact::solve(unit.a, unit.b, {.hull_vertices = false});
      const auto d_scaled = exact::solve(scaled.a, scaled.b, {.hull_vertices = false});
      CHECK(d_scaled.distance == d_unit.distance * scale[k]);
    }
  }
}
