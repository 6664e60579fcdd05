// Unit tests of the exact oracle against hand-computed rationals and against an independent
// brute force written here with GMP's C++ rationals (no CGAL in this translation unit).
//
// The brute force uses that the hull distance is the distance from the origin to the hull of
// the difference cloud D = {a − b}, whose nearest point lies in a simplex spanned by at most
// three points of D: the minimum over all points, segments and triangles of D is the exact
// answer. Its depth is the minimum over supporting planes through three points of D, and a
// point is extreme iff its distance to the hull of the other points is positive.
#include <gmpxx.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/brute_force_oracle.hpp"
#include "gjklab/exact/oracle.hpp"

using gjklab::Vec3;
namespace ex = gjklab::exact;
using namespace gjklab::testing::brute_force;

namespace {

// ---- exact rationals in the test ----

mpq_class value(const ex::Rational& r) {
  mpq_class q(r.numerator() + "/" + r.denominator(), 10);
  return q;
}

/// The oracle's rational is in lowest terms with a positive denominator and equals expected.
void require_rational(const ex::Rational& r, const mpq_class& expected) {
  mpq_class q(r.numerator() + "/" + r.denominator(), 10);
  mpq_class canonical = q;
  canonical.canonicalize();
  CHECK(canonical.get_num().get_str() == r.numerator());
  CHECK(canonical.get_den().get_str() == r.denominator());
  CHECK(canonical.get_den() >= 1);
  INFO("oracle " << r.numerator() << "/" << r.denominator() << " expected " << expected.get_str());
  CHECK(canonical == expected);
}

ex::Rational rational(const mpq_class& q) {
  mpq_class c = q;
  c.canonicalize();
  return {c.get_num().get_str(), c.get_den().get_str()};
}

/// The midpoint of two adjacent doubles, exactly.
mpq_class half_way(double a, double b) {
  return (exact(a) + exact(b)) / 2;
}

/// Is r the double nearest to x? (Checks x lies within half an ulp on each side.)
bool is_nearest(double r, const mpq_class& x) {
  if (r == 0) return abs(x) <= half_way(0, std::numeric_limits<double>::denorm_min());
  const double down = std::nextafter(r, 0.0), up = std::nextafter(r, r * 2);
  const mpq_class lo = half_way(r, down), hi = half_way(r, up);
  return r > 0 ? (lo <= x && x <= hi) : (hi <= x && x <= lo);
}

std::vector<Vec3> box(const Vec3& lo, const Vec3& hi) {
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i)
    v.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  return v;
}

std::vector<Vec3> translated(std::vector<Vec3> cloud, const Vec3& t) {
  for (Vec3& p : cloud)
    p += t;
  return cloud;
}

/// Solves and checks the answer against an exact expected squared distance.
ex::OracleAnswer check_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                                const mpq_class& expected, bool depth = false) {
  const ex::OracleAnswer ans = ex::solve(a, b, {depth});
  require_rational(ans.distance_squared, expected);
  CHECK(ans.intersect == (sgn(expected) == 0));
  CHECK(ans.distance == ex::sqrt_to_double(ans.distance_squared));
  CHECK((ans.distance == 0) == (sgn(expected) == 0));
  if (!depth || !ans.intersect) {
    CHECK_FALSE(ans.depth_squared.has_value());
    CHECK_FALSE(ans.depth.has_value());
  }
  return ans;
}

}  // namespace

