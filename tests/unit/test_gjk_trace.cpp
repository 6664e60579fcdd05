// Traces: the traced query returns bit-identical results, and the trace tells the story.
#include <catch2/catch.hpp>

#include "../support/random_pairs.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

using namespace gjklab;

TEST_CASE("trace: traced and untraced GJK runs give identical results", "[unit][trace]") {
  testing::Rng rng(99);
  int separated = 0;
  for (int i = 0; i < 300; ++i) {
    const auto pair = testing::random_pair(rng, testing::CloudKind::sphere, rng.integer(4, 64),
                                           rng.integer(4, 64),
                                           i % 2 ? rng.log_uniform(1e-8, 1) : -rng.uniform(0, 0.5));
    const Polytope a(pair.a), b(pair.b);
    const DistanceResult plain = gjk_distance(a, b);
    TraceRecorder recorder;
    const DistanceResult traced = gjk_distance(a, b, {}, recorder);
    INFO("pair " << i);
    CHECK(traced.distance == plain.distance);
    CHECK(traced.closest == plain.closest);
    CHECK(traced.iterations == plain.iterations);
    CHECK(traced.termination == plain.termination);
    REQUIRE(recorder.iterations.size() == static_cast<std::size_t>(plain.iterations));
    separated += !plain.intersect;

    // The trace's last step explains the termination; the lower bound never exceeds ‖v‖.
    const GjkIterationTrace& last = recorder.iterations.back();
    if (plain.termination == Termination::converged)
      CHECK((last.step == GjkStep::gap_converged || last.step == GjkStep::repeated_support ||
             last.step == GjkStep::contact));
    for (const auto& t : recorder.iterations) {
      // Up to rounding: the bound is a quotient of rounded dot products.
      CHECK(t.lower_bound <= std::sqrt(t.v_norm_squared) * (1 + 1e-14));
      CHECK(t.support.index_a >= 0);
      CHECK(t.support.a == a.vertices()[t.support.index_a]);
      CHECK(t.support.b == b.vertices()[t.support.index_b]);
    }

    const BooleanResult bool_plain = gjk_intersect(a, b);
    TraceRecorder bool_recorder;
    const BooleanResult bool_traced = gjk_intersect(a, b, {}, bool_recorder);
    CHECK(bool_traced.intersect == bool_plain.intersect);
    CHECK(bool_traced.iterations == bool_plain.iterations);
    CHECK(bool_recorder.iterations.size() == static_cast<std::size_t>(bool_plain.iterations));
  }
  CHECK(separated > 50);
  CHECK(separated < 250);
}
