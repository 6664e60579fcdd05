// The separating axis test: known boxes, lower-dimensional shapes, agreement with the exact
// oracle on seeded random pairs, and (hidden tag [.sat-scaling]) its cost against GJK.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <vector>

#include "../support/random_pairs.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/gjk/epa.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/peers/sat.hpp"

using namespace gjklab;
using peers::SatOptions;
using peers::SatResult;
using peers::SatShape;
using testing::CloudKind;
using testing::Rng;

namespace {

Polytope moved(const Polytope& p, const Vec3& t) {
  return p.transformed(Pose::from_translation(t));
}

SatResult sat(const Polytope& a, const Polytope& b, const SatOptions& o = {}) {
  return peers::sat_query(SatShape(a.vertices()), SatShape(b.vertices()), o);
}

Pose rotation_about(const Vec3& axis, double angle, const Vec3& t = Vec3::Zero()) {
  return {Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(), t};
}

/// SAT against the exact oracle on one pair: the boolean (outside the touching band) and
/// the depth of intersecting pairs. Returns whether the boolean was inside the band.
bool check_against_exact(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                         double band = 1e-10, double depth_tolerance = 1e-12) {
  const auto exact = exact::solve(a, b, {.depth = true});
  const SatResult r = peers::sat_query(SatShape(a), SatShape(b));
  const double size = pair_size(a, b);
  CHECK(r.termination == Termination::converged);
  const double margin = exact.intersect ? *exact.depth : exact.distance;
  const bool in_band = margin <= band * size;
  if (!in_band) CHECK(r.intersect == exact.intersect);
  if (exact.intersect && r.intersect)
    CHECK(std::abs(r.depth - *exact.depth) <= depth_tolerance * size);
  if (!exact.intersect && !r.intersect) CHECK(r.separation <= exact.distance * (1 + 1e-14));
  return in_band;
}

}  // namespace

TEST_CASE("sat: separated and overlapping boxes", "[unit][sat]") {
  const Polytope box = shapes::box();
  SECTION("face-face gap") {
    const SatResult r = sat(box, moved(box, Vec3(1.5, 0.2, 0.1)));
    CHECK_FALSE(r.intersect);
    CHECK(r.separation == Approx(0.5).epsilon(1e-15));
    CHECK(r.normal.isApprox(Vec3::UnitX(), 1e-15));
    CHECK(r.depth == 0);
    CHECK(r.support_calls == 2 * r.axes_tested);
  }
  SECTION("overlap along x") {
    const SatResult r = sat(box, moved(box, Vec3(0.5, 0.25, 0)));
    CHECK(r.intersect);
    CHECK(std::abs(r.depth - 0.5) <= 1e-15);
    CHECK(r.normal.isApprox(Vec3::UnitX(), 1e-15));
    CHECK(r.axes_tested == 6 + 6 + 6);  // face normals; 9 edge pairs, 6 of them parallel
  }
  SECTION("cubes of side 2 at z = 0 and z = 1.9") {
    const Polytope cube = shapes::box(Vec3(2, 2, 2));
    const SatResult r = sat(cube, moved(cube, Vec3(0, 0, 1.9)));
    CHECK(r.intersect);
    CHECK(std::abs(r.depth - 0.1) <= 1e-15);
    CHECK(r.normal.isApprox(Vec3::UnitZ(), 1e-15));
  }
  SECTION("edge-edge separation along a cross product") {
    const Polytope a = box.transformed(rotation_about(Vec3::UnitY(), M_PI / 4));
    const Polytope b = box.transformed(rotation_about(Vec3::UnitZ(), M_PI / 4, Vec3(2, 0, 0)));
    SatOptions all;
    all.early_exit = false;
    const SatResult r = sat(a, b, all);
    CHECK_FALSE(r.intersect);
    CHECK(std::abs(r.separation - (2 - std::sqrt(2.0))) <= 1e-15);
    const SatResult first = sat(a, b);
    CHECK_FALSE(first.intersect);
    CHECK(first.axes_tested <= r.axes_tested);
  }
  SECTION("touching boxes intersect with depth 0") {
    const SatResult r = sat(box, moved(box, Vec3(1, 0.25, 0.5)));
    CHECK(r.intersect);
    CHECK(r.depth == 0);
  }
}