TEST_CASE("exact oracle: Rational::to_double rounds to nearest, ties to even", "[unit][exact]") {
  CHECK(ex::Rational{"0", "1"}.to_double() == 0.0);
  CHECK(ex::Rational{"1", "3"}.to_double() == 1.0 / 3.0);
  CHECK(ex::Rational{"2", "3"}.to_double() == 2.0 / 3.0);
  CHECK(ex::Rational{"1", "10"}.to_double() == 0.1);
  CHECK(ex::Rational{"-7", "10"}.to_double() == -0.7);
  CHECK(ex::Rational{"1", "64"}.to_double() == 0.015625);
  // Ties: 2^53 + 1 lies half-way between 2^53 and 2^53 + 2 (even mantissa wins); likewise
  // 2^53 + 3 goes up to 2^53 + 4.
  const mpz_class two53 = mpz_class(1) << 53;
  CHECK(ex::Rational{mpz_class(two53 + 1).get_str(), "1"}.to_double() == std::ldexp(1.0, 53));
  CHECK(ex::Rational{mpz_class(two53 + 3).get_str(), "1"}.to_double() == std::ldexp(1.0, 53) + 4.0);
  // Subnormals: 2^-1075 is a tie between 0 and the least subnormal; 3·2^-1076 is not.
  const std::string two1074 = mpz_class(mpz_class(1) << 1074).get_str();
  const std::string two1075 = mpz_class(mpz_class(1) << 1075).get_str();
  const std::string two1076 = mpz_class(mpz_class(1) << 1076).get_str();
  const double tiny = std::numeric_limits<double>::denorm_min();
  CHECK(ex::Rational{"1", two1074}.to_double() == tiny);
  CHECK(ex::Rational{"1", two1075}.to_double() == 0.0);
  CHECK(ex::Rational{"3", two1076}.to_double() == tiny);
  CHECK(ex::Rational{"3", two1075}.to_double() == 2 * tiny);  // 1.5 ulp: tie to even (2)
  CHECK(ex::Rational{mpz_class(mpz_class(1) << 1024).get_str(), "1"}.to_double() ==
        std::numeric_limits<double>::infinity());
  CHECK_THROWS_AS((ex::Rational{"1", "0"}.to_double()), std::invalid_argument);
  CHECK_THROWS_AS((ex::Rational{"x", "1"}.to_double()), std::invalid_argument);

  std::mt19937_64 rng(12345);
  for (int i = 0; i < 300; ++i) {
    // Random doubles of every magnitude convert back to themselves.
    double x;
    do {
      const std::uint64_t bits = rng();
      std::memcpy(&x, &bits, sizeof x);
    } while (!std::isfinite(x));
    CHECK(rational(exact(x)).to_double() == x);
    // Random rationals with large numerators and denominators round to nearest.
    mpz_class num(std::to_string(rng()) + std::to_string(rng()));
    mpz_class den(std::to_string(rng() >> (i % 60)));
    if (den == 0) den = 1;
    num >>= static_cast<unsigned>(i % 100);
    const mpq_class q(num, den);
    INFO(num.get_str() << "/" << den.get_str());
    CHECK(is_nearest(rational(q).to_double(), q));
  }
}

TEST_CASE("exact oracle: sqrt_to_double is correctly rounded", "[unit][exact]") {
  CHECK(ex::sqrt_to_double({"0", "1"}) == 0.0);
  CHECK(ex::sqrt_to_double({"2", "1"}) == std::sqrt(2.0));
  CHECK(ex::sqrt_to_double({"1", "64"}) == 0.125);
  CHECK(ex::sqrt_to_double({"9", "4"}) == 1.5);
  CHECK(ex::sqrt_to_double({"4", "5"}) == std::sqrt(0.8));  // √0.8 is far from a tie
  CHECK(std::isnan(ex::sqrt_to_double({"-1", "4"})));
  const std::string two2148 = mpz_class(mpz_class(1) << 2148).get_str();
  CHECK(ex::sqrt_to_double({"1", two2148}) == std::numeric_limits<double>::denorm_min());

  std::mt19937_64 rng(777);
  for (int i = 0; i < 300; ++i) {
    // IEEE sqrt is correctly rounded: on exact doubles both must agree.
    double x;
    do {
      const std::uint64_t bits = rng() & ~(std::uint64_t(1) << 63);
      std::memcpy(&x, &bits, sizeof x);
    } while (!std::isfinite(x));
    CHECK(ex::sqrt_to_double(rational(exact(x))) == std::sqrt(x));
    // Random rationals: the result r satisfies lo² ≤ q ≤ hi² for the half-ulp bounds.
    mpz_class num(std::to_string(rng()) + std::to_string(rng()));
    mpz_class den(std::to_string(rng() >> (i % 60)) + std::to_string(rng() % 1000));
    if (den == 0) den = 1;
    const mpq_class q(num >> static_cast<unsigned>(i % 200), den);
    const double r = ex::sqrt_to_double(rational(q));
    const mpq_class lo = half_way(r, std::nextafter(r, 0.0));
    const mpq_class hi = half_way(r, std::nextafter(r, 2 * r + 1));
    INFO(q.get_str());
    CHECK(lo * lo <= q);
    CHECK(q <= hi * hi);
  }
}

