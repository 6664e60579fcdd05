// Generators for the classic demo shapes, unit-sized and centred at the origin.
//
// "Unit-sized" means each fits the cube [-0.5, 0.5]^3 with extent 1 along its axis:
// box of side 1; cone and cylinder of height 1 and radius 0.5 along z; UV sphere of radius 0.5.
#pragma once

#include "gjklab/geometry/polytope.hpp"

namespace gjklab::shapes {

inline constexpr int kDefaultConeVertices = 33;
inline constexpr int kDefaultCylinderVertices = 64;
inline constexpr int kDefaultSphereVertices = 482;

/// Axis-aligned box with the given full extents (8 vertices).
Polytope box(const Vec3& extents = Vec3(1, 1, 1));
/// Cone: apex at z = +0.5 and a regular (vertices − 1)-gon of radius 0.5 at z = −0.5.
/// Throws std::invalid_argument if vertices < 4.
Polytope cone(int vertices = kDefaultConeVertices);
/// Cylinder: two regular (vertices / 2)-gons of radius 0.5 at z = ±0.5.
/// Throws std::invalid_argument if vertices is odd or < 6.
Polytope cylinder(int vertices = kDefaultCylinderVertices);
/// UV sphere of radius 0.5: two poles and rings × segments points with rings = segments / 2 − 1,
/// the largest such grid with at most `vertices` points (482 = 2 + 15·32).
/// Throws std::invalid_argument if vertices < 6.
Polytope uv_sphere(int vertices = kDefaultSphereVertices);

}  // namespace gjklab::shapes
