// The GJK distance variants (gjk-johnson, gjk-johnson-backup, gjk-sv, gjk-voronoi,
// gjk-nesterov, gjk-polyak) against the exact oracle, scale invariance, the convergence criteria,
// the Nesterov restart rule, and warm starts from the previous query's simplex.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "../support/random_pairs.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/gjk/gjk_nesterov.hpp"
#include "gjklab/gjk/subalgorithms.hpp"

using namespace gjklab;
using testing::CloudKind;
using testing::Rng;

namespace {

struct Variant {
  std::string name;
  std::function<DistanceResult(const Polytope&, const Polytope&, const GjkDistanceOptions&)> run;
};

std::vector<Variant> variants() {
  return {
      {"gjk-johnson",
       [](const Polytope& a, const Polytope& b, const GjkDistanceOptions& o) {
         return gjk_distance_with<JohnsonSubAlgorithm>(a, b, o);
       }},
      {"gjk-johnson-backup",
       [](const Polytope& a, const Polytope& b, const GjkDistanceOptions& o) {
         return gjk_distance_with<JohnsonBackupSubAlgorithm>(a, b, o);
       }},
      {"gjk-sv",
       [](const Polytope& a, const Polytope& b, const GjkDistanceOptions& o) {
         return gjk_distance_with<SignedVolumesSubAlgorithm>(a, b, o);
       }},
      {"gjk-voronoi",
       [](const Polytope& a, const Polytope& b, const GjkDistanceOptions& o) {
         return gjk_distance_with<VoronoiSubAlgorithm>(a, b, o);
       }},
      {"gjk-nesterov",
       [](const Polytope& a, const Polytope& b, const GjkDistanceOptions& o) {
         GjkNesterovOptions n;
         static_cast<GjkDistanceOptions&>(n) = o;
         return gjk_nesterov(a, b, n);
       }},
      {"gjk-polyak", [](const Polytope& a, const Polytope& b,
                        const GjkDistanceOptions& o) { return gjk_polyak(a, b, o); }},
  };
}

/// Seeded pairs like the property test's, smaller: half separated by 1e-6 … 10 sizes, a
/// quarter overlapping a little, a quarter deeply.
testing::RandomPair sample_pair(Rng& rng, int i, int max_vertices) {
  const CloudKind kind = (i % 2 == 0) ? CloudKind::sphere : CloudKind::cube;
  const int na = static_cast<int>(std::round(rng.log_uniform(4, max_vertices)));
  const int nb = static_cast<int>(std::round(rng.log_uniform(4, max_vertices)));
  const double gap = (i % 4 < 2)    ? rng.log_uniform(1e-6, 10)
                     : (i % 4 == 2) ? -rng.log_uniform(1e-6, 0.1)
                                    : -rng.uniform(0.1, 1.0);
  return testing::random_pair(rng, kind, na, nb, gap);
}

constexpr double kBand = 1e-10;

}  // namespace

TEST_CASE("distance variants agree with the exact oracle on 300 seeded pairs", "[unit][variants]") {
  Rng rng(4242);
  const auto all = variants();
  int intersecting = 0, separated = 0;
  for (int i = 0; i < 300; ++i) {
    const auto pair = sample_pair(rng, i, 48);
    const Polytope a(pair.a), b(pair.b);
    const double size = pair_size(pair.a, pair.b);
    const auto exact = exact::solve(a.vertices(), b.vertices());
    exact.intersect ? ++intersecting : ++separated;
    for (const Variant& v : all) {
      const DistanceResult r = v.run(a, b, {});
      INFO("pair " << i << " " << v.name << " exact distance " << exact.distance << " size " << size
                   << " termination " << to_string(r.termination));
      CHECK(r.termination != Termination::step_limit);
      CHECK(r.termination != Termination::numerical_failure);
      if (exact.intersect || exact.distance > kBand * size) CHECK(r.intersect == exact.intersect);
      CHECK(std::abs(r.distance - exact.distance) <= kBand * size);
      // Bounds: the reported lower bound never exceeds the true distance (up to rounding),
      // and the witnesses realise the reported distance.
      CHECK(r.lower_bound <= exact.distance * (1 + 1e-12) + 1e-15 * size);
      if (!r.intersect)
        CHECK(std::abs((r.witness_a - r.witness_b).norm() - r.distance) <= 1e-14 * size);
    }
  }
  CHECK(intersecting > 50);
  CHECK(separated > 100);
}