TEST_CASE("exact oracle: invalid clouds are rejected with the cloud named", "[unit][exact]") {
  const std::vector<Vec3> good = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  const std::vector<Vec3> empty;
  std::vector<Vec3> bad = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  bad[3].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(ex::solve(empty, good), std::invalid_argument);
  CHECK_THROWS_WITH(ex::solve(empty, good), "cloud A: empty point cloud");
  CHECK_THROWS_WITH(ex::solve(good, empty), "cloud B: empty point cloud");
  CHECK_THROWS_AS(ex::solve(good, bad), std::invalid_argument);
  CHECK_THROWS_WITH(ex::solve(good, bad), "cloud B: non-finite coordinate in point 3");
  bad[3].y() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(ex::solve(bad, good), "cloud A: non-finite coordinate in point 3");
  CHECK_THROWS_AS(ex::hull_vertex_count(empty), std::invalid_argument);
  CHECK_THROWS_AS(ex::hull_vertex_count(bad), std::invalid_argument);
}

TEST_CASE("exact oracle: unit boxes separated along x", "[unit][exact]") {
  const std::vector<Vec3> a = box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  SECTION("dyadic gap 0.125") {
    const auto ans = check_distance(a, box(Vec3(1.125, 0, 0), Vec3(2.125, 1, 1)), mpq_class(1, 64));
    CHECK(ans.distance == 0.125);
    CHECK(ans.hull_vertices_a == 8);
    CHECK(ans.hull_vertices_b == 8);
  }
  SECTION("gap 0.1: exactly (double(1.1) - 1)^2") {
    const mpq_class gap = exact(1.1) - 1;
    const auto ans = check_distance(a, box(Vec3(1.1, 0.5, -0.25), Vec3(2.1, 1.5, 0.75)), gap * gap);
    CHECK(value(ans.distance_squared) != mpq_class(1, 100));
    CHECK(ans.distance == Approx(0.1).epsilon(1e-14));
  }
  SECTION("diagonal offset: nearest features are edges") {
    // B shifted by (1.25, 1.5, 0): nearest points on the edges x=1,y=1 and x=1.25,y=1.5.
    check_distance(a, box(Vec3(1.25, 1.5, 0.5), Vec3(2.25, 2.5, 1.5)),
                   mpq_class(1, 16) + mpq_class(1, 4));
  }
}

TEST_CASE("exact oracle: edge-edge and vertex-face configurations", "[unit][exact]") {
  SECTION("crossing edges of two tetrahedra") {
    // A's top edge runs along x at z = 0, B's bottom edge along y at z = 2.
    const std::vector<Vec3> a = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, -1), Vec3(0, -1, -1)};
    const std::vector<Vec3> b = {Vec3(0, -1, 2), Vec3(0, 1, 2), Vec3(1, 0, 3), Vec3(-1, 0, 3)};
    check_distance(a, b, 4);
  }
  SECTION("skew edges at an oblique angle") {
    // Segment (0,0,0)-(2,0,0) vs (1,-2,2)-(1,2,0): nearest at t = 1 and u = 3/5: d^2 = 4/5.
    const std::vector<Vec3> a = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, -1), Vec3(1, 0.5, -3)};
    const std::vector<Vec3> b = {Vec3(1, -2, 2), Vec3(1, 2, 0), Vec3(1, 0, 3), Vec3(3, 0, 3)};
    check_distance(a, b, brute_distance2(a, b));
    check_distance({Vec3(0, 0, 0), Vec3(2, 0, 0)}, {Vec3(1, -2, 2), Vec3(1, 2, 0)},
                   mpq_class(4, 5));
  }
  SECTION("vertex of a tetrahedron below the face of a box") {
    const std::vector<Vec3> a = {Vec3(0, 0, 0.5), Vec3(1, 0, -1), Vec3(-1, 1, -1),
                                 Vec3(-1, -1, -1)};
    const auto ans = check_distance(a, box(Vec3(-2, -2, 1.25), Vec3(2, 2, 2)), mpq_class(9, 16));
    CHECK(ans.distance == 0.75);
    CHECK(ans.hull_vertices_a == 4);
  }
  SECTION("vertex facing an oblique face") {
    // The plane x + y + z = 1 of the corner triangle; the point (1,1,1) is at 2/sqrt(3).
    const std::vector<Vec3> tri = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, 0)};
    check_distance(tri, {Vec3(1, 1, 1)}, mpq_class(4, 3));
  }
}

