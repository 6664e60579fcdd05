// The libccd peer adapter: answers, support and iteration counts, the iteration budget of GJK and
// MPR, numerical failures, option checks and re-entrancy.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "gjklab/geometry/shapes.hpp"
#include "gjklab/peers/libccd.hpp"

using namespace gjklab;
using namespace gjklab::peers;

namespace {

Polytope placed(const Polytope& shape, const Quat& rotation, const Vec3& translation) {
  return shape.transformed(Pose::from_quaternion(rotation, translation));
}

/// A budget that libccd never reaches on these small shapes.
LibccdOptions unbounded(double mpr_tolerance = LibccdDefaults::mpr_tolerance) {
  LibccdOptions options;
  options.max_iterations = 1'000'000;
  options.mpr_tolerance = mpr_tolerance;
  return options;
}

LibccdOptions with_budget(int max_iterations,
                          double mpr_tolerance = LibccdDefaults::mpr_tolerance) {
  LibccdOptions options;
  options.max_iterations = max_iterations;
  options.mpr_tolerance = mpr_tolerance;
  return options;
}

/// The counting identities documented in libccd.hpp.
void check_gjk_counts(const BooleanResult& r, int max_iterations) {
  CHECK(r.support_calls >= 1);
  CHECK(r.iterations == r.support_calls - 1);
  CHECK(r.iterations <= max_iterations);
}

void check_mpr_counts(const BooleanResult& r, int max_iterations) {
  CHECK(r.support_calls >= 1);
  CHECK(r.iterations == std::max(r.support_calls - 2, 0));
  CHECK(r.iterations <= max_iterations);
}

bool same(const BooleanResult& x, const BooleanResult& y) {
  return x.intersect == y.intersect && x.iterations == y.iterations &&
         x.support_calls == y.support_calls && x.termination == y.termination;
}

// Two UV spheres (radius 0.5, vertices on the sphere) whose centres are 1.0005 apart: separated
// by a gap of at least 5e-4, which GJK needs many iterations to prove.
const Quat kSphereRotation(0.3, -0.5, 0.7, 0.2);
const Vec3 kSphereDirection = Vec3(0.6, -0.3, 0.74).normalized();

}  // namespace

TEST_CASE("libccd: clearly separated boxes do not intersect", "[unit]") {
  const Polytope a = shapes::box();
  const Polytope b = shapes::box().transformed(Pose::from_translation(Vec3(3, 0.2, 0.1)));
  for (const BooleanResult& r : {libccd_gjk_intersect(a, b), libccd_mpr_intersect(a, b)}) {
    CHECK_FALSE(r.intersect);
    CHECK(r.termination == Termination::converged);
    CHECK(r.support_calls > 0);
  }
  check_gjk_counts(libccd_gjk_intersect(a, b), LibccdDefaults::max_iterations);
  check_mpr_counts(libccd_mpr_intersect(a, b), LibccdDefaults::max_iterations);
}

TEST_CASE("libccd: clearly overlapping boxes intersect", "[unit]") {
  const Polytope a = shapes::box();
  const Polytope b = shapes::box().transformed(Pose::from_translation(Vec3(0.5, 0.2, 0.1)));
  const BooleanResult gjk = libccd_gjk_intersect(a, b);
  const BooleanResult mpr = libccd_mpr_intersect(a, b);
  CHECK(gjk.intersect);
  CHECK(mpr.intersect);
  CHECK(gjk.termination == Termination::converged);
  CHECK(mpr.termination == Termination::converged);
  check_gjk_counts(gjk, LibccdDefaults::max_iterations);
  check_mpr_counts(mpr, LibccdDefaults::max_iterations);
  // Deciding an overlap needs a simplex/portal, i.e. more than the first support point.
  CHECK(gjk.support_calls >= 3);
  CHECK(mpr.support_calls >= 3);
}

TEST_CASE("libccd: answers and counts on random clear-cut pairs", "[unit]") {
  // Every shape lies in [-0.5, 0.5]^3 (circumradius < 0.87) and contains the ball of radius
  // 0.2 about its centre (the cone's inradius is about 0.22), so centres more than 2 apart are
  // separated and centres less than 0.4 apart overlap.
  const std::array<Polytope, 4> shape = {shapes::box(), shapes::cone(), shapes::cylinder(),
                                         shapes::uv_sphere()};
  std::mt19937 rng(20240611);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> far(2.05, 3.0), near(0.0, 0.38);
  for (int trial = 0; trial < 200; ++trial) {
    const Polytope& a = shape[trial % 4];
    const Quat rotation(normal(rng), normal(rng), normal(rng), normal(rng));
    const Vec3 direction = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const bool separated = trial % 2 == 0;
    const double distance = separated ? far(rng) : near(rng);
    const Polytope b = placed(shape[(trial / 4) % 4], rotation, distance * direction);
    INFO("trial " << trial << ", centre distance " << distance);

    const BooleanResult gjk = libccd_gjk_intersect(a, b);
    const BooleanResult mpr = libccd_mpr_intersect(a, b);
    CHECK(gjk.intersect == !separated);
    CHECK(mpr.intersect == !separated);
    CHECK(gjk.termination == Termination::converged);
    CHECK(mpr.termination == Termination::converged);
    check_gjk_counts(gjk, LibccdDefaults::max_iterations);
    check_mpr_counts(mpr, LibccdDefaults::max_iterations);
  }
}