TEST_CASE("distance variants: 2^k scaling gives exactly 2^k distances", "[unit][variants]") {
  Rng rng(77);
  int compared = 0;
  for (const Variant& v : variants()) {
    for (int i = 0; i < 60; ++i) {
      const auto pair = sample_pair(rng, i, 32);
      const Polytope a(pair.a), b(pair.b);
      const DistanceResult base = v.run(a, b, {});
      for (int k : {-40, -7, 3, 40}) {
        const double s = std::ldexp(1.0, k);
        const DistanceResult scaled = v.run(a.scaled(s), b.scaled(s), {});
        INFO(v.name << " pair " << i << " k " << k);
        CHECK(scaled.distance == base.distance * s);
        CHECK(scaled.intersect == base.intersect);
        CHECK(scaled.iterations == base.iterations);
        CHECK(scaled.termination == base.termination);
        ++compared;
      }
    }
  }
  CHECK(compared == 6 * 60 * 4);
}

TEST_CASE("convergence criteria: each stops within its documented bound",
          "[unit][variants][convergence]") {
  Rng rng(99);
  int checked = 0;
  for (int i = 0; i < 120; ++i) {
    const auto pair =
        testing::random_pair(rng, i % 2 ? CloudKind::cube : CloudKind::sphere, rng.integer(16, 64),
                             rng.integer(16, 64), rng.log_uniform(1e-3, 1));
    const Polytope a(pair.a), b(pair.b);
    const auto exact = exact::solve(a.vertices(), b.vertices());
    if (exact.intersect) continue;
    const double d = exact.distance, size = pair_size(pair.a, pair.b);
    const double slack = 1e-12 * size;  // rounding of the reported distance

    GjkDistanceOptions relative;
    relative.relative_gap = 1e-4;
    GjkDistanceOptions absolute;
    absolute.convergence = GjkConvergence::absolute;
    absolute.absolute_gap_squared = 1e-6 * size * size;
    GjkDistanceOptions duality;
    duality.convergence = GjkConvergence::duality_gap;
    duality.duality_gap_tolerance = 1e-6 * size * size;

    for (const Variant& v : variants()) {
      INFO(v.name << " pair " << i << " exact " << d);
      const DistanceResult r = v.run(a, b, relative);
      CHECK(r.distance - d <= 1e-4 * r.distance + slack);
      const DistanceResult s = v.run(a, b, absolute);
      // ‖v − v*‖² ≤ 2 · absolute_gap_squared.
      CHECK(s.distance - d <= std::sqrt(2 * absolute.absolute_gap_squared) + slack);
      const DistanceResult t = v.run(a, b, duality);
      // ‖v‖² − d² ≤ g.
      CHECK(t.distance * t.distance - d * d <= duality.duality_gap_tolerance + slack * size);
      // Loose tolerances stop no later than the default ones.
      const DistanceResult tight = v.run(a, b, {});
      CHECK(r.iterations <= tight.iterations);
      CHECK(s.iterations <= tight.iterations);
      CHECK(t.iterations <= tight.iterations);
      for (const DistanceResult* x : {&r, &s, &t})
        CHECK(x->termination == Termination::converged);
      ++checked;
    }
  }
  CHECK(checked > 400);
  CHECK(to_string(GjkConvergence::duality_gap) == "duality_gap");
  CHECK(convergence_from_string("absolute") == GjkConvergence::absolute);
  CHECK_FALSE(convergence_from_string("hybrid").has_value());
}

