// Exact integer geometry on the input doubles, and the filtered extreme-point search.
#include "integer_geometry.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace gjklab::exact::detail {

namespace {

constexpr double kUnitRoundoff = 0x1p-53;

/// The exponent e of the least significant mantissa bit of a finite x ≠ 0 in its binary64
/// encoding: x is an integer multiple of 2^e (e = −1074 for subnormals).
long base_exponent(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const long biased = static_cast<long>((bits >> 52) & 0x7FF);
  return biased == 0 ? -1074 : biased - 1075;
}

/// n scaled by a power of two so that its largest component lies in [0.5, 1), each component
/// truncated to a double: |result_i − n_i·2^-s| < 2^-52 |n_i·2^-s| + 2^-1075 for the common s.
std::array<double, 3> scaled_direction(const IntVec& n) {
  std::array<double, 3> mantissa{};
  std::array<long, 3> exponent{};
  long top = std::numeric_limits<long>::min();
  for (int i = 0; i < 3; ++i) {
    mantissa[i] = mpz_get_d_2exp(&exponent[i], n[i].get_mpz_t());
    if (mantissa[i] != 0) top = std::max(top, exponent[i]);
  }
  std::array<double, 3> out{};
  for (int i = 0; i < 3; ++i)
    if (mantissa[i] != 0) {
      const long shift = std::max<long>(exponent[i] - top, -2000);  // beyond: flushes to 0
      out[i] = std::ldexp(mantissa[i], static_cast<int>(shift));
    }
  return out;
}

}  // namespace

IntegerFrame integer_frame(std::span<const Vec3> a, std::span<const Vec3> b) {
  IntegerFrame frame;
  long lowest = std::numeric_limits<long>::max();
  for (std::span<const Vec3> cloud : {a, b})
    for (const Vec3& p : cloud)
      for (int i = 0; i < 3; ++i) {
        const double x = p[i];
        if (x == 0) continue;
        lowest = std::min(lowest, base_exponent(x));
        frame.max_abs = std::max(frame.max_abs, std::abs(x));
      }
  frame.exponent = lowest == std::numeric_limits<long>::max() ? 0 : lowest;
  return frame;
}

Int to_integer(double x, long exponent) {
  if (x == 0) return 0;
  int e = 0;
  const double fraction = std::frexp(x, &e);  // x = fraction·2^e, 0.5 ≤ |fraction| < 1
  Int out(std::ldexp(fraction, 53));          // an integer of at most 53 bits, exact
  const long shift = static_cast<long>(e) - 53 - exponent;
  if (shift >= 0) {
    mpz_mul_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(shift));
  } else {
    // Only subnormals reach here: their frexp mantissa has trailing zero bits to spare.
    mpz_tdiv_q_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(-shift));
  }
  return out;
}

IntVec to_integer(const Vec3& p, long exponent) {
  return {to_integer(p.x(), exponent), to_integer(p.y(), exponent), to_integer(p.z(), exponent)};
}

Extreme extreme_point(std::span<const Vec3> cloud, const IntVec& n, const IntegerFrame& frame,
                      bool maximise) {
  // Floating-point pass on s(x) = ±d·x, d = scaled_direction(n) (the sign makes it a minimum).
  // With ‖d‖∞ < 1 and |x_i| ≤ max_abs, the computed s differs from the exact ±(n·x)·2^-s by at
  // most (2u + γ3)·Σ|d_i||x_i| ≤ 5.01u·‖d‖₁·max_abs from truncating d (u = 2^-53) and rounding
  // the dot product, plus at most 6·2^-1075·(1 + max_abs) from underflow; `bound` is
  // 8u·‖d‖₁·max_abs plus 2^-1070·(1 + max_abs), which covers both and its own rounding.
  const std::array<double, 3> d = scaled_direction(n);
  const double sign = maximise ? -1.0 : 1.0;
  const double norm1 = std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]);
  const double bound = 8 * kUnitRoundoff * norm1 * frame.max_abs + 0x1p-1070 * (1 + frame.max_abs);
  std::vector<std::size_t> candidates;
  if (std::isfinite(bound)) {
    double best = std::numeric_limits<double>::infinity();
    bool finite = true;
    for (const Vec3& x : cloud) {
      const double s = sign * (d[0] * x.x() + d[1] * x.y() + d[2] * x.z());
      finite = finite && std::isfinite(s);
      best = std::min(best, s);
    }
    if (finite) {
      // Any point whose computed value exceeds best + 2·bound is beaten exactly by the point
      // that attained best; the slack covers the rounding of this sum.
      const double threshold = best + 2.01 * bound + 4 * kUnitRoundoff * std::abs(best);
      for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Vec3& x = cloud[i];
        if (sign * (d[0] * x.x() + d[1] * x.y() + d[2] * x.z()) <= threshold)
          candidates.push_back(i);
      }
    }
  }
  if (candidates.empty()) {  // the filter could not be evaluated (overflow): every point
    candidates.resize(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
      candidates[i] = i;
  }
  Extreme out;
  bool first = true;
  for (std::size_t i : candidates) {
    Int value = dot(n, to_integer(cloud[i], frame.exponent));
    if (first || (maximise ? value > out.value : value < out.value)) {
      out.index = i;
      out.value = std::move(value);
      first = false;
    }
  }
  return out;
}

}  // namespace gjklab::exact::detail
