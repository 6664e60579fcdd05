// Internal to src/exact/: exact geometry on the input doubles as integers, and the
// floating-point filters that avoid most of it. No CGAL here.
//
// Every finite double is an integer multiple of a power of two, so the coordinates of two
// clouds are all integer multiples of one unit 2^exponent (the frame). In that unit every
// point, difference, dot and cross product is an integer, computed exactly: with GMP's
// mpz_class (Int), or with the fixed-width Wide of wide_int.hpp where it is wide enough.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cstddef>
#include <span>

#include "gjklab/geometry/types.hpp"

namespace gjklab::exact::detail {

using Int = mpz_class;
/// A point or vector with integer coordinates of type I (Int, or Wide on the fast path).
template <class I>
using Vec3Of = std::array<I, 3>;
using IntVec = Vec3Of<Int>;

/// The common unit of two clouds: every coordinate x of either is X·2^exponent, X an integer.
struct IntegerFrame {
  long exponent = 0;
};

/// Thrown by to_integer when x is not an integer multiple of 2^exponent: the frame must be
/// refined to `exponent`, the unit of x's least significant bit.
struct FrameTooCoarse {
  long exponent = 0;
};

/// The frame of two clouds of finite points (one pass over the coordinates).
IntegerFrame integer_frame(std::span<const Vec3> a, std::span<const Vec3> b);

/// The unit of x's least significant mantissa bit: x is an integer multiple of 2^result
/// (−1074 for subnormals). x must be finite and non-zero.
long base_exponent(double x);

/// x / 2^exponent, exactly; throws FrameTooCoarse if that is not an integer.
template <class I>
I to_integer(double x, long exponent);
template <class I>
Vec3Of<I> to_integer(const Vec3& p, long exponent) {
  return {to_integer<I>(p.x(), exponent), to_integer<I>(p.y(), exponent),
          to_integer<I>(p.z(), exponent)};
}

template <class I>
Vec3Of<I> operator-(const Vec3Of<I>& x, const Vec3Of<I>& y) {
  return {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
}
template <class I>
I dot(const Vec3Of<I>& x, const Vec3Of<I>& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}
template <class I>
Vec3Of<I> cross(const Vec3Of<I>& x, const Vec3Of<I>& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}
template <class I>
bool is_zero(const Vec3Of<I>& x) {
  return sgn(x[0]) == 0 && sgn(x[1]) == 0 && sgn(x[2]) == 0;
}

/// A point of a cloud extreme in a direction, and its exact dot product with that direction.
template <class I>
struct Extreme {
  std::size_t index = 0;
  I value;  ///< n·X in the frame's units (X the point as an integer vector)
};

/// The point of `cloud` that minimises n·x (or maximises it, with `maximise`), decided exactly
/// for an integer direction n ≠ 0 (the first such point on ties). A floating-point pass with a
/// proven error bound per point keeps only the points that may be extreme; those are then
/// compared exactly. cloud must be non-empty; throws FrameTooCoarse if a point that may be
/// extreme is not integral in the frame.
template <class I>
Extreme<I> extreme_point(std::span<const Vec3> cloud, const Vec3Of<I>& n, const IntegerFrame& frame,
                         bool maximise);

}  // namespace gjklab::exact::detail
