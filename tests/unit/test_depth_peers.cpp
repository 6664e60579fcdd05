// Penetration-depth peers: libccd's GJK+EPA and MPR penetration through the bounded adapter,
// and the optional FCL and Bullet adapters when they were built. Their disagreements with the
// exact oracle on random pairs are counted and reported, not asserted.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "../support/random_pairs.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/run/provenance.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/peers/libccd.hpp"
#ifdef GJKLAB_HAVE_FCL
#include "gjklab/peers/fcl.hpp"
#endif
#ifdef GJKLAB_HAVE_BULLET
#include "gjklab/peers/bullet.hpp"
#endif

using namespace gjklab;
using namespace gjklab::peers;
using testing::CloudKind;
using testing::Rng;

namespace {

Polytope moved(const Polytope& p, const Vec3& t) {
  return p.transformed(Pose::from_translation(t));
}

const Polytope& cube() {
  static const Polytope c = shapes::box(Vec3(2, 2, 2));
  return c;
}

}  // namespace

TEST_CASE("libccd penetration: boxes", "[unit][libccd]") {
  const Polytope b = moved(cube(), Vec3(0, 0, 1.9));
  SECTION("MPR on cubes overlapping by 0.1") {
    const LibccdPenetration r = libccd_mpr_penetration(cube(), b);
    CHECK(r.intersect);
    CHECK(r.termination == Termination::converged);
    CHECK(std::abs(r.depth - 0.1) <= 1e-3);
    CHECK(r.normal.z() > 0.99);
    CHECK(r.support_calls > 0);
  }
  SECTION("GJK+EPA on cubes overlapping by 0.1: libccd 2.1's NaN stays inside the adapter") {
    // libccd 2.1 answers this pair with depth 0 and a NaN direction (or asks for support in a
    // NaN direction): the adapter reports a numerical failure with finite values. A libccd
    // that gets it right must give the right depth.
    const LibccdPenetration r = libccd_gjk_penetration(cube(), b);
    CHECK(r.normal.allFinite());
    CHECK(std::isfinite(r.depth));
    CHECK((r.termination == Termination::numerical_failure ||
           (r.termination == Termination::converged && std::abs(r.depth - 0.1) <= 1e-3)));
    WARN("libccd-gjk-epa on the cubes: termination " << to_string(r.termination) << ", depth "
                                                     << r.depth);
  }
  SECTION("GJK+EPA on turned boxes") {
    const Polytope turned = shapes::box().transformed(
        Pose::from_quaternion(Quat(0.9, 0.2, -0.3, 0.1), Vec3(0.3, 0.6, 0.2)));
    const auto exact = exact::solve(shapes::box().vertices(), turned.vertices(), {.depth = true});
    REQUIRE(exact.intersect);
    const LibccdPenetration r = libccd_gjk_penetration(shapes::box(), turned);
    CHECK(r.intersect);
    CHECK(r.termination == Termination::converged);
    CHECK(std::abs(r.depth - *exact.depth) <= 1e-3);
  }
  const Polytope apart = moved(cube(), Vec3(2.5, 0.1, 0.2));
  for (const auto& r :
       {libccd_gjk_penetration(cube(), apart), libccd_mpr_penetration(cube(), apart)}) {
    CHECK_FALSE(r.intersect);
    CHECK(r.termination == Termination::converged);
    CHECK(r.depth == 0);
  }
}

TEST_CASE("libccd penetration: the adapter's budget ends EPA and MPR", "[unit][libccd]") {
  const Polytope a = shapes::uv_sphere();
  const Polytope b =
      a.transformed(Pose::from_quaternion(Quat(0.3, 0.1, 0.5, 0.2), Vec3(0.1, 0.2, 0.05)));
  SECTION("GJK+EPA with epa_tolerance 0 does not stop by itself") {
    // With a zero tolerance libccd's EPA keeps adding support points it already has; only the
    // adapter's budget ends it, and libccd still returns its nearest face.
    LibccdOptions o;
    o.epa_tolerance = 0;
    o.max_depth_iterations = 40;
    const LibccdPenetration r = libccd_gjk_penetration(a, b, o);
    CHECK(r.intersect);
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.support_calls == libccd_gjk_penetration_budget(o));
    CHECK(r.iterations == r.support_calls - 1);
    CHECK(std::isfinite(r.depth));
  }
  SECTION("MPR penetration with a small budget") {
    LibccdOptions o;
    o.max_iterations = 1;
    o.max_depth_iterations = 0;
    const LibccdPenetration r = libccd_mpr_penetration(a, b, o);
    CHECK_FALSE(r.intersect);  // undetermined
    CHECK(r.termination == Termination::step_limit);
    CHECK(r.support_calls == 3);
  }
  SECTION("invalid options") {
    LibccdOptions o;
    o.epa_tolerance = -1;
    CHECK_THROWS_AS(libccd_gjk_penetration(a, b, o), std::invalid_argument);
    o = {};
    o.max_depth_iterations = -1;
    CHECK_THROWS_AS(libccd_mpr_penetration(a, b, o), std::invalid_argument);
  }
}