TEST_CASE("sat: flat, collinear and point shapes agree with the exact oracle", "[unit][sat]") {
  const std::vector<Vec3> tri = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Vec3> seg = {{0, 0, 0}, {1, 0, 0}};
  const Polytope unit_box = shapes::box();
  const std::vector<Vec3> box(unit_box.vertices().begin(), unit_box.vertices().end());
  auto shift = [](std::vector<Vec3> p, const Vec3& t) {
    for (Vec3& v : p)
      v += t;
    return p;
  };
  struct Pair {
    const char* name;
    std::vector<Vec3> a, b;
    bool intersect;
  };
  const std::vector<Pair> pairs = {
      {"coplanar triangles overlapping", tri, shift(tri, {0.2, 0.2, 0}), true},
      {"coplanar triangles apart in the plane", tri, shift(tri, {0.7, 0.7, 0}), false},
      {"triangles in parallel planes", tri, shift(tri, {0.1, 0.1, 0.5}), false},
      {"triangle through a box", box, shift(tri, {-0.2, -0.2, 0.1}), true},
      {"coplanar skew segments apart", seg, {{0, 1, 0}, {1, 0.2, 0}}, false},
      {"coplanar segments crossing", seg, {{0.5, -1, 0}, {0.5, 1, 0}}, true},
      {"skew segments", seg, {{0.5, -1, 0.1}, {0.5, 1, 0.1}}, false},
      {"collinear segments apart", seg, shift(seg, {2, 0, 0}), false},
      {"collinear segments overlapping", seg, shift(seg, {0.5, 0, 0}), true},
      {"parallel segments apart", seg, shift(seg, {0.3, 1, 0}), false},
      {"segment and a point off it", seg, {{0.5, 0.5, 0.5}}, false},
      {"segment and a point on it", seg, {{0.25, 0, 0}}, true},
      {"segment through a triangle", tri, {{0.2, 0.2, -1}, {0.2, 0.2, 1}}, true},
      {"segment in the triangle's plane, outside", tri, {{1, 1, 0}, {2, 0.5, 0}}, false},
      {"point in the triangle's plane, outside", tri, {{0.8, 0.8, 0}}, false},
      {"point inside the triangle", tri, {{0.2, 0.2, 0}}, true},
      {"two points", {{1, 2, 3}}, {{1, 2, 3.5}}, false},
      {"equal points", {{1, 2, 3}}, {{1, 2, 3}}, true},
  };
  for (const Pair& p : pairs) {
    INFO(p.name);
    const auto exact = exact::solve(p.a, p.b);
    REQUIRE(exact.intersect == p.intersect);
    const SatResult r = peers::sat_query(SatShape(p.a), SatShape(p.b));
    CHECK(r.intersect == p.intersect);
    check_against_exact(p.a, p.b);
  }
}

