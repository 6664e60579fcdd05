// Exact integer geometry on the input doubles, and the filtered extreme-point search.
#include "exact/arithmetic/integer_geometry.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "exact/arithmetic/wide_int.hpp"

namespace gjklab::exact::detail {

namespace {

constexpr double kUnitRoundoff = 0x1p-53;

/// |n| as a double mantissa in [0.5, 1) and its binary exponent (truncated, as
/// mpz_get_d_2exp): relative error below 2^-52.
double mantissa_2exp(const Int& n, long* exponent) {
  return mpz_get_d_2exp(exponent, n.get_mpz_t());
}
double mantissa_2exp(const Wide& n, long* exponent) {
  return n.mantissa_2exp(exponent);
}

/// n scaled by a power of two so that its largest component lies in [0.5, 1), each component
/// truncated to a double: |result_i − n_i·2^-s| < 2^-52 |n_i·2^-s| + 2^-1075 for the common s.
template <class I>
std::array<double, 3> scaled_direction(const Vec3Of<I>& n) {
  std::array<double, 3> mantissa{};
  std::array<long, 3> exponent{};
  long top = std::numeric_limits<long>::min();
  for (int i = 0; i < 3; ++i) {
    mantissa[i] = mantissa_2exp(n[i], &exponent[i]);
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

/// A point that may be extreme: its index and the upper end of its value's interval.
using Candidate = std::pair<std::size_t, double>;

/// True when a component of d was truncated below the normal range (or flushed to zero): its
/// error is then absolute (up to 2^-1075), not relative, and grows with |x_i|.
bool has_tiny_component(const std::array<double, 3>& d) {
  for (double di : d)
    if (std::abs(di) < 0x1p-1021) return true;  // includes a flushed non-zero component
  return false;
}

/// The floating-point pass of extreme_point: the points whose value s(x) = ±d·x may be the
/// largest, in index order, with d = scaled_direction(n). For each point the computed s
/// differs from the exact ±(n·x)·2^-s by at most (2u + γ3)·a with a = Σ|d_i x_i| (truncating
/// d, rounding the dot product), plus underflow: at most 3·2^-1075 from the products and, when
/// d has a component below the normal range, 2^-1075·‖x‖₁ from its truncation. The bound e is
/// 8u·a (which also covers the rounding of s ± e) plus 2^-1020 — or 2^-1070·(1 + ‖x‖₁) for a
/// tiny d, kept apart because a product with a subnormal result costs about a hundred cycles.
/// The exact maximiser's interval [s − e, s + e] reaches the largest lower end, so it is kept.
/// False when the pass overflowed (then no point can be ruled out).
template <bool kTinyDirection>
bool filter_candidates(std::span<const Vec3> cloud, const std::array<double, 3>& d, double sign,
                       std::vector<Candidate>& out) {
  out.clear();
  double best_low = -std::numeric_limits<double>::infinity();
  bool finite = true;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3& x = cloud[i];
    const double s = sign * ((d[0] * x.x() + d[1] * x.y()) + d[2] * x.z());
    const double a = std::abs(d[0] * x.x()) + std::abs(d[1] * x.y()) + std::abs(d[2] * x.z());
    double e = 8 * kUnitRoundoff * a;
    if constexpr (kTinyDirection)
      e += 0x1p-1070 * (1 + std::abs(x.x()) + std::abs(x.y()) + std::abs(x.z()));
    else
      e += 0x1p-1020;
    const double low = s - e, high = s + e;
    finite = finite && std::isfinite(low) && std::isfinite(high);
    best_low = std::max(best_low, low);
    // best_low only grows, so a point kept by the final bound passed this test too.
    if (high >= best_low) out.emplace_back(i, high);
  }
  if (!finite) return false;
  std::erase_if(out, [&](const Candidate& c) { return c.second < best_low; });
  return true;
}

}  // namespace

long base_exponent(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const long biased = static_cast<long>((bits >> 52) & 0x7FF);
  return biased == 0 ? -1074 : biased - 1075;
}

IntegerFrame integer_frame(std::span<const Vec3> a, std::span<const Vec3> b) {
  long lowest = std::numeric_limits<long>::max();
  for (std::span<const Vec3> cloud : {a, b})
    for (const Vec3& p : cloud)
      for (int i = 0; i < 3; ++i)
        if (p[i] != 0) lowest = std::min(lowest, base_exponent(p[i]));
  return {lowest == std::numeric_limits<long>::max() ? 0 : lowest};
}

namespace {

/// x = ±mantissa·2^shift·2^exponent with a 53-bit integer mantissa; throws FrameTooCoarse when
/// x is not an integer multiple of 2^exponent.
struct Split {
  std::uint64_t mantissa = 0;
  bool negative = false;
  long shift = 0;  ///< ≥ 0
};

Split split(double x, long exponent) {
  // From the encoding: x = ±M·2^e with M the 52 stored bits plus the hidden one (none for
  // subnormals). frexp and ldexp are library calls that cost more than the rest here.
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto biased = static_cast<long>((bits >> 52) & 0x7FF);
  Split out;
  out.negative = (bits >> 63) != 0;
  out.mantissa = bits & ((std::uint64_t{1} << 52) - 1);
  if (biased != 0) out.mantissa |= std::uint64_t{1} << 52;
  const long shift = (biased == 0 ? -1074 : biased - 1075) - exponent;
  if (shift < 0) {
    // Only exact when the mantissa's low −shift bits are zero (fewer significant bits).
    if (-shift >= 64 || (out.mantissa & ((std::uint64_t{1} << -shift) - 1)) != 0)
      throw FrameTooCoarse{base_exponent(x)};
    out.mantissa >>= -shift;
    return out;
  }
  out.shift = shift;
  return out;
}

}  // namespace

template <>
Int to_integer<Int>(double x, long exponent) {
  if (x == 0) return 0;
  const Split s = split(x, exponent);
  Int out(static_cast<unsigned long>(s.mantissa));
  mpz_mul_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(s.shift));
  if (s.negative) out = -out;
  return out;
}

template <>
Wide to_integer<Wide>(double x, long exponent) {
  if (x == 0) return 0;
  const Split s = split(x, exponent);
  return Wide::shifted(s.mantissa, s.negative, s.shift);
}

template <class I>
Extreme<I> extreme_point(std::span<const Vec3> cloud, const Vec3Of<I>& n, const IntegerFrame& frame,
                         bool maximise) {
  thread_local std::vector<Candidate> candidates;
  const std::array<double, 3> d = scaled_direction(n);
  const double sign = maximise ? 1.0 : -1.0;
  const bool filtered = has_tiny_component(d)
                            ? filter_candidates<true>(cloud, d, sign, candidates)
                            : filter_candidates<false>(cloud, d, sign, candidates);
  if (!filtered) {
    candidates.resize(cloud.size());  // the filter overflowed: every point
    for (std::size_t i = 0; i < cloud.size(); ++i)
      candidates[i] = {i, 0.0};
  }
  Extreme<I> out;
  bool first = true;
  for (const Candidate& c : candidates) {
    I value = dot(n, to_integer<I>(cloud[c.first], frame.exponent));
    if (first || (maximise ? value > out.value : value < out.value)) {
      out.index = c.first;
      out.value = std::move(value);
      first = false;
    }
  }
  return out;
}

template Extreme<Int> extreme_point<Int>(std::span<const Vec3>, const Vec3Of<Int>&,
                                         const IntegerFrame&, bool);
template Extreme<Wide> extreme_point<Wide>(std::span<const Vec3>, const Vec3Of<Wide>&,
                                           const IntegerFrame&, bool);

}  // namespace gjklab::exact::detail