TEST_CASE("exact oracle: nested and touching shapes", "[unit][exact]") {
  const std::vector<Vec3> cube = box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  SECTION("nested cubes") {
    const auto ans = check_distance(box(Vec3(-1, -1, -1), Vec3(1, 1, 1)),
                                    box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5)), 0, true);
    REQUIRE(ans.depth_squared.has_value());
    require_rational(*ans.depth_squared, mpq_class(9, 4));
    CHECK(ans.depth == 1.5);
  }
  SECTION("point inside a tetrahedron") {
    const std::vector<Vec3> tet = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 4)};
    const auto ans = check_distance(tet, {Vec3(1, 1, 1)}, 0, true);
    // Depth of a point in a tetrahedron: distance to the nearest face plane, here the slanted
    // face x + y + z = 4 at (4 - 3)/sqrt(3).
    require_rational(*ans.depth_squared, mpq_class(1, 3));
  }
  SECTION("face contact") {
    const auto ans = check_distance(cube, box(Vec3(1, 0.25, 0.25), Vec3(2, 0.75, 0.75)), 0, true);
    REQUIRE(ans.depth_squared.has_value());
    require_rational(*ans.depth_squared, 0);
    CHECK(*ans.depth == 0.0);
  }
  SECTION("vertex-vertex contact") {
    const auto ans = check_distance(cube, box(Vec3(1, 1, 1), Vec3(2, 2, 2)), 0, true);
    require_rational(*ans.depth_squared, 0);
  }
  SECTION("edge-edge contact") {
    const std::vector<Vec3> a = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, -1), Vec3(0, -1, -1)};
    const std::vector<Vec3> b = {Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(1, 0, 1), Vec3(-1, 0, 1)};
    const auto ans = check_distance(a, b, 0, true);
    require_rational(*ans.depth_squared, 0);
  }
  SECTION("flat overlapping polygons: no interior, depth 0") {
    const std::vector<Vec3> sq = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    const std::vector<Vec3> tri = {Vec3(0.5, 0.5, 0), Vec3(2, 0.5, 0), Vec3(0.5, 2, 0)};
    const auto ans = check_distance(sq, tri, 0, true);
    require_rational(*ans.depth_squared, 0);
  }
  SECTION("depth is not computed unless requested") {
    const auto ans = check_distance(cube, cube, 0, false);
    CHECK_FALSE(ans.depth_squared.has_value());
  }
}

TEST_CASE("exact oracle: single points, duplicates and triangles", "[unit][exact]") {
  const std::vector<Vec3> tri = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  check_distance({Vec3(0.25, 0.25, 1)}, tri, 1);
  check_distance({Vec3(2, 2, 0)}, tri, mpq_class(9, 2));  // to the edge x + y = 1
  check_distance({Vec3(-3, 0.5, 0)}, tri, 9);             // to the edge x = 0
  check_distance({Vec3(0.25, 0.25, 0)}, tri, 0);          // in the triangle
  check_distance({Vec3(3, 4, 0)}, {Vec3(0, 0, 0)}, 25);
  const std::vector<Vec3> dup(5, Vec3(0.25, 0.25, -2));
  const auto ans = check_distance(dup, tri, 4);
  CHECK(ans.hull_vertices_a == 1);
  CHECK(ans.hull_vertices_b == 3);
  std::vector<Vec3> tri_dup = tri;
  tri_dup.insert(tri_dup.end(), tri.begin(), tri.end());
  CHECK(check_distance(dup, tri_dup, 4).hull_vertices_b == 3);
}

