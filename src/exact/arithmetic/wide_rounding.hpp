// Internal to src/exact/: correctly rounded doubles from Wide integers without GMP.
//
// Each conversion takes a long double estimate q of the value t (64-bit mantissas: relative
// error below 2^-60), rounds it to a double r, and proves r right: r is the nearest double
// when t lies strictly between the midpoints that separate r from its neighbours (a t on a
// midpoint takes the neighbour with the even mantissa). Nearly always q is so far from both
// midpoints (relative to the error bound) that this holds for t too, which a comparison of
// long doubles shows; otherwise t is compared with the midpoints exactly, in integers. The
// estimate is within one ulp, so at most two neighbours are tried. Results in the subnormal
// range or beyond the double range are left to the GMP conversions (nullopt).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "exact/arithmetic/wide_int.hpp"

namespace gjklab::exact::detail {

/// sign(lhs·2^lhs_shift − rhs·2^rhs_shift) for lhs, rhs ≥ 0.
inline int compare_scaled(const Wide& lhs, long lhs_shift, const Wide& rhs, long rhs_shift) {
  const long common = std::min(lhs_shift, rhs_shift);
  return compare(lhs.shifted_left(lhs_shift - common), rhs.shifted_left(rhs_shift - common));
}

/// A midpoint between adjacent doubles, M·2^k with an odd integer M < 2^55.
struct Midpoint {
  std::uint64_t m = 0;
  long k = 0;
};

/// The midpoints below and above a positive normal double r.
inline void midpoints_of(double r, Midpoint& below, Midpoint& above) {
  int e = 0;
  const double f = std::frexp(r, &e);                            // r = f·2^e, 0.5 ≤ f < 1
  const auto R = static_cast<std::uint64_t>(std::ldexp(f, 53));  // r = R·2^(e−53), exact
  above = {2 * R + 1, e - 54L};
  // Below a power of two the spacing halves.
  below =
      R == (std::uint64_t{1} << 52) ? Midpoint{4 * R - 1, e - 55L} : Midpoint{2 * R - 1, e - 54L};
}

/// Relative error bound of the long double estimates: 2^-60 (see the file comment), doubled.
constexpr long double kEstimateError = 0x1p-59L;

/// 2^e as a double, for −1022 ≤ e ≤ 1023 (built from its bits: ldexp is a library call that
/// costs more than the rest of a rounding).
inline double power_of_two(long e) {
  return std::bit_cast<double>(static_cast<std::uint64_t>(e + 1023) << 52);
}

/// The double nearest to t = q·2^e when the estimate q of t·2^-e (0.25 ≤ q < 4, relative error
/// at most kEstimateError) shows it: q rounded to 53 bits is r, and q's error interval lies
/// strictly between the midpoints around r (r ± half its spacing, exact in long double). Scaled
/// by 2^e, which is exact in the normal range (|e| ≤ 1000 keeps it there). nullopt otherwise.
inline std::optional<double> clearly_rounded(long double q, long e) {
  if (e < -1000 || e > 1000) return std::nullopt;
  const double r = static_cast<double>(q);
  const auto bits = std::bit_cast<std::uint64_t>(r);
  const long lsb = static_cast<long>(bits >> 52) - 1075;  // r is a multiple of 2^lsb
  const bool power = (bits & ((std::uint64_t{1} << 52) - 1)) == 0;
  const long double above = static_cast<long double>(r) + power_of_two(lsb - 1);
  const long double below = static_cast<long double>(r) - power_of_two(power ? lsb - 2 : lsb - 1);
  const long double margin = kEstimateError * q;
  if (!(below < q - margin && q + margin < above)) return std::nullopt;
  return r * power_of_two(e);
}

/// Proves or corrects the estimate r of a positive value t: `side(mid)` is sign(t − mid).
/// Returns the double nearest to t (ties to even), or nullopt outside the normal range.
template <class Side>
std::optional<double> settle(double r, const Side& side) {
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (!std::isnormal(r) || r > std::numeric_limits<double>::max() / 4) return std::nullopt;
    Midpoint below, above;
    midpoints_of(r, below, above);
    const int hi = side(above);
    if (hi > 0) {
      r = std::nextafter(r, std::numeric_limits<double>::infinity());
      continue;
    }
    const int lo = side(below);
    if (lo < 0) {
      r = std::nextafter(r, 0.0);
      continue;
    }
    const bool r_even = (above.m / 2) % 2 == 0;  // above.m = 2R + 1
    if (hi == 0) return r_even ? r : std::nextafter(r, std::numeric_limits<double>::infinity());
    if (lo == 0) return r_even ? r : std::nextafter(r, 0.0);
    return r;
  }
  return std::nullopt;
}

/// num/den as a long double for num ≥ 0, den > 0, with a relative error below 5·2^-64: both
/// truncated to their top 64 bits (2^-63 each), the division rounded (2^-64); the scaling by a
/// power of two is exact in long double's range.
inline long double ratio_estimate(const Wide& num, const Wide& den) {
  if (sgn(num) == 0) return 0;
  long e_num = 0, e_den = 0;
  const long double m_num = num.magnitude_2exp(&e_num), m_den = den.magnitude_2exp(&e_den);
  return std::ldexp(m_num / m_den, static_cast<int>(e_num - e_den));
}

/// The double nearest to num/den·2^exponent (den ≠ 0).
inline std::optional<double> nearest_quotient(const Wide& num, const Wide& den, long exponent) {
  if (sgn(num) == 0) return 0.0;
  const bool negative = (sgn(num) < 0) != (sgn(den) < 0);
  const Wide n = abs(num), d = abs(den);
  long en = 0, ed = 0;
  const long double q = n.magnitude_2exp(&en) / d.magnitude_2exp(&ed);
  const long e = en - ed + exponent;
  if (const std::optional<double> r = clearly_rounded(q, e)) return negative ? -*r : *r;
  if (e < -1000 || e > 1000) return std::nullopt;
  const double estimate = static_cast<double>(std::ldexp(q, static_cast<int>(e)));
  // t − M·2^k ⋚ 0  ⇔  n·2^exponent ⋚ M·d·2^k.
  const auto side = [&](const Midpoint& mid) {
    return compare_scaled(n, exponent, Wide::shifted(mid.m, false, 0) * d, mid.k);
  };
  const std::optional<double> r = settle(estimate, side);
  if (!r) return std::nullopt;
  return negative ? -*r : *r;
}

/// The double nearest to √(num/den·2^exponent) for num ≥ 0, den > 0.
inline std::optional<double> nearest_sqrt(const Wide& num, const Wide& den, long exponent) {
  if (sgn(num) == 0) return 0.0;
  long en = 0, ed = 0;
  long double q = num.magnitude_2exp(&en) / den.magnitude_2exp(&ed);
  long e = en - ed + exponent;
  if (e % 2 != 0) {  // an even exponent halves exactly under the root
    q *= 2;
    --e;
  }
  const long double root = std::sqrt(q);
  if (const std::optional<double> r = clearly_rounded(root, e / 2)) return *r;
  if (e < -2000 || e > 2000) return std::nullopt;
  const double estimate = static_cast<double>(std::ldexp(root, static_cast<int>(e / 2)));
  // √t' − M·2^k ⋚ 0  ⇔  num·2^exponent ⋚ M²·den·2^(2k).
  const auto side = [&](const Midpoint& mid) {
    const Wide m = Wide::shifted(mid.m, false, 0);
    return compare_scaled(num, exponent, m * m * den, 2 * mid.k);
  };
  return settle(estimate, side);
}

}  // namespace gjklab::exact::detail
