// An algorithm added from outside the library: this file and one line (AddedAlgorithm) make
// `test-gjk-bool-fixed` an algorithm like the registered ones. Its entry is built from its
// query and an option schema; parsing and describing its options, the traced and swept runs
// and the benchmark's direct loop all follow from that entry, with nothing else to list.
#include <catch2/catch.hpp>

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

namespace {

// ---- the algorithm: boolean GJK that always starts from its fixed direction ----

/// Its own options, in a struct the library does not know: stored in AlgorithmOptions::added
/// and reached by its schema's row.
struct FixedStartOptions {
  int max_iterations = GjkBooleanDefaults::max_iterations;
};

constexpr OptionRow kFixedStartRows[] = {
    {"max_iterations",
     [](AlgorithmOptions& o) -> int& { return o.added.get<FixedStartOptions>().max_iterations; },
     "iteration bound of the fixed-start query"},
};

GjkBooleanOptions fixed_start(const AlgorithmOptions& o) {
  GjkBooleanOptions options;
  options.start = GjkBooleanStart::fixed_direction;
  options.max_iterations = o.added.value<FixedStartOptions>().max_iterations;
  return options;
}

Outcome run_fixed(const QueryRequest& q) {
  const GjkBooleanOptions o = fixed_start(q.options);
  auto query = [&](const auto& a, const auto& b) {
    return q.trace ? gjk_intersect(a, b, o, *q.trace) : gjk_intersect(a, b, o);
  };
  if (!q.radii.any()) return from_boolean(query(q.a, q.b));
  return from_boolean(
      query(SphereSwept<Polytope>(q.a, q.radii.a), SphereSwept<Polytope>(q.b, q.radii.b)));
}

BenchTally bench_fixed(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps) {
  BenchTally t;
  for (int r = 0; r < reps; ++r)
    for (const BenchPair& p : pairs) {
      const BooleanResult answer = gjk_intersect(*p.a, *p.b, fixed_start(o));
      ++t.queries;
      t.iterations += answer.iterations;
      t.support_calls += answer.support_calls;
      t.intersections += answer.intersect;
    }
  return t;
}

AlgorithmInfo fixed_start_entry() {
  return {.name = "test-gjk-bool-fixed",
          .kind = AnswerKind::boolean,
          .description = "gjk-bool started from its fixed direction whatever `start` says",
          .run = run_fixed,
          .can = {.swept = true, .traced = true},
          .options = kFixedStartRows,
          .bench = bench_fixed};
}

// ---- the test's pairs ----

std::vector<Polytope> test_shapes() {
  std::vector<Polytope> shapes;
  const Polytope box = shapes::box(), cone = shapes::cone();
  for (int k = 0; k < 4; ++k) {
    const Mat3 r = Eigen::AngleAxisd(0.4 * k + 0.1, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    shapes.push_back(box.transformed({r, Vec3::Zero()}));
    shapes.push_back(cone.transformed({r.transpose(), Vec3(0.5 + 0.7 * k, 0.1 * k, 0)}));
  }
  return shapes;
}

}  // namespace

TEST_CASE("added algorithm: one file and one line make it a registered algorithm",
          "[unit][registry]") {
  const std::vector<Polytope> shapes = test_shapes();
  std::vector<BenchPair> pairs;
  for (std::size_t i = 0; i + 1 < shapes.size(); i += 2)
    pairs.push_back({&shapes[i], &shapes[i + 1]});
  const std::size_t builtin = algorithms().size();
  REQUIRE(find_algorithm("test-gjk-bool-fixed") == nullptr);
  {
    const AddedAlgorithm added(fixed_start_entry());  // the one line

    const AlgorithmInfo* algorithm = find_algorithm("test-gjk-bool-fixed");
    REQUIRE(algorithm != nullptr);
    CHECK(algorithms().size() == builtin + 1);
    CHECK(algorithms().back().name == "test-gjk-bool-fixed");
    CHECK(algorithm_names().find("test-gjk-bool-fixed") != std::string::npos);
    CHECK_THROWS_AS(AddedAlgorithm(fixed_start_entry()), std::invalid_argument);

    // Its answers are gjk-bool's with start = fixed_direction, plain, traced and swept.
    AlgorithmOptions fixed;
    fixed.gjk_boolean.start = GjkBooleanStart::fixed_direction;
    const AlgorithmInfo& gjk_bool = *find_algorithm("gjk-bool");
    const SweptRadii radii{0.25, 0.5};
    int intersecting = 0;
    for (const BenchPair& p : pairs) {
      const Outcome mine = run_algorithm(*algorithm, *p.a, *p.b, {}, AlgorithmOptions{});
      const Outcome reference = run_algorithm(gjk_bool, *p.a, *p.b, {}, fixed);
      CHECK(mine.intersect == reference.intersect);
      CHECK(mine.iterations == reference.iterations);
      TraceRecorder trace;
      const Outcome traced =
          run_algorithm_traced(*algorithm, *p.a, *p.b, {}, AlgorithmOptions{}, trace);
      CHECK(traced.iterations == mine.iterations);
      CHECK_FALSE(trace.iterations.empty());
      const Outcome swept = run_algorithm(*algorithm, *p.a, *p.b, radii, AlgorithmOptions{});
      CHECK(swept.intersect == run_algorithm(gjk_bool, *p.a, *p.b, radii, fixed).intersect);
      intersecting += mine.intersect;
    }
    CHECK(intersecting > 0);  // both kinds of pair were asked
    CHECK(intersecting < static_cast<int>(pairs.size()));

    // Experiment files name it and set its own options, which its schema describes and
    // replay reads back; the library's structs are untouched.
    const ExperimentConfig config = parse_experiment(
        "name = \"added\"\nseed = 1\ncases = 1\n[[family]]\nshape = \"box\"\n"
        "[[algorithm]]\nname = \"test-gjk-bool-fixed\"\nmax_iterations = 3\n",
        "added.toml");
    REQUIRE(config.algorithms.size() == 1);
    const AlgorithmOptions& parsed = config.algorithms[0].options;
    CHECK(parsed.added.value<FixedStartOptions>().max_iterations == 3);
    CHECK(parsed.gjk_boolean.max_iterations == AlgorithmOptions{}.gjk_boolean.max_iterations);
    const auto described = describe_options(config.algorithms[0]);
    CHECK(std::find(described.begin(), described.end(),
                    std::pair<std::string, std::string>{"max_iterations", "3"}) != described.end());
    const AlgorithmSpec replayed = spec_from_description("test-gjk-bool-fixed", described);
    CHECK(replayed.options.added.value<FixedStartOptions>().max_iterations == 3);
    CHECK_THROWS_AS(parse_experiment("name = \"added\"\nseed = 1\ncases = 1\n[[family]]\n"
                                     "shape = \"box\"\n[[algorithm]]\n"
                                     "name = \"test-gjk-bool-fixed\"\nmax_iterations = 0\n",
                                     "added.toml"),
                    ConfigError);
    // Its bound is its own: at one iteration it stops where gjk-bool's default would go on.
    const AlgorithmOptions one =
        spec_from_description("test-gjk-bool-fixed", {{"max_iterations", "1"}}).options;
    int stopped = 0;
    for (const BenchPair& p : pairs)
      stopped +=
          run_algorithm(*algorithm, *p.a, *p.b, {}, one).termination == Termination::step_limit;
    CHECK(stopped > 0);

    // The benchmark finds its direct loop in the entry, and it makes the registry's queries.
    const BenchLoop loop = find_bench_loop("test-gjk-bool-fixed");
    REQUIRE(loop == &bench_fixed);
    const BenchTally direct = loop(pairs, AlgorithmOptions{}, 2);
    const BenchTally via_registry =
        run_bench_loop_via_registry(*algorithm, pairs, AlgorithmOptions{}, 2);
    CHECK(direct.queries == via_registry.queries);
    CHECK(direct.iterations == via_registry.iterations);
    CHECK(direct.intersections == via_registry.intersections);
  }
  // Gone with the object that added it.
  CHECK(find_algorithm("test-gjk-bool-fixed") == nullptr);
  CHECK(algorithms().size() == builtin);
}