TEST_CASE("exact oracle: segments and collinear clouds", "[unit][exact]") {
  const std::vector<Vec3> seg = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  check_distance(seg, {Vec3(0, 1, 1), Vec3(0, 1, 2)}, 2);
  check_distance(seg, {Vec3(0.5, -1, 1), Vec3(0.5, 1, 1)}, 1);  // crossing skew segments
  check_distance(seg, {Vec3(2, 0, 0), Vec3(3, 0, 0)}, 1);       // collinear, disjoint
  check_distance(seg, {Vec3(1, 0, 0), Vec3(3, 0, 0)}, 0);       // collinear, touching
  const std::vector<Vec3> line = {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(1, 0, 0), Vec3(0.25, 0, 0),
                                  Vec3(0.5, 0, 0)};
  const auto ans = check_distance(line, {Vec3(1, -2, 2), Vec3(1, 2, 0)}, mpq_class(4, 5));
  CHECK(ans.hull_vertices_a == 2);
  CHECK(ans.hull_vertices_b == 2);
  // A slanted collinear cloud against a point: the exact foot of the perpendicular.
  const std::vector<Vec3> slant = {Vec3(0, 0, 0), Vec3(1, 2, 3), Vec3(2, 4, 6), Vec3(0.5, 1, 1.5)};
  check_distance(slant, {Vec3(1, 0, 0)}, mpq_class(13, 14));
}

TEST_CASE("exact oracle: coplanar polygons", "[unit][exact]") {
  const std::vector<Vec3> square = {Vec3(0, 0, 0),   Vec3(1, 0, 0),   Vec3(1, 1, 0),
                                    Vec3(0, 1, 0),   Vec3(0.5, 0, 0), Vec3(1, 0.5, 0),
                                    Vec3(0.5, 1, 0), Vec3(0, 0.5, 0), Vec3(0.5, 0.5, 0)};
  SECTION("same plane, separated") {
    const auto ans =
        check_distance(square, {Vec3(1.5, 0, 0), Vec3(3, 0, 0), Vec3(3, 1, 0)}, mpq_class(1, 4));
    CHECK(ans.hull_vertices_a == 4);
    CHECK(ans.hull_vertices_b == 3);
  }
  SECTION("same plane, corner to corner") {
    check_distance(square, {Vec3(2, 2, 0), Vec3(3, 2, 0), Vec3(2, 3, 0)}, 2);
  }
  SECTION("parallel planes, overlapping projections") {
    check_distance(square, translated(square, Vec3(0.5, 0.5, 0.75)), mpq_class(9, 16));
  }
  SECTION("crossing planes") {
    // A vertical triangle piercing the square's plane outside the square.
    check_distance(square, {Vec3(1.5, 0.5, -1), Vec3(1.5, 0.5, 1), Vec3(2.5, 0.5, 0)},
                   mpq_class(1, 4));
    check_distance(square, {Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(2.5, 0.5, 0)}, 0);
  }
}

