// A triangle mesh as plain data: vertex coordinates and faces of three vertex indices, and a
// generated family of closed meshes (star_mesh). exact/closed_mesh.hpp reads and validates them.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
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

}  // namespace gjklab
