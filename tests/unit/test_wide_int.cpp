// The certificates' fixed-width integers (src/exact/arithmetic/wide_int.hpp) and their correctly rounded
// conversions (src/exact/arithmetic/wide_rounding.hpp), against GMP on random and hand-made values, and
// the certificate's refinement of its integer frame.
#include <gmp.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>

#include "../../src/exact/arithmetic/gmp_support.hpp"
#include "../../src/exact/arithmetic/wide_int.hpp"
#include "../../src/exact/arithmetic/wide_rounding.hpp"
#include "gjklab/exact/certificate.hpp"
#include "gjklab/exact/oracle.hpp"

using gjklab::Vec3;
using gjklab::exact::detail::Mpq;
using gjklab::exact::detail::Mpz;
using gjklab::exact::detail::Wide;

namespace {

/// A random Wide of up to `limbs` random limbs (often with zero or all-ones limbs, to reach
/// carries and borrows), and the same value in `z`.
Wide random_wide(std::mt19937_64& rng, int limbs, mpz_ptr z) {
  const int n = static_cast<int>(rng() % (limbs + 1));
  Wide x = 0;
  mpz_set_ui(z, 0);
  for (int k = 0; k < n; ++k) {
    std::uint64_t limb = rng();
    if (rng() % 4 == 0) limb = 0;
    if (rng() % 4 == 0) limb = ~std::uint64_t{0};
    x = x.shifted_left(64) + Wide::shifted(limb, false, 0);
    mpz_mul_2exp(z, z, 64);
    Mpz l;
    mpz_import(l.get(), 1, 1, sizeof limb, 0, 0, &limb);
    mpz_add(z, z, l.get());
  }
  if (rng() % 2) {
    x = -x;
    mpz_neg(z, z);
  }
  return x;
}

bool equals(const Wide& x, mpz_srcptr z) {
  Mpz w;
  x.to_mpz(w.get());
  return mpz_cmp(w.get(), z) == 0;
}

int sign_of(int c) {
  return (c > 0) - (c < 0);
}

}  // namespace

TEST_CASE("fixed-width integers: +, -, *, shifts and comparisons equal GMP's", "[unit][exact]") {
  std::mt19937_64 rng(20261125);
  Mpz zx, zy, zr;
  for (int trial = 0; trial < 20000; ++trial) {
    const Wide x = random_wide(rng, 7, zx.get()), y = random_wide(rng, 7, zy.get());
    mpz_add(zr.get(), zx.get(), zy.get());
    REQUIRE(equals(x + y, zr.get()));
    mpz_sub(zr.get(), zx.get(), zy.get());
    REQUIRE(equals(x - y, zr.get()));
    mpz_mul(zr.get(), zx.get(), zy.get());
    REQUIRE(equals(x * y, zr.get()));
    REQUIRE(compare(x, y) == sign_of(mpz_cmp(zx.get(), zy.get())));
    REQUIRE((x == y) == (mpz_cmp(zx.get(), zy.get()) == 0));
    REQUIRE(sgn(x) == mpz_sgn(zx.get()));
    const long shift = static_cast<long>(rng() % 300);
    mpz_mul_2exp(zr.get(), zx.get(), static_cast<mp_bitcnt_t>(shift));
    REQUIRE(equals(x.shifted_left(shift), zr.get()));
    if (sgn(x) != 0) {
      long e_wide = 0, e_gmp = 0;
      CHECK(x.mantissa_2exp(&e_wide) == mpz_get_d_2exp(&e_gmp, zx.get()));
      CHECK(e_wide == e_gmp);
    }
  }
}

TEST_CASE("fixed-width integers: a result beyond the capacity throws instead of wrapping",
          "[unit][exact]") {
  const Wide big = Wide::shifted(1, false, 64L * (Wide::kLimbs - 1));  // 2^(64·15)
  CHECK_THROWS_AS(big * big, gjklab::exact::detail::WideOverflow);
  CHECK_THROWS_AS(big.shifted_left(64), gjklab::exact::detail::WideOverflow);
  const Wide top = big.shifted_left(63);  // 2^(64·16 − 1): the largest power of two that fits
  CHECK_THROWS_AS(top + top, gjklab::exact::detail::WideOverflow);
  CHECK_NOTHROW(top - top);
  // 8 limbs times 9 limbs has room for 17, but 2^(64·7)·2^(64·8) fits in 16: no overflow.
  const Wide eight = Wide::shifted(1, false, 64L * 7), nine = Wide::shifted(1, true, 64L * 8);
  Mpz expected;
  mpz_set_si(expected.get(), -1);
  mpz_mul_2exp(expected.get(), expected.get(), 64 * 15);
  CHECK(equals(eight * nine, expected.get()));
  CHECK(equals(nine * eight, expected.get()));
}