TEST_CASE("exact oracle: tiny and offset coordinates", "[unit][exact]") {
  const std::vector<Vec3> a = box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const std::vector<Vec3> b = {Vec3(1.25, 0.5, 0.5), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(2, 0, 1)};
  const std::vector<Vec3> s = {Vec3(0, 0, 0), Vec3(2, 0, 0)};
  const std::vector<Vec3> t = {Vec3(1, -2, 2), Vec3(1, 2, 0)};
  SECTION("translation by 2^30 leaves exact distances unchanged") {
    const Vec3 shift(1 << 30, 1 << 30, 1 << 30);
    check_distance(translated(a, shift), translated(b, shift), mpq_class(1, 16));
    check_distance(translated(s, shift), translated(t, shift), mpq_class(4, 5));
    check_distance(translated(a, shift), translated(a, shift + Vec3(1, 0, 0)), 0, true);
  }
  SECTION("offset by 1e9: the exact answer is that of the rounded coordinates") {
    const Vec3 shift(1e9, -1e9, 1e9);
    const auto a9 = translated(a, shift + Vec3(0.1, 0.2, 0.3));
    const auto b9 = translated(b, shift + Vec3(0.1, 0.2, 0.3));
    check_distance(a9, b9, brute_distance2(a9, b9));
    const auto s9 = translated(s, shift + Vec3(0.3, 0, 0)), t9 = translated(t, shift);
    check_distance(s9, t9, brute_distance2(s9, t9));
  }
  SECTION("coordinates scaled by 2^-40") {
    const double k = std::ldexp(1.0, -40);
    std::vector<Vec3> ak = a, bk = b, sk = s, tk = t;
    for (auto* cloud : {&ak, &bk, &sk, &tk})
      for (Vec3& p : *cloud)
        p *= k;
    const mpq_class k2 = exact(k) * exact(k);
    check_distance(ak, bk, k2 / 16);
    check_distance(sk, tk, k2 * mpq_class(4, 5));
  }
  SECTION("coordinates around 1e200: squared distances beyond the double range") {
    for (const double k : {1e160, 1e200}) {
      std::vector<Vec3> sk = s, tk = t, ak = a, bk = b;
      for (auto* cloud : {&sk, &tk, &ak, &bk})
        for (Vec3& p : *cloud)
          p *= k;
      const mpq_class k2 = exact(k) * exact(k);
      const auto ans = check_distance(sk, tk, k2 * mpq_class(4, 5));
      CHECK(ans.distance == Approx(k * std::sqrt(0.8)).epsilon(1e-12));
      check_distance(ak, bk, brute_distance2(ak, bk));  // 1.25 * k is rounded
    }
  }
  SECTION("coordinates around 1e-7 and 1e-300") {
    for (const double k : {1e-7, 1e-300}) {
      std::vector<Vec3> sk = s, tk = t;
      for (Vec3& p : sk)
        p *= k;
      for (Vec3& p : tk)
        p *= k;
      const auto ans = check_distance(sk, tk, brute_distance2(sk, tk));
      CHECK(ans.distance == Approx(k * std::sqrt(0.8)).epsilon(1e-12));
    }
  }
}

TEST_CASE("exact oracle: point vs degenerate triangle (regression)", "[unit][exact]") {
  const std::vector<Vec3> point = {Vec3(1.1, -7.9, 16.588)};
  const std::vector<Vec3> tri = {Vec3(2.277, -7.9, 16.318), Vec3(-0.57, -8.1, 16.607),
                                 Vec3(-0.57, -8.1, 16.607)};
  // Independently: the exact squared distance from the point to the segment.
  const mpq_class expected = point_segment_distance2(exact(point[0]), exact(tri[0]), exact(tri[1]));
  const auto ans = check_distance(point, tri, expected);
  CHECK(ans.distance > 0.17);
  CHECK(ans.distance < 0.172);
  CHECK(ans.hull_vertices_b == 2);
  CHECK(ans.distance_squared.denominator() != "1");
}