TEST_CASE("nesterov: momentum, restarts, traces and the step limit", "[unit][nesterov]") {
  Rng rng(2022);
  int restarted = 0, separated = 0;
  long nesterov_iterations = 0, plain_iterations = 0;
  for (int i = 0; i < 150; ++i) {
    const auto pair = sample_pair(rng, i, 200);
    const Polytope a(pair.a), b(pair.b);
    const DistanceResult plain = gjk_nesterov(a, b);
    TraceRecorder recorder;
    const DistanceResult traced = gjk_nesterov(a, b, {}, recorder);
    INFO("pair " << i);
    // Traced and untraced runs execute the same arithmetic.
    CHECK(traced.distance == plain.distance);
    CHECK(traced.iterations == plain.iterations);
    CHECK(traced.termination == plain.termination);
    REQUIRE(recorder.iterations.size() == static_cast<std::size_t>(plain.iterations));
    int restarts = 0;
    for (const auto& t : recorder.iterations)
      restarts += t.step == GjkStep::momentum_restart;
    CHECK(restarts <= 1);  // the restart is permanent
    restarted += restarts;
    if (plain.termination == Termination::converged && !plain.intersect) {
      ++separated;
      // The final step is a plain-GJK stop, after the momentum was dropped.
      const GjkStep last = recorder.iterations.back().step;
      CHECK((last == GjkStep::gap_converged || last == GjkStep::repeated_support));
      CHECK(restarts == 1);
    }
    // With coal's normalisation heuristic the answer is as accurate.
    GjkNesterovOptions normalised;
    normalised.normalize_direction = true;
    const DistanceResult other = gjk_nesterov(a, b, normalised);
    const double size = pair_size(pair.a, pair.b);
    CHECK(other.intersect == plain.intersect);
    CHECK(std::abs(other.distance - plain.distance) <= 2 * kBand * size);
    nesterov_iterations += plain.iterations;
    plain_iterations += gjk_distance_with<SignedVolumesSubAlgorithm>(a, b, {}).iterations;
  }
  CHECK(separated > 50);
  CHECK(restarted > 50);
  WARN("nesterov iterations " << nesterov_iterations << " vs plain GJK (signed volumes) "
                              << plain_iterations << " on 150 pairs");

  // Bounded by max_iterations, reported as the step limit, with an upper bound answer.
  const Polytope a(testing::random_cloud(rng, CloudKind::sphere, 400));
  Polytope b(testing::random_cloud(rng, CloudKind::sphere, 400));
  b = b.transformed(Pose::from_translation(Vec3(2.001, 0.3, 0.1)));
  GjkNesterovOptions limited;
  limited.max_iterations = 2;
  const DistanceResult r = gjk_nesterov(a, b, limited);
  CHECK(r.termination == Termination::step_limit);
  CHECK(r.iterations == 2);
  CHECK(r.support_calls == 3);
  CHECK(r.distance >= exact::solve(a.vertices(), b.vertices()).distance);
}

TEMPLATE_TEST_CASE("warm start from the previous simplex: same answers, no more iterations",
                   "[unit][warm_start]", JohnsonSubAlgorithm, JohnsonBackupSubAlgorithm,
                   SignedVolumesSubAlgorithm, VoronoiSubAlgorithm) {
  Rng rng(31);
  const Polytope a(testing::random_cloud(rng, CloudKind::sphere, 96));
  const Polytope b0(testing::random_cloud(rng, CloudKind::cube, 64));
  // B sweeps past A: far, grazing, overlapping, and away again, turning as it goes.
  int frames = 0, contacts = 0;
  long cold_total = 0, warm_total = 0;
  Simplex previous;
  for (int f = 0; f <= 240; ++f) {
    const double s = f / 240.0;
    const Pose pose =
        Pose::from_quaternion(Quat(Eigen::AngleAxisd(1.5 * s, Vec3(1, 2, 3).normalized())),
                              Vec3(-5 + 10 * s, 1.2 - 1.5 * s, 0.4));
    const Polytope b = b0.transformed(pose);
    const DistanceResult cold = gjk_distance_with<TestType>(a, b, {});
    const DistanceResult warm = gjk_distance_warm_with<TestType>(a, b, previous.vertices(), {});
    INFO("frame " << f << " cold " << cold.distance << " (" << cold.iterations << " it) warm "
                  << warm.distance << " (" << warm.iterations << " it)");
    CHECK(warm.intersect == cold.intersect);
    CHECK(std::abs(warm.distance - cold.distance) <= 1e-12 * (1 + cold.distance));
    CHECK(warm.termination == Termination::converged);
    CHECK(warm.iterations <= cold.iterations);
    cold_total += cold.iterations;
    warm_total += warm.iterations;
    contacts += cold.intersect;
    previous = warm.simplex;
    ++frames;
  }
  CHECK(contacts > 20);
  CHECK(contacts < frames - 20);
  CHECK(warm_total < cold_total);
  WARN("warm start: " << warm_total << " iterations vs " << cold_total << " cold over " << frames
                      << " frames");

  // An empty start is the cold query, bit for bit.
  const Polytope b = b0.transformed(Pose::from_translation(Vec3(2.5, 0.1, 0.2)));
  const DistanceResult cold = gjk_distance_with<TestType>(a, b, {});
  const DistanceResult empty = gjk_distance_warm_with<TestType>(a, b, {}, {});
  CHECK(empty.distance == cold.distance);
  CHECK(empty.iterations == cold.iterations);
  CHECK(empty.support_calls == cold.support_calls);
}