TEST_CASE("sat: agrees with the exact oracle on seeded random pairs", "[unit][sat]") {
  // Booleans must agree outside the touching band (1e-10 of the pair's size); depths of
  // intersecting pairs within 1e-12 of the size.
  Rng rng(20260302);
  int intersecting = 0, separated = 0, in_band = 0;
  for (int i = 0; i < 300; ++i) {
    const CloudKind kind = i % 2 ? CloudKind::cube : CloudKind::sphere;
    const int na = static_cast<int>(std::round(rng.log_uniform(4, 32)));
    const int nb = static_cast<int>(std::round(rng.log_uniform(4, 32)));
    const double gap = (i % 4 < 2)    ? rng.log_uniform(1e-9, 1)
                       : (i % 4 == 2) ? -rng.log_uniform(1e-9, 0.1)
                                      : -rng.uniform(0.1, 1.0);
    const auto pair = testing::random_pair(rng, kind, na, nb, gap);
    INFO("pair " << i);
    if (check_against_exact(pair.a, pair.b)) ++in_band;
    (exact::solve(pair.a, pair.b).intersect ? intersecting : separated) += 1;
  }
  // Flat clouds: both in the plane z = 0, or in parallel planes, and segments.
  int flat_pairs = 0;
  for (int i = 0; i < 100; ++i) {
    auto flat = [&](int n, double z) {
      std::vector<Vec3> p;
      const int kind = i % 3;  // polygon, segment, polygon vs segment
      const int count = kind == 1 ? 2 : n;
      for (int k = 0; k < count; ++k)
        p.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), z);
      return p;
    };
    const double dz = i % 5 == 0 ? 0.25 : 0.0;
    std::vector<Vec3> a = flat(rng.integer(3, 12), 0.0), b = flat(rng.integer(3, 12), dz);
    const Vec3 t(rng.uniform(-2, 2), rng.uniform(-2, 2), 0);
    for (Vec3& v : b)
      v += t;
    INFO("flat pair " << i);
    if (check_against_exact(a, b)) ++in_band;
    ++flat_pairs;
  }
  CHECK(intersecting > 50);
  CHECK(separated > 50);
  WARN("sat vs exact: " << intersecting << " intersecting, " << separated
                        << " separated random pairs, " << flat_pairs << " flat pairs; " << in_band
                        << " inside the touching band (booleans not compared)");
}

TEST_CASE("sat: scaling with the vertex count, against GJK", "[.sat-scaling]") {
  // Median wall time per query on random sphere points, n points per shape; SAT on prepared
  // shapes (hull features computed before timing). Reports only; asserts agreement.
  using Clock = std::chrono::steady_clock;
  Rng rng(99);
  std::ostringstream table;
  table << "n  pairs | sat overlap (us)  sat separated (us)  axes(overlap) | gjk-johnson (us)  "
           "gjk-bool (us)  epa overlap (us)\n";
  for (int n = 8; n <= 512; n *= 2) {
    const int pairs = n >= 256 ? 3 : 9;
    std::vector<double> sat_in, sat_out, gjk, gbool, epa;
    long axes = 0;
    for (int p = 0; p < pairs; ++p) {
      for (const double gap : {-0.3, 0.05}) {
        const auto pair = testing::random_pair(rng, CloudKind::sphere, n, n, gap);
        const Polytope a(pair.a), b(pair.b);
        const SatShape sa(pair.a), sb(pair.b);
        auto time = [](auto&& f, int reps) {
          std::vector<double> us;
          for (int r = 0; r < reps; ++r) {
            const auto t0 = Clock::now();
            f();
            us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
          }
          std::nth_element(us.begin(), us.begin() + reps / 2, us.end());
          return us[reps / 2];
        };
        SatResult s;
        const int reps = n >= 256 ? 3 : 21;
        const double t_sat = time([&] { s = peers::sat_query(sa, sb); }, reps);
        const DistanceResult d = gjk_distance(a, b);
        CHECK(s.intersect == d.intersect);
        (gap < 0 ? sat_in : sat_out).push_back(t_sat);
        if (gap < 0) axes += s.axes_tested;
        gjk.push_back(time([&] { (void)gjk_distance(a, b); }, 101));
        gbool.push_back(time([&] { (void)gjk_intersect(a, b); }, 101));
        if (gap < 0) epa.push_back(time([&] { (void)gjk_epa(a, b); }, 51));
      }
    }
    auto median = [](std::vector<double> v) {
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return v[v.size() / 2];
    };
    table << n << "  " << pairs << " | " << median(sat_in) << "  " << median(sat_out) << "  "
          << axes / pairs << " | " << median(gjk) << "  " << median(gbool) << "  " << median(epa)
          << "\n";
  }
  WARN(table.str());
}