TEST_CASE("exact oracle: penetration depth of boxes", "[unit][exact]") {
  SECTION("side-2 boxes centred at (0,0,0) and (0,0,1.9)") {
    const std::vector<Vec3> a = box(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    const double c = 1.9;
    const std::vector<Vec3> b = box(Vec3(-1, -1, c - 1.0), Vec3(1, 1, c + 1.0));
    const ex::OracleAnswer ans = check_distance(a, b, 0, true);
    REQUIRE(ans.depth_squared.has_value());
    // A − B spans z in [-1 - (c+1), 1 - (c-1)]; the nearest face is z = 1 - (c-1) = 2 - c
    // (c - 1.0 is exact in double).
    const mpq_class d = 1 - exact(c - 1.0);
    CHECK(d == 2 - exact(c));
    require_rational(*ans.depth_squared, d * d);
    CHECK(*ans.depth == Approx(0.1).epsilon(1e-14));
    CHECK(*ans.depth == ex::sqrt_to_double(*ans.depth_squared));
  }
  SECTION("off-centre nested cubes") {
    const auto ans = check_distance(box(Vec3(-1, -1, -1), Vec3(1, 1, 1)),
                                    box(Vec3(-0.25, -0.5, -0.5), Vec3(0.75, 0.5, 0.5)), 0, true);
    require_rational(*ans.depth_squared, mpq_class(25, 16));  // x-range of A − B: [-1.75, 1.25]
  }
  SECTION("tilted tetrahedron in a box: depth against the brute force") {
    const std::vector<Vec3> a = box(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    const std::vector<Vec3> b = {Vec3(0.1, 0.3, 0.2), Vec3(0.9, -0.3, 0.1), Vec3(-0.2, 0.7, 0.4),
                                 Vec3(0.3, 0.1, 1.3)};
    const auto ans = check_distance(a, b, 0, true);
    require_rational(*ans.depth_squared, brute_depth2(a, b));
  }
}

TEST_CASE("exact oracle: hull_vertex_count", "[unit][exact]") {
  CHECK(ex::hull_vertex_count(std::vector<Vec3>{Vec3(1, 2, 3)}) == 1);
  CHECK(ex::hull_vertex_count(std::vector<Vec3>(7, Vec3(1, 2, 3))) == 1);
  CHECK(ex::hull_vertex_count(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(-0.0, 0, 0)}) == 1);
  CHECK(ex::hull_vertex_count(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(0.5, 0.5, 0.5),
                                                Vec3(2, 2, 2), Vec3(2, 2, 2)}) == 2);
  // Square with edge midpoints and centre (axis-aligned and in a tilted plane).
  std::vector<Vec3> square;
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; j <= 2; ++j)
      square.emplace_back(0.5 * i, 0.5 * j, 0.25);
  CHECK(ex::hull_vertex_count(square) == 4);
  std::vector<Vec3> tilted;
  for (const Vec3& p : square)
    tilted.emplace_back(p.x(), p.y(), p.x() + 3 * p.y());
  CHECK(ex::hull_vertex_count(tilted) == 4);
  std::vector<Vec3> vertical;
  for (const Vec3& p : square)
    vertical.emplace_back(p.x(), 2.0, p.y());
  CHECK(ex::hull_vertex_count(vertical) == 4);
  // Triangle in the plane x + y + z = 1 with edge midpoints.
  CHECK(ex::hull_vertex_count(std::vector<Vec3>{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                                                Vec3(0.5, 0.5, 0), Vec3(0, 0.5, 0.5)}) == 3);
  // Cube with interior points, face centres and edge midpoints: the 3x3x3 grid.
  std::vector<Vec3> grid;
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; j <= 2; ++j)
      for (int k = 0; k <= 2; ++k)
        grid.emplace_back(i, j, k);
  CHECK(ex::hull_vertex_count(grid) == 8);
  std::vector<Vec3> cube = box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  cube.emplace_back(0.5, 0.5, 0.5);
  cube.emplace_back(0.25, 0.75, 0.5);
  CHECK(ex::hull_vertex_count(cube) == 8);
  // Octahedron with its centre; square pyramid whose apex is above a face centre.
  CHECK(ex::hull_vertex_count(std::vector<Vec3>{Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0),
                                                Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1),
                                                Vec3(0, 0, 0)}) == 6);
  // Points on a 4x4x4 grid in a tetrahedron (many on faces and edges): 4 corners.
  std::vector<Vec3> tet;
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; i + j <= 3; ++j)
      for (int k = 0; i + j + k <= 3; ++k)
        tet.emplace_back(i, j, k);
  CHECK(ex::hull_vertex_count(tet) == 4);
}

