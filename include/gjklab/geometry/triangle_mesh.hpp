// A triangle mesh as plain data: vertex coordinates and faces of three vertex indices, and
// generated closed meshes: stars, prisms and solids of revolution (star_mesh, prism_mesh,
// lathe_mesh). exact/closed_mesh.hpp reads and validates them.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// One triangle: three indices into TriangleMesh::vertices. Its orientation is the order of
/// the indices: seen from outside a closed mesh, they turn counter-clockwise (right-hand rule,
/// the normal (b − a) × (c − a) points outward).
using MeshFace = std::array<std::uint32_t, 3>;

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<MeshFace> faces;

  friend bool operator==(const TriangleMesh&, const TriangleMesh&) = default;
};

/// A closed, star-shaped triangle mesh: a UV sphere of `rings` × `segments` (rings ≥ 2,
/// segments ≥ 3) whose vertex in each direction u lies at radius(u)·u (radius > 0). Every
/// triangle stays in the cone of its corners' rays from the origin, so the surface never crosses
/// itself, whatever the radii: with equal radii a convex UV sphere, with varied ones a
/// non-convex star. Faces turn counter-clockwise seen from outside. radius is called once per
/// vertex, north pole first, then ring by ring, south pole last. 2·segments·(rings − 1) faces.
TriangleMesh star_mesh(int rings, int segments, const std::function<double(const Vec3&)>& radius);

/// A point of a plane: a prism's polygon corner (x, y), a lathe profile's point (r, z).
using PlanePoint = std::array<double, 2>;

/// The prism over a polygon in the plane z = const, between heights z0 < z1. The polygon (at
/// least 3 corners, counter-clockwise seen from +z, simple) must be star-shaped from its first
/// corner: the fan of triangles from it is its top and bottom (an L, a T, any convex polygon).
/// Throws std::invalid_argument for fewer than 3 corners, a non-finite value or z0 >= z1; the
/// other conditions are the caller's (validate_closed_mesh checks the result).
TriangleMesh prism_mesh(std::span<const PlanePoint> polygon, double z0, double z1);

/// The solid swept by turning a profile in the half-plane (r, z), r >= 0, about the z axis, in
/// `segments` (>= 3) steps (vertices at the angles 2πj/segments). The profile goes
/// counter-clockwise around the region it bounds (the solid on its left):
///  - ring: every point has r > 0, and the polygon is closed implicitly (last to first): a
///    torus from a circle, a tube (a peg's hole) from a rectangle;
///  - !ring: the first and last points lie on the axis (r = 0; each becomes one pole vertex)
///    and the others have r > 0: a ball from a half circle, a peg from a rectangle's half, a cup
///    from the half of its cross-section.
/// Faces turn counter-clockwise seen from outside. Throws std::invalid_argument for a profile
/// of too few points (ring: 3, else 3 with 1 off the axis), a non-finite value, or a point on
/// the wrong side of the axis.
TriangleMesh lathe_mesh(std::span<const PlanePoint> profile, int segments, bool ring);

}  // namespace gjklab