TEST_CASE("separation certificate: squared and unsquared bounds agree at every scale",
          "[unit][variants]") {
  // ‖v‖ = 2^k and ‖w‖ = 2^(k+1), v·w 2× and 0.5× the rounding bound kDotRoundoff·‖v‖‖w‖:
  // from lengths where the squared threshold underflows (k below about −230) to where it
  // overflows (k above about 280), while ‖v‖² and ‖w‖² stay normal doubles.
  for (int k = -500; k <= 500; k += 20) {
    const double s = std::ldexp(1.0, k);
    const double vv = s * s, ww = 4 * s * s;  // ‖v‖ = s, ‖w‖ = 2s
    const double bound = kDotRoundoff * s * (2 * s);
    CAPTURE(k);
    CHECK(detail::separation_certified(2 * bound, vv, ww));
    CHECK_FALSE(detail::separation_certified(0.5 * bound, vv, ww));
    CHECK_FALSE(detail::separation_certified(0.0, vv, ww));
    CHECK_FALSE(detail::separation_certified(-bound, vv, ww));
  }
}

TEST_CASE("momentum directions: Polyak's average and Nesterov's mix, step by step",
          "[unit][nesterov]") {
  // Polyak: d_k = d_{k−1}/(k+1) + k/(k+1)·v_k.
  PolyakDirections polyak;
  polyak.start(Vec3(4, 0, 0), Vec3(9, 9, 9));
  CHECK(polyak.direction(1, Vec3(0, 2, 0)).isApprox(Vec3(2, 1, 0)));
  CHECK(polyak.direction(2, Vec3(0, 0, 3)).isApprox(Vec3(2.0 / 3, 1.0 / 3, 2)));
  // Nesterov: δ_1 = 1/2, y_1 = (v_1 + s_0)/2, d_1 = (d_0 + y_1)/2.
  NesterovDirections nesterov;
  nesterov.start(Vec3(4, 0, 0), Vec3(0, 0, 2));
  CHECK(nesterov.direction(1, Vec3(0, 2, 0)).isApprox(Vec3(2, 0.5, 0.5)));
  // Plain GJK takes v itself.
  CHECK(PlainDirections{}.direction(7, Vec3(1, 2, 3)) == Vec3(1, 2, 3));
}

TEST_CASE("momentum starts from the direction of the first support point", "[unit][nesterov]") {
  // The centre start takes its first support point in −c (c = c_A − c_B), so d_0 ∥ c; a fixed
  // start in −c is the same query step for step. (The momentum was once seeded from
  // initial_direction whatever the start, so the two differed.)
  Rng rng(77);
  int compared = 0;
  for (int i = 0; i < 60; ++i) {
    const auto pair = sample_pair(rng, i, 64);
    const Polytope a(pair.a), b(pair.b);
    const Vec3 c = a.vertex_mean() - b.vertex_mean();
    GjkNesterovOptions fixed;
    fixed.start = GjkDistanceStart::fixed_direction;
    fixed.initial_direction = -c;
    const DistanceResult centre = gjk_nesterov(a, b);
    const DistanceResult same = gjk_nesterov(a, b, fixed);
    INFO("pair " << i);
    CHECK(same.distance == centre.distance);
    CHECK(same.iterations == centre.iterations);
    GjkDistanceOptions fixed_plain = fixed;
    CHECK(gjk_polyak(a, b, fixed_plain).distance == gjk_polyak(a, b).distance);
    ++compared;
  }
  CHECK(compared == 60);
}