TEST_CASE("libccd: GJK stops at max_iterations with step_limit", "[unit]") {
  const Polytope a = shapes::uv_sphere();
  const Polytope b = placed(shapes::uv_sphere(), kSphereRotation, 1.0005 * kSphereDirection);

  const BooleanResult full = libccd_gjk_intersect(a, b, unbounded());
  REQUIRE_FALSE(full.intersect);
  REQUIRE(full.termination == Termination::converged);
  REQUIRE(full.iterations >= 4);  // the case needs several iterations
  const int k = full.iterations;

  SECTION("max_iterations = 1") {
    const BooleanResult r = libccd_gjk_intersect(a, b, with_budget(1));
    CHECK_FALSE(r.intersect);
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.iterations == 1);
    CHECK(r.support_calls == 2);
  }
  SECTION("one iteration short of the proof") {
    const BooleanResult r = libccd_gjk_intersect(a, b, with_budget(k - 1));
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.iterations == k - 1);
  }
  SECTION("a proof found in the last allowed iteration is not a step limit") {
    const BooleanResult r = libccd_gjk_intersect(a, b, with_budget(k));
    CHECK(same(r, full));
  }
  SECTION("max_iterations = 0: only the initial support point") {
    const BooleanResult r = libccd_gjk_intersect(a, b, with_budget(0));
    CHECK_FALSE(r.intersect);
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.iterations == 0);
    CHECK(r.support_calls == 1);
  }
}

TEST_CASE("libccd: GJK finding an intersection in the last allowed iteration converges", "[unit]") {
  const Polytope a = shapes::uv_sphere();
  const Polytope b = placed(shapes::uv_sphere(), kSphereRotation, 0.99 * kSphereDirection);
  const BooleanResult full = libccd_gjk_intersect(a, b, unbounded());
  REQUIRE(full.intersect);
  REQUIRE(full.iterations >= 2);
  CHECK(same(libccd_gjk_intersect(a, b, with_budget(full.iterations)), full));
  const BooleanResult short_run = libccd_gjk_intersect(a, b, with_budget(full.iterations - 1));
  CHECK_FALSE(short_run.intersect);
  CHECK(short_run.termination == Termination::step_limit);
}

TEST_CASE("libccd: MPR stops at max_iterations with step_limit", "[unit]") {
  // Overlapping by about 1% of the diameter: portal refinement needs several passes.
  const Polytope a = shapes::uv_sphere();
  const Polytope b = placed(shapes::uv_sphere(), kSphereRotation, 0.99 * kSphereDirection);

  const BooleanResult full = libccd_mpr_intersect(a, b, unbounded());
  REQUIRE(full.intersect);
  REQUIRE(full.termination == Termination::converged);
  REQUIRE(full.iterations >= 3);
  const int k = full.iterations;

  SECTION("max_iterations = 1") {
    const BooleanResult r = libccd_mpr_intersect(a, b, with_budget(1));
    CHECK_FALSE(r.intersect);  // undetermined
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.iterations == 1);
    CHECK(r.support_calls == 3);
  }
  SECTION("one iteration short") {
    const BooleanResult r = libccd_mpr_intersect(a, b, with_budget(k - 1));
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.iterations == k - 1);
    CHECK(r.support_calls == k + 1);
  }
  SECTION("exactly enough iterations") {
    CHECK(same(libccd_mpr_intersect(a, b, with_budget(k)), full));
  }
  SECTION("max_iterations = 0 still allows portal discovery's first two support points") {
    const BooleanResult r = libccd_mpr_intersect(a, b, with_budget(0));
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.iterations == 0);
    CHECK(r.support_calls == 2);
  }
}

TEST_CASE("libccd: MPR's budget ends refinement on a touching configuration", "[unit]") {
  // Fine curved shapes placed where libccd's MPR answer flips (found by bisection), with
  // mpr_tolerance 0: refinement creeps towards the contact point, and only the adapter's budget
  // bounds libccd's while(1) loop.
  const Polytope a = shapes::cylinder(2000);
  const Polytope cone = shapes::cone(2000);
  const Quat rotation(0.1, 0.9, -0.2, 0.4);
  const Vec3 direction = Vec3(-0.2, 0.5, 0.8).normalized();
  const LibccdOptions exhaustive = unbounded(0.0);
  double inside = 0, outside = 3;
  for (int i = 0; i < 80 && outside - inside > 0; ++i) {
    const double mid = 0.5 * (inside + outside);
    if (mid == inside || mid == outside) break;
    if (libccd_mpr_intersect(a, placed(cone, rotation, mid * direction), exhaustive).intersect)
      inside = mid;
    else
      outside = mid;
  }
  for (const double distance : {inside, outside}) {
    INFO("centre distance " << distance);
    const Polytope b = placed(cone, rotation, distance * direction);
    const BooleanResult full = libccd_mpr_intersect(a, b, exhaustive);
    REQUIRE(full.termination == Termination::converged);
    REQUIRE(full.iterations >= 3);
    for (int budget = 0; budget < full.iterations; ++budget) {
      const BooleanResult r = libccd_mpr_intersect(a, b, with_budget(budget, 0.0));
      CHECK_FALSE(r.intersect);
      CHECK(r.termination == Termination::step_limit);
      CHECK(r.support_calls == budget + 2);
      CHECK(r.iterations == budget);
    }
  }
}