namespace {

/// Compares the oracle with the brute force on `trials` random pairs of small clouds: random
/// doubles, half-integer grids (duplicates, collinear and coplanar subsets, touching pairs),
/// all-coplanar and all-collinear clouds, at unit scale, at 1e-7 and offset by ~1e9.
/// Asserts every answer; returns how many pairs intersect and how many are apart, so that the
/// caller can check the sample. `certificates` chooses the oracle's path for the distance:
/// certified by exact GJK (no hint: from the pair (0, 0)) or the QP.
struct Sample {
  int intersecting = 0, separated = 0;
};
Sample compare_with_brute_force(std::uint64_t seed, int trials, int max_a, int max_b,
                                bool certificates = true) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> small(-2, 2);
  auto random_cloud = [&](int size, int kind, const Vec3& shift, double scale) {
    std::vector<Vec3> cloud;
    for (int i = 0; i < size; ++i) {
      Vec3 p;
      if (kind == 0)
        p = Vec3(unit(rng), unit(rng), unit(rng));
      else
        p = Vec3(small(rng), small(rng), small(rng)) * 0.5;        // many degeneracies
      if (kind == 2) p.z() = 0.5;                                  // coplanar
      if (kind == 3) p = Vec3(p.x(), 2 * p.x() - 1, 0.5 - p.x());  // collinear
      cloud.push_back(scale * p + shift);
    }
    return cloud;
  };
  int intersecting = 0, separated = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const int na = 1 + trial % max_a, nb = 1 + (trial / max_a) % max_b;
    const double scale = trial % 6 == 5 ? 1e-7 : 1.0;
    const Vec3 base = trial % 4 == 3 ? Vec3(1e9, -2e9, 3e9) : Vec3(0, 0, 0);
    const Vec3 offset(0.4 * (trial % 3), 0.3 * (trial % 2), 0);
    const std::vector<Vec3> a = random_cloud(na, trial % 4, base, scale);
    const std::vector<Vec3> b = random_cloud(nb, (trial / 4) % 4, base + scale * offset, scale);
    INFO("seed " << seed << " trial " << trial);
    const ex::OracleAnswer ans = ex::solve(a, b, {.depth = true, .certificates = certificates});
    CHECK(ans.method == (certificates ? ex::AnswerMethod::certified : ex::AnswerMethod::qp));
    require_rational(ans.distance_squared, brute_distance2(a, b));
    CHECK(ans.distance == ex::sqrt_to_double(ans.distance_squared));
    CHECK(ans.hull_vertices_a == brute_hull_vertex_count(a));
    CHECK(ans.hull_vertices_b == brute_hull_vertex_count(b));
    if (ans.intersect) {
      ++intersecting;
      REQUIRE(ans.depth_squared.has_value());
      require_rational(*ans.depth_squared, brute_depth2(a, b));
      CHECK(*ans.depth == ex::sqrt_to_double(*ans.depth_squared));
    } else {
      ++separated;
      CHECK_FALSE(ans.depth_squared.has_value());
    }
  }
  return {intersecting, separated};
}

}  // namespace

TEST_CASE("exact oracle: agrees with an independent brute force on small random clouds",
          "[unit][exact]") {
  // Every answer by either path, on samples where both answers occur (a tenth each at least).
  for (const bool certificates : {true, false}) {
    const Sample s = compare_with_brute_force(20240611 + certificates, 240, 5, 4, certificates);
    CHECK(s.intersecting >= 24);
    CHECK(s.separated >= 24);
  }
}

// A longer run of the same comparison (hidden; run with "[exact-stress]").
TEST_CASE("exact oracle: brute-force comparison, long run", "[.][exact-stress]") {
  for (std::uint64_t seed = 1; seed <= 20; ++seed)
    for (bool certificates : {true, false}) {
      const Sample s = compare_with_brute_force(seed, 200, 6, 5, certificates);
      CHECK(s.intersecting >= 20);
      CHECK(s.separated >= 20);
    }
  // Hull vertex counts of larger clouds on a coarse grid (many points on facets and edges).
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<int> coord(0, 3);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Vec3> cloud;
    const int size = 4 + trial % 10;
    for (int i = 0; i < size; ++i) {
      Vec3 p(coord(rng), coord(rng), coord(rng));
      if (trial % 3 == 1) p.z() = p.x() + p.y();  // a tilted plane
      cloud.push_back(p);
    }
    INFO("trial " << trial);
    CHECK(ex::hull_vertex_count(cloud) == brute_hull_vertex_count(cloud));
  }
}
