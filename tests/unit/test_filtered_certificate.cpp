// The distance certificate decided in floating point (src/exact/certificates/filtered_distance.cpp): where it
// answers, the exact certificate on the same hint answers the same, bit for bit, and the QP
// agrees; on adversarial hints it never certifies a wrong value; points that tie with the
// supporting plane are decided exactly, including a tie broken by one ulp; the long double
// rounding of a weighted sum of points is right or declines, never wrong.
#include <gmpxx.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "../../src/exact/certificates/filtered_distance.hpp"
#include "../../src/exact/arithmetic/gmp_support.hpp"
#include "../support/gjk_hints.hpp"
#include "gjklab/exact/certificate.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

using namespace gjklab;
using exact::DistanceHint;
using exact::detail::certify_distance_exact;
using exact::detail::certify_distance_filtered;
using gjklab::testing::gjk_hint;

namespace {

using Cloud = std::vector<Vec3>;

exact::OracleAnswer qp(const Cloud& a, const Cloud& b) {
  return exact::solve(a, b, {.certificates = false, .hull_vertices = false});
}

/// n points of a family around `centre`, at scale `size`: on a sphere, on a grid of small
/// integers (many exact ties with any axis-aligned plane), or flat (all at z = centre.z).
Cloud cloud(std::mt19937_64& rng, int family, int n, const Vec3& centre, double size) {
  std::normal_distribution<double> normal(0, 1);
  std::uniform_int_distribution<int> cell(-2, 2);
  Cloud out;
  for (int i = 0; i < n; ++i) {
    Vec3 p;
    if (family == 0) p = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    if (family == 1) p = Vec3(cell(rng), cell(rng), cell(rng)) / 2;
    if (family == 2) p = Vec3(normal(rng), normal(rng), 0);
    out.push_back(centre + size * p);
  }
  return out;
}

void require_same(const exact::DistanceCertificate& f, const exact::DistanceCertificate& e) {
  CHECK(f.intersect == e.intersect);
  CHECK(f.distance == e.distance);
  CHECK(f.distance_squared == e.distance_squared);
  CHECK(f.witness_a == e.witness_a);
  CHECK(f.witness_b == e.witness_b);
  CHECK(f.feature.simplex == e.feature.simplex);
  CHECK(f.repair_steps == 0);
}

}  // namespace

TEST_CASE("filtered distance certificate: the exact certificate's answer on GJK hints",
          "[certificate][exact]") {
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> gap(0.05, 0.6);  // separated: intersections go exact
  const double scales[] = {1.0, 1e-150, 1e150, 3.0e-7};
  int filtered = 0, total = 0, plain_filtered = 0, plain_total = 0;
  for (int round = 0; round < 1200; ++round) {
    const int family = round % 3;
    const double size = scales[(round / 3) % 4];
    const int n = 4 + static_cast<int>(rng() % 60);
    const Cloud a = cloud(rng, family, n, Vec3::Zero(), size);
    const Cloud b = cloud(rng, family, n, Vec3(2 + gap(rng), 0.25, 0.1) * size, size);
    const DistanceHint hint = gjk_hint(a, b);
    const auto f = certify_distance_filtered(a, b, hint);
    ++total;
    if (family == 0 && size == 1.0) ++plain_total;
    if (!f) continue;
    ++filtered;
    if (family == 0 && size == 1.0) ++plain_filtered;
    INFO("round " << round << ", family " << family << ", scale " << size);
    const auto e = certify_distance_exact(a, b, hint, 0);
    REQUIRE(e);  // the same hint proves the answer exactly, with no repair step
    require_same(*f, *e);
    if (round % 10 == 0) CHECK(f->distance_squared == qp(a, b).distance_squared);
  }
  // The fast path is what makes the oracle cheap: it must answer nearly every plain pair.
  CHECK(plain_filtered >= plain_total * 95 / 100);
  CHECK(filtered >= total / 2);
}

TEST_CASE("filtered distance certificate: adversarial hints never certify a wrong value",
          "[certificate][exact]") {
  std::mt19937_64 rng(7);
  int rejected = 0, certified = 0;
  for (int round = 0; round < 600; ++round) {
    const int n = 4 + static_cast<int>(rng() % 12);
    const Cloud a = cloud(rng, round % 3, n, Vec3::Zero(), 1);
    const Cloud b = cloud(rng, round % 3, n, Vec3(1.5, 0.2, 0), 1);
    DistanceHint hint = gjk_hint(a, b);
    const auto index = [&] { return static_cast<std::int32_t>(rng() % n); };
    switch (round % 5) {
      case 0:  // one index replaced
        hint.simplex[rng() % hint.simplex.size()] = {index(), index()};
        break;
      case 1:  // an extra pair
        if (hint.simplex.size() < 4) hint.simplex.push_back({index(), index()});
        break;
      case 2:  // two pairs that share no index: not one connected feature
        hint.simplex = {{0, 0}, {1, 1}};
        break;
      case 3:  // a random simplex
        hint.simplex.assign(1 + rng() % 3, {0, 0});
        for (auto& p : hint.simplex)
          p = {index(), index()};
        break;
      default:  // out of range
        hint.simplex.push_back({n, 0});
        break;
    }
    const auto f = certify_distance_filtered(a, b, hint);
    if (!f) {
      ++rejected;
      continue;
    }
    ++certified;
    const exact::OracleAnswer truth = qp(a, b);
    INFO("round " << round);
    CHECK(f->distance_squared == truth.distance_squared);
    CHECK(f->intersect == truth.intersect);
  }
  CHECK(rejected > 0);
  CHECK(certified > 0);
}