TEST_CASE("optional peers: built peers are registered and in the provenance", "[unit][peers]") {
  std::string optional;
  for (const auto& [name, value] : experiment::build_provenance())
    if (name == "optional_peers") optional = value;
#ifdef GJKLAB_HAVE_FCL
  CHECK(experiment::find_algorithm("fcl-libccd") != nullptr);
  CHECK(experiment::find_algorithm("fcl-indep") != nullptr);
  CHECK(optional.find("fcl") != std::string::npos);
#else
  CHECK(experiment::find_algorithm("fcl-libccd") == nullptr);
  CHECK(optional.find("fcl") == std::string::npos);
#endif
#ifdef GJKLAB_HAVE_BULLET
  CHECK(experiment::find_algorithm("bullet-gjk") != nullptr);
  CHECK(experiment::find_algorithm("bullet-epa2") != nullptr);
  CHECK(optional.find("bullet") != std::string::npos);
#else
  CHECK(experiment::find_algorithm("bullet-gjk") == nullptr);
  CHECK(optional.find("bullet") == std::string::npos);
#endif
#if !defined(GJKLAB_HAVE_FCL) && !defined(GJKLAB_HAVE_BULLET)
  CHECK(optional == "none");
#endif
}

#ifdef GJKLAB_HAVE_FCL
TEST_CASE("fcl: separated and overlapping boxes", "[unit][peers][fcl]") {
  const FclShape a(cube());
  for (const FclSolver solver : {FclSolver::libccd, FclSolver::indep}) {
    INFO((solver == FclSolver::libccd ? "fcl-libccd" : "fcl-indep"));
    const PenetrationResult apart =
        fcl_query(a, FclShape(moved(cube(), Vec3(2.5, 0.1, 0.2))), solver);
    CHECK_FALSE(apart.intersect);
    CHECK(apart.termination == Termination::converged);
    CHECK(std::abs(apart.distance - 0.5) <= 1e-6);
    CHECK(apart.normal.x() > 0.99);
    const PenetrationResult overlap =
        fcl_query(a, FclShape(moved(cube(), Vec3(0, 0, 1.9))), solver);
    CHECK(overlap.intersect);
    CHECK(overlap.termination == Termination::converged);
    CHECK(std::abs(overlap.depth - 0.1) <= 1e-6);
    CHECK(std::abs(overlap.normal.z()) > 0.99);
  }
  FclOptions bad;
  bad.max_iterations = 0;
  CHECK_THROWS_AS(fcl_query(a, a, FclSolver::indep, bad), std::invalid_argument);
}

TEST_CASE("fcl: answers do not depend on where the shapes were built", "[unit][peers][fcl]") {
  // FCL's Convex averages its vertices for an interior point and breaks support ties by vertex
  // index, so its distances depend on the order of the hull's vertices. That order came from
  // CGAL and depended on heap addresses: on this pair fcl-indep's distance changed in the 10th
  // digit between runs of one experiment. Shapes built after other allocations, or on another
  // thread, must give bit-identical answers.
  const std::string data = GJKLAB_TEST_DATA_DIR;
  const std::vector<Vec3> a = experiment::read_point_file(data + "/offset_pair_a.xyz");
  const std::vector<Vec3> b = experiment::read_point_file(data + "/offset_pair_b.xyz");
  auto answer = [&](FclSolver solver, int blocks) {
    std::vector<std::unique_ptr<char[]>> held;  // moves CGAL's hull elsewhere on the heap
    for (int k = 0; k < blocks; ++k)
      held.emplace_back(std::make_unique<char[]>(16 + (k * 37 * (blocks % 7 + 3)) % 9000));
    const FclShape sa{Polytope(a)}, sb{Polytope(b)};
    return fcl_query(sa, sb, solver);
  };
  for (const FclSolver solver : {FclSolver::libccd, FclSolver::indep}) {
    INFO((solver == FclSolver::libccd ? "fcl-libccd" : "fcl-indep"));
    const PenetrationResult first = answer(solver, 0);
    CHECK_FALSE(first.intersect);
    CHECK(std::abs(first.distance - 0.3471535258698718) <= 1e-8);  // the exact distance
    auto same = [&](const PenetrationResult& r) {
      CHECK(r.intersect == first.intersect);
      CHECK(r.distance == first.distance);
      CHECK(r.witness_a == first.witness_a);
      CHECK(r.witness_b == first.witness_b);
      CHECK(r.termination == first.termination);
    };
    for (int blocks = 1; blocks <= 400; blocks += 21)
      same(answer(solver, blocks));
    PenetrationResult other;
    std::thread([&] { other = answer(solver, 150); }).join();
    same(other);
  }
}
#endif