TEST_CASE("fixed-width integers: quotients and square roots round like GMP's, ties to even",
          "[unit][exact]") {
  namespace detail = gjklab::exact::detail;
  std::mt19937_64 rng(7);
  Mpz zn, zd;
  Mpq q;
  int decided = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Wide n = random_wide(rng, 5, zn.get()), d = random_wide(rng, 5, zd.get());
    if (sgn(d) == 0) continue;
    const long exponent = static_cast<long>(rng() % 200) - 100;
    if (const std::optional<double> r = detail::nearest_quotient(n, d, exponent)) {
      CHECK(*r == detail::nearest_double(zn.get(), zd.get(), exponent));
      ++decided;
    }
    n = abs(n);
    d = abs(d);
    mpz_abs(zn.get(), zn.get());
    mpz_abs(zd.get(), zd.get());
    if (const std::optional<double> r = detail::nearest_sqrt(n, d, 2 * exponent)) {
      mpq_set_num(q.get(), zn.get());
      mpq_set_den(q.get(), zd.get());
      mpq_canonicalize(q.get());
      if (exponent > 0) mpq_mul_2exp(q.get(), q.get(), static_cast<mp_bitcnt_t>(2 * exponent));
      if (exponent < 0) mpq_div_2exp(q.get(), q.get(), static_cast<mp_bitcnt_t>(-2 * exponent));
      CHECK(*r == detail::nearest_sqrt(q.get()));
    }
  }
  CHECK(decided > 15000);
  // Exactly on midpoints: 2^53 + 1 lies between 2^53 and 2^53 + 2, and so does √((2^53 + 1)²).
  const Wide m = Wide::shifted((std::uint64_t{1} << 53) + 1, false, 0);
  CHECK(detail::nearest_quotient(m, 1, 0) == std::optional<double>(0x1p53));
  CHECK(detail::nearest_sqrt(m * m, 1, 0) == std::optional<double>(0x1p53));
  const Wide m3 = Wide::shifted((std::uint64_t{1} << 53) + 3, false, 0);  // up to 2^53 + 4
  CHECK(detail::nearest_quotient(m3, 1, 0) == std::optional<double>(0x1p53 + 4));
  CHECK(detail::nearest_sqrt(m3 * m3, 1, 0) == std::optional<double>(0x1p53 + 4));
}

TEST_CASE("distance certificate on a face with a point finer than the hint's frame",
          "[unit][certificate]") {
  // Every point of A's face x = 1 ties in the separating direction, so the certificate must
  // compare them exactly; (1, 0.1, 0.3) is not an integer in the unit of the hint's points.
  const std::vector<Vec3> a = {{1, 0, 0}, {1, 1, 0}, {1, 0, 1}, {1, 1, 1}, {1, 0.1, 0.3}};
  const std::vector<Vec3> b = {{3, 0.5, 0.5}, {4, 0.25, 0.75}};
  const gjklab::exact::OracleAnswer qp = gjklab::exact::solve(a, b, {.certificates = false});
  for (const gjklab::exact::DistanceHint& hint :
       {gjklab::exact::DistanceHint{{{0, 0}}}, gjklab::exact::DistanceHint{{{1, 1}, {2, 0}}},
        gjklab::exact::DistanceHint{}}) {
    const auto cert = gjklab::exact::certify_distance(a, b, hint);
    REQUIRE(cert.has_value());
    CHECK(cert->distance_squared.numerator() == qp.distance_squared.numerator());
    CHECK(cert->distance_squared.denominator() == qp.distance_squared.denominator());
    CHECK(cert->distance == qp.distance);
  }
}
