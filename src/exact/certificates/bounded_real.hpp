// Long double values with a running bound on their error (private to src/exact/certificates):
// the filtered distance certificate takes a sign only where the value exceeds its bound, and a
// nearest double only where the value's interval lies inside one double's rounding cell.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "gjklab/geometry/types.hpp"

namespace gjklab::exact::detail::bounded {

using Real = long double;
// The products below have degree ≤ 8 in the coordinates, so the exponent range of an x87 or
// IEEE quad long double holds them without overflow or underflow for any finite doubles.
static_assert(std::numeric_limits<Real>::max_exponent >= 16 * 1024 / 2, "wide long double");
static_assert(std::numeric_limits<Real>::digits >= 64, "long double with a 64-bit mantissa");

/// Relative error bound of one rounded long double operation (twice the unit roundoff).
constexpr Real kUnit = std::numeric_limits<Real>::epsilon();
/// Covers the rounding of the error bounds' own arithmetic (relative, a few ulps per step).
constexpr Real kSafety = 1 + 0x1p-40L;

/// A value v with |exact − v| ≤ err.
struct Approx {
  Real v = 0;
  Real err = 0;
};

inline Approx input(double x) {
  return {x, 0};
}
inline Approx operator+(const Approx& x, const Approx& y) {
  const Real v = x.v + y.v;
  return {v, x.err + y.err + kUnit * std::fabs(v)};
}
inline Approx operator-(const Approx& x, const Approx& y) {
  const Real v = x.v - y.v;
  return {v, x.err + y.err + kUnit * std::fabs(v)};
}
inline Approx operator-(const Approx& x) {
  return {-x.v, x.err};
}
inline Approx operator*(const Approx& x, const Approx& y) {
  const Real v = x.v * y.v;
  return {v,
          std::fabs(x.v) * y.err + std::fabs(y.v) * x.err + x.err * y.err + kUnit * std::fabs(v)};
}
/// x / y for y decided non-zero (|y.v| > y.err).
inline Approx operator/(const Approx& x, const Approx& y) {
  const Real v = x.v / y.v;
  const Real room = std::fabs(y.v) - y.err * kSafety;
  if (!(room > 0)) return {0, std::numeric_limits<Real>::infinity()};  // undecidable
  return {v, (x.err + std::fabs(v) * y.err) / room * kSafety + kUnit * std::fabs(v)};
}

inline bool positive(const Approx& x) {
  return x.v > x.err * kSafety;
}
inline bool negative(const Approx& x) {
  return -x.v > x.err * kSafety;
}

using AVec = std::array<Approx, 3>;

inline AVec input(const Vec3& p) {
  return {input(p.x()), input(p.y()), input(p.z())};
}
inline AVec operator-(const AVec& x, const AVec& y) {
  return {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
}
inline AVec operator+(const AVec& x, const AVec& y) {
  return {x[0] + y[0], x[1] + y[1], x[2] + y[2]};
}
inline AVec operator*(const Approx& s, const AVec& x) {
  return {s * x[0], s * x[1], s * x[2]};
}
inline Approx dot(const AVec& x, const AVec& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}
inline AVec cross(const AVec& x, const AVec& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}
inline bool nonzero(const AVec& x) {
  return std::any_of(x.begin(), x.end(),
                     [](const Approx& c) { return positive(c) || negative(c); });
}

/// [lo, hi] ⊇ [x.v − x.err, x.v + x.err], rounded outwards.
struct Interval {
  Real lo, hi;
};
inline Interval widen(const Approx& x) {
  constexpr Real kTiny = std::numeric_limits<Real>::denorm_min();
  const Real lo = x.v - x.err * kSafety, hi = x.v + x.err * kSafety;
  return {lo - (std::fabs(lo) * kUnit + kTiny), hi + (std::fabs(hi) * kUnit + kTiny)};
}

/// The double nearest to every real number in r, if there is one (strictly inside its rounding
/// cell, so no tie to break).
inline std::optional<double> nearest_double(const Interval& r) {
  const auto candidate = static_cast<double>((r.lo + r.hi) / 2);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double below = std::nextafter(candidate, -kInf), above = std::nextafter(candidate, kInf);
  if (!std::isfinite(below) || !std::isfinite(above)) return std::nullopt;
  // Two neighbouring doubles add exactly in a 64-bit mantissa, and halving is exact.
  const Real low_edge = (static_cast<Real>(candidate) + below) / 2;
  const Real high_edge = (static_cast<Real>(candidate) + above) / 2;
  if (low_edge < r.lo && r.hi < high_edge) return candidate;
  return std::nullopt;
}

/// The double nearest to √x for x decided positive.
inline std::optional<double> nearest_sqrt(const Approx& x) {
  const Interval r = widen(x);
  if (!(r.lo > 0)) return std::nullopt;
  // sqrt is correctly rounded; scaling by 1 ∓ 2ε more than covers it and its own rounding.
  return nearest_double({std::sqrt(r.lo) * (1 - 2 * kUnit), std::sqrt(r.hi) * (1 + 2 * kUnit)});
}

inline std::optional<Vec3> nearest_point(const AVec& x) {
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    const std::optional<double> c = nearest_double(widen(x[i]));
    if (!c) return std::nullopt;
    out[i] = *c;
  }
  return out;
}

}  // namespace gjklab::exact::detail::bounded