#ifdef GJKLAB_HAVE_BULLET
TEST_CASE("bullet: separated and overlapping boxes", "[unit][peers][bullet]") {
  const BulletShape a(cube());
  const BulletShape apart(moved(cube(), Vec3(2.5, 0.1, 0.2)));
  const BulletShape overlapping(moved(cube(), Vec3(0, 0, 1.9)));
  for (const bool epa2 : {false, true}) {
    INFO((epa2 ? "bullet-epa2" : "bullet-gjk"));
    auto query = [&](const BulletShape& b) {
      return epa2 ? bullet_epa2_query(a, b) : bullet_gjk_query(a, b);
    };
    const PenetrationResult s = query(apart);
    CHECK_FALSE(s.intersect);
    CHECK(s.termination == Termination::converged);
    CHECK(std::abs(s.distance - 0.5) <= 1e-6);
    CHECK(s.normal.x() > 0.99);
    CHECK(std::abs((s.witness_b - s.witness_a).norm() - s.distance) <= 1e-6);
    const PenetrationResult o = query(overlapping);
    CHECK(o.intersect);
    CHECK(o.termination == Termination::converged);
    CHECK(std::abs(o.depth - 0.1) <= 1e-6);
    CHECK(o.normal.z() > 0.99);
    CHECK((o.witness_a - o.witness_b - o.depth * o.normal).norm() <= 1e-6);
  }
}
#endif

TEST_CASE("depth peers against the exact oracle on seeded random pairs (reported)",
          "[unit][peers]") {
  // Disagreements are counted and reported: booleans outside the touching band (1e-10 of the
  // size) and depth errors above 1e-6 of the size.
  Rng rng(20260303);
  struct Tally {
    int queries = 0, wrong_boolean = 0, depth_off = 0, not_converged = 0;
    double worst_depth_error = 0;
  };
  std::map<std::string, Tally> tally;
  int intersecting = 0;
  constexpr int kPairs = 200;
  for (int i = 0; i < kPairs; ++i) {
    const CloudKind kind = i % 2 ? CloudKind::cube : CloudKind::sphere;
    const int na = static_cast<int>(std::round(rng.log_uniform(4, 64)));
    const int nb = static_cast<int>(std::round(rng.log_uniform(4, 64)));
    const double gap = i % 3 == 0 ? rng.log_uniform(1e-6, 1) : -rng.uniform(0.05, 1);
    const auto pair = testing::random_pair(rng, kind, na, nb, gap);
    const Polytope a(pair.a), b(pair.b);
    const double size = pair_size(pair.a, pair.b);
    const auto exact = exact::solve(pair.a, pair.b, {.depth = true});
    if (exact.intersect) ++intersecting;
    const double margin = exact.intersect ? *exact.depth : exact.distance;
    for (const auto& algorithm : experiment::algorithms()) {
      if (!algorithm.peer || !algorithm.depth) continue;
      const experiment::Outcome o = experiment::run_algorithm(algorithm, a, b, {}, {});
      Tally& t = tally[std::string(algorithm.name)];
      ++t.queries;
      if (o.termination != Termination::converged) ++t.not_converged;
      if (o.intersect != exact.intersect && margin > 1e-10 * size) ++t.wrong_boolean;
      if (o.intersect && exact.intersect && o.depth) {
        const double e = std::abs(*o.depth - *exact.depth) / size;
        t.worst_depth_error = std::max(t.worst_depth_error, e);
        if (e > 1e-6) ++t.depth_off;
      }
    }
  }
  CHECK(intersecting > kPairs / 3);
  CHECK(intersecting < kPairs);
  REQUIRE(tally.count("libccd-gjk-epa") == 1);
  for (const auto& [name, t] : tally) {
    CHECK(t.queries == kPairs);
    WARN(name << ": wrong booleans outside the band " << t.wrong_boolean << "/" << kPairs
              << ", depth error > 1e-6·size " << t.depth_off << "/" << intersecting << " (worst "
              << t.worst_depth_error << "), not converged " << t.not_converged);
  }
}
