// The support-plane scan of the filtered distance certificate (private to
// src/exact/certificates): every point of a cloud tested against a plane in double, with a
// proven bound per point, four points at a time where the processor has AVX2; the few points
// within their bound of the plane are handed back to be decided exactly.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::exact::detail {

/// Points too close to their plane to call in floating point.
using Ties = std::vector<std::size_t>;

/// The scan's direction: the long double direction scaled by a power of two (so that its
/// largest component is near 1) and rounded to doubles, and per component a bound w_i such
/// that |computed d·(x − x_r) − exact| ≤ Σ w_i |x_i − x_ri| + 2^-1070 (see filtered_distance.cpp's
/// header: the direction's error, the rounding of x − x_r, of the products and of the sums).
struct ScanDirection {
  std::array<double, 3> d{}, w{};
};

/// Scans a cloud: every x must satisfy sign·d·(x − x_r) ≥ 0. False when a point is decided on
/// the wrong side; points too close to call go to `ties` (those in `skip`, the feature's own
/// points, lie on the plane exactly and need no test).
bool scan_side(std::span<const Vec3> cloud, const Vec3& ref, const ScanDirection& s, double sign,
               std::span<const std::int32_t> skip, Ties& ties);

}  // namespace gjklab::exact::detail
