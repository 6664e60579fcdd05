// Exact errors of a floating-point answer's witness points: how far each lies from its hull,
// and how far their distance is from the exact distance. Measured in exact arithmetic on the
// doubles, each correctly rounded to the nearest double (length units).
#pragma once

#include <span>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::exact {

/// The distance from point p to the convex hull of a non-empty cloud (0 when p is inside or
/// on it), exactly, correctly rounded: certified by exact GJK, or by the QP where that fails.
/// Throws std::invalid_argument for an empty cloud or a non-finite coordinate.
double distance_to_hull(std::span<const Vec3> cloud, const Vec3& p);

/// | ‖p − q‖ − √distance_squared |, correctly rounded (finite p and q).
double distance_difference(const Vec3& p, const Vec3& q, const Rational& distance_squared);

}  // namespace gjklab::exact
