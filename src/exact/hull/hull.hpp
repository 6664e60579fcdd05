// Internal to src/exact/: exact convex-hull computations (implemented with CGAL in hull.cpp).
// The interface uses plain types so that the distance translation unit does not need the
// hull headers and the two CGAL translation units compile in parallel.
#pragma once

#include <gmp.h>

#include <array>
#include <span>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::exact::detail {

struct HullSummary {
  /// Affine dimension of the cloud: 0 (one distinct point), 1, 2 or 3.
  int dimension = 0;
  /// The extreme points of the cloud (the vertices of its convex hull), each once.
  std::vector<Vec3> extreme_points;
};

/// Exact hull summary of a non-empty cloud of finite points.
HullSummary hull_summary(std::span<const Vec3> cloud);

/// out := the exact squared distance from the origin to the boundary of the convex hull of
/// {a − b : a ∈ a_points, b ∈ b_points}, assuming that hull contains the origin; 0 when the
/// hull has no interior. Pass the extreme points of each cloud (the hull is the same, and
/// the difference cloud is much smaller).
void penetration_depth_squared(std::span<const Vec3> a_points, std::span<const Vec3> b_points,
                               mpq_ptr out);

/// The boundary triangles of the convex hull of the exact points a[k] − b[k] (k over the
/// inputs), each as three input indices, counter-clockwise seen from outside (coplanar facets
/// triangulated); empty when the points do not span space. Duplicates map to one of them.
std::vector<std::array<int, 3>> difference_hull_triangles(std::span<const Vec3> a,
                                                          std::span<const Vec3> b);

}  // namespace gjklab::exact::detail