TEST_CASE("libccd: a NaN direction inside MPR is a numerical failure", "[unit]") {
  // A segment against a point off its line: the Minkowski difference is a segment, so portal
  // discovery's first three points are collinear and libccd normalises a zero normal (0/0).
  const Polytope segment({Vec3(2, -1, -1), Vec3(-2, 2, 2)});
  const Polytope point({Vec3(1, 0, 1)});
  const BooleanResult mpr = libccd_mpr_intersect(segment, point);
  CHECK_FALSE(mpr.intersect);
  CHECK(mpr.termination == Termination::numerical_failure);
  CHECK(mpr.support_calls == 2);
  // GJK has no trouble with the same pair: the point is off the segment.
  const BooleanResult gjk = libccd_gjk_intersect(segment, point);
  CHECK_FALSE(gjk.intersect);
  CHECK(gjk.termination == Termination::converged);
}

TEST_CASE("libccd: invalid options are rejected", "[unit]") {
  const Polytope a = shapes::box();
  const Polytope b = shapes::box().transformed(Pose::from_translation(Vec3(3, 0, 0)));
  LibccdOptions negative;
  negative.max_iterations = -1;
  CHECK_THROWS_AS(libccd_gjk_intersect(a, b, negative), std::invalid_argument);
  CHECK_THROWS_AS(libccd_mpr_intersect(a, b, negative), std::invalid_argument);
  LibccdOptions bad_tolerance;
  bad_tolerance.mpr_tolerance = std::nan("");
  CHECK_THROWS_AS(libccd_mpr_intersect(a, b, bad_tolerance), std::invalid_argument);
  bad_tolerance.mpr_tolerance = -1e-4;
  CHECK_THROWS_AS(libccd_mpr_intersect(a, b, bad_tolerance), std::invalid_argument);
}

TEST_CASE("libccd: queries on concurrent threads give the results they give alone", "[unit]") {
  // Different queries, including ones that leave libccd by longjmp (step limit, NaN), run
  // interleaved on several threads; each must match its result computed alone.
  const Polytope sphere = shapes::uv_sphere();
  const Polytope near_sphere = placed(sphere, kSphereRotation, 0.99 * kSphereDirection);
  const Polytope far_sphere = placed(sphere, kSphereRotation, 1.0005 * kSphereDirection);
  const Polytope segment({Vec3(2, -1, -1), Vec3(-2, 2, 2)});
  const Polytope point({Vec3(1, 0, 1)});

  struct Job {
    bool mpr;
    const Polytope* a;
    const Polytope* b;
    LibccdOptions options;
  };
  const std::vector<Job> jobs = {
      {false, &sphere, &far_sphere, unbounded()},     // GJK, separated
      {false, &sphere, &far_sphere, with_budget(2)},  // GJK, step limit
      {false, &sphere, &near_sphere, unbounded()},    // GJK, intersecting
      {true, &sphere, &near_sphere, unbounded()},     // MPR, intersecting
      {true, &sphere, &near_sphere, with_budget(1)},  // MPR, step limit (longjmp)
      {true, &segment, &point, unbounded()},          // MPR, NaN direction (longjmp)
      {true, &sphere, &far_sphere, unbounded()},      // MPR, separated
  };
  auto run = [](const Job& job) {
    return job.mpr ? libccd_mpr_intersect(*job.a, *job.b, job.options)
                   : libccd_gjk_intersect(*job.a, *job.b, job.options);
  };
  std::vector<BooleanResult> alone;
  for (const Job& job : jobs)
    alone.push_back(run(job));
  // The reference results cover every exit path: converged, step_limit and numerical_failure.
  CHECK(alone[1].termination == Termination::step_limit);
  CHECK(alone[4].termination == Termination::step_limit);
  CHECK(alone[5].termination == Termination::numerical_failure);

  constexpr int kThreads = 4;
  constexpr int kRounds = 300;
  std::vector<int> mismatches(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < kRounds; ++round) {
        const std::size_t j = static_cast<std::size_t>(t + round) % jobs.size();
        if (!same(run(jobs[j]), alone[j])) ++mismatches[t];
      }
    });
  }
  for (std::thread& thread : threads)
    thread.join();
  for (int t = 0; t < kThreads; ++t)
    CHECK(mismatches[t] == 0);
}

TEST_CASE("libccd: version is reported", "[unit]") {
  const std::string version = libccd_version();
  CHECK_FALSE(version.empty());
  // Debian's libccd 2.1 installs a package config that calls itself 2.0.
  CHECK(version.rfind("2.", 0) == 0);
}
