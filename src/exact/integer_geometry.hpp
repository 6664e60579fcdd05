// Internal to src/exact/: exact geometry on the input doubles as integers, and the
// floating-point filters that avoid most of it. No CGAL here.
//
// Every finite double is an integer multiple of a power of two, so the coordinates of two
// clouds are all integer multiples of one unit 2^exponent (the frame). In that unit every
// point, difference, dot and cross product is an integer, computed exactly with GMP.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cstddef>
#include <span>

#include "gjklab/geometry/types.hpp"

namespace gjklab::exact::detail {

using Int = mpz_class;
using IntVec = std::array<Int, 3>;

/// The common unit of two clouds: every coordinate x of either is X·2^exponent, X an integer.
struct IntegerFrame {
  long exponent = 0;
  /// Largest |coordinate| of either cloud (the scale of the floating-point filters).
  double max_abs = 0;
};

/// The frame of two clouds of finite points (one pass over the coordinates).
IntegerFrame integer_frame(std::span<const Vec3> a, std::span<const Vec3> b);

/// x / 2^exponent, exactly (x must be an integer multiple of 2^exponent).
Int to_integer(double x, long exponent);
IntVec to_integer(const Vec3& p, long exponent);

inline IntVec operator-(const IntVec& x, const IntVec& y) {
  return {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
}
inline Int dot(const IntVec& x, const IntVec& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}
inline IntVec cross(const IntVec& x, const IntVec& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}
inline bool is_zero(const IntVec& x) {
  return sgn(x[0]) == 0 && sgn(x[1]) == 0 && sgn(x[2]) == 0;
}

/// A point of a cloud extreme in a direction, and its exact dot product with that direction.
struct Extreme {
  std::size_t index = 0;
  Int value;  ///< n·X in the frame's units (X the point as an integer vector)
};

/// The point of `cloud` that minimises n·x (or maximises it, with `maximise`), decided exactly
/// for an integer direction n ≠ 0. A floating-point pass with a proven error bound keeps only
/// the points that may be extreme; those are then compared exactly. cloud must be non-empty.
Extreme extreme_point(std::span<const Vec3> cloud, const IntVec& n, const IntegerFrame& frame,
                      bool maximise);

}  // namespace gjklab::exact::detail