TEST_CASE("filtered distance certificate: coplanar faces tie and are decided exactly",
          "[certificate][exact]") {
  // Two unit cubes face to face at distance 1: four vertices of each lie on its supporting
  // plane, which the double scan cannot decide.
  Cloud a, b;
  for (int i = 0; i < 8; ++i) {
    a.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    b.emplace_back(2 + (i & 1), (i >> 1) & 1, (i >> 2) & 1);
  }
  const DistanceHint vertex_pair{{{1, 0}}};  // a = (1, 0, 0), b = (2, 0, 0)
  const auto f = certify_distance_filtered(a, b, vertex_pair);
  REQUIRE(f);
  CHECK(f->distance == 1.0);
  CHECK(f->distance_squared == exact::Rational("1", "1"));

  // One vertex of A one ulp beyond the plane: the tie breaks the wrong way, the filtered
  // certificate declines, and the exact path still finds the distance.
  a[7] = Vec3(std::nextafter(1.0, 2.0), 1, 1);
  CHECK_FALSE(certify_distance_filtered(a, b, vertex_pair));
  const auto c = exact::certify_distance(a, b, vertex_pair);
  REQUIRE(c);
  CHECK(c->distance_squared == qp(a, b).distance_squared);
  CHECK(c->distance < 1.0);
}

TEST_CASE("long double witness rounding: right or undecided, never wrong", "[certificate][exact]") {
  // Σ λ_k x_k with λ_k = w_k / D for small integers: the long double weights are within one
  // rounding of the exact ones, and the exact sum is rounded with GMP for comparison.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> weight(0, 1000);
  std::normal_distribution<double> coordinate(0, 1);
  int decided = 0;
  for (int round = 0; round < 20000; ++round) {
    const int n = 1 + static_cast<int>(rng() % 4);
    std::array<long double, 4> lambda{};
    std::array<Vec3, 4> x;
    std::array<int, 4> w{};
    int d = 0;
    for (int k = 0; k < n; ++k) {
      w[k] = weight(rng);
      d += w[k];
      // Coordinates of mixed magnitudes, some repeated so that sums land on midpoints.
      x[k] = Vec3(coordinate(rng), std::ldexp(coordinate(rng), -30), round % 7 == 0 ? 1.0 : 0.5);
    }
    if (d == 0) continue;
    if (round % 11 == 0 && n >= 2) x[1].z() = std::nextafter(x[0].z(), 2.0);  // midpoints
    for (int k = 0; k < n; ++k)
      lambda[k] = static_cast<long double>(w[k]) / d;
    const std::optional<Vec3> fast = exact::detail::nearest_weighted_sum(
        {lambda.data(), static_cast<std::size_t>(n)}, {x.data(), static_cast<std::size_t>(n)});
    if (!fast) continue;
    ++decided;
    for (int j = 0; j < 3; ++j) {
      mpq_class sum = 0;
      for (int k = 0; k < n; ++k)
        sum += mpq_class(w[k]) * mpq_class(x[k][j]);
      sum /= d;
      INFO("round " << round << ", coordinate " << j);
      CHECK((*fast)[j] == exact::detail::nearest_double(sum.get_mpq_t()));
    }
  }
  CHECK(decided > 15000);
}

TEST_CASE("filtered intersection certificate: the exact certificate's answer on GJK tetrahedra",
          "[certificate][exact]") {
  // Overlapping pairs, whose GJK hints are mostly tetrahedra around the origin: the common
  // point's rounding in double-word arithmetic equals the exact one, at every scale.
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> offset(0.0, 1.2);
  const double scales[] = {1.0, 1e-150, 1e150, 3.0e-7};
  int tetrahedra = 0, filtered = 0, plain_tetrahedra = 0, plain_filtered = 0;
  for (int round = 0; round < 1500; ++round) {
    const int family = round % 3;
    const double size = scales[(round / 3) % 4];
    const int n = 4 + static_cast<int>(rng() % 60);
    const Cloud a = cloud(rng, family, n, Vec3::Zero(), size);
    const Cloud b = cloud(rng, family, n, Vec3(offset(rng), 0.25, 0.1) * size, size);
    const DistanceHint hint = gjk_hint(a, b);
    if (hint.simplex.size() != 4) continue;
    const bool plain = family == 0 && size == 1.0;
    ++tetrahedra;
    plain_tetrahedra += plain;
    const auto f = certify_distance_filtered(a, b, hint);
    if (!f) continue;
    ++filtered;
    plain_filtered += plain;
    INFO("round " << round << ", family " << family << ", scale " << size);
    const auto e = certify_distance_exact(a, b, hint, 0);
    REQUIRE(e);
    CHECK(f->intersect);
    require_same(*f, *e);
    if (round % 10 == 0) CHECK(qp(a, b).intersect);
  }
  CHECK(tetrahedra > 300);
  CHECK(plain_filtered >= plain_tetrahedra * 95 / 100);
  CHECK(filtered >= tetrahedra / 2);
}

TEST_CASE("filtered intersection certificate: four-pair hints that do not enclose the origin",
          "[certificate][exact]") {
  // Random four pairs, on overlapping and on separated clouds: a certified intersection must
  // be one (the QP agrees) with the exact certificate's common point; most are declined.
  std::mt19937_64 rng(17);
  int rejected = 0, certified = 0;
  for (int round = 0; round < 800; ++round) {
    const int n = 4 + static_cast<int>(rng() % 12);
    const double apart = round % 2 == 0 ? 0.3 : 2.5;
    const Cloud a = cloud(rng, round % 3, n, Vec3::Zero(), 1);
    const Cloud b = cloud(rng, round % 3, n, Vec3(apart, 0.2, 0), 1);
    DistanceHint hint;
    while (hint.simplex.size() < 4) {
      const exact::IndexPair p{static_cast<std::int32_t>(rng() % n),
                               static_cast<std::int32_t>(rng() % n)};
      if (std::find(hint.simplex.begin(), hint.simplex.end(), p) == hint.simplex.end())
        hint.simplex.push_back(p);
    }
    const auto f = certify_distance_filtered(a, b, hint);
    if (!f) {
      ++rejected;
      continue;
    }
    ++certified;
    INFO("round " << round);
    CHECK(f->intersect);
    CHECK(qp(a, b).intersect);
    const auto e = certify_distance_exact(a, b, hint, 0);
    REQUIRE(e);
    require_same(*f, *e);
  }
  CHECK(rejected > 400);
  CHECK(certified > 0);
}

TEST_CASE("filtered intersection certificate: a common point on a rounding midpoint",
          "[certificate][exact]") {
  // W_k = a_k − b_k form a regular tetrahedron centred on the origin, so every weight is 1/4
  // and p_x = (1 + 1 + 2·(1 + 2^-52)) / 4 = 1 + 2^-53, halfway between 1 and its successor:
  // the filtered certificate cannot prove the rounding and must decline; exactly, the tie goes
  // to the even neighbour, 1. Moving b_3 along x by t unbalances the weights (the x rows of
  // Σ λ_k W_k = 0 no longer split them in halves), which moves p_x off the midpoint by about
  // t·2^-54: decided in double-word arithmetic for t ≥ 2^-40, equal to the exact rounding; at
  // t = 2^-52 the offset is below the evaluation's error bound, and it may decline.
  const double up = 1 + 0x1p-52;
  const std::array<Vec3, 4> w = {Vec3(0.5, 1, 1), Vec3(0.5, -1, -1), Vec3(-0.5, 1, -1),
                                 Vec3(-0.5, -1, 1)};
  const std::array<double, 4> x = {1, 1, up, up};
  Cloud a, b;
  for (int k = 0; k < 4; ++k) {
    a.emplace_back(x[k], 0.75, 0.75);
    b.push_back(a.back() - w[k]);
    REQUIRE(a.back() - b.back() == w[k]);  // exact differences
  }
  const DistanceHint hint{{{0, 0}, {1, 1}, {2, 2}, {3, 3}}};
  CHECK_FALSE(certify_distance_filtered(a, b, hint));
  const auto midpoint = exact::certify_distance(a, b, hint);
  REQUIRE(midpoint);
  CHECK(midpoint->intersect);
  CHECK(midpoint->witness_a == Vec3(1, 0.75, 0.75));

  for (const double tilt : {0x1p-40, -0x1p-40, 0x1p-20, 0x1p-52, -0x1p-52}) {
    Cloud tilted_b = b;
    tilted_b[3].x() += tilt;
    INFO("tilt " << tilt);
    const auto f = certify_distance_filtered(a, tilted_b, hint);
    const auto e = certify_distance_exact(a, tilted_b, hint, 0);
    REQUIRE(e);
    CHECK(e->witness_a.x() == (tilt > 0 ? 1.0 : up));  // off the midpoint, to either side
    if (std::fabs(tilt) >= 0x1p-40) REQUIRE(f);
    if (f) require_same(*f, *e);
  }
}
