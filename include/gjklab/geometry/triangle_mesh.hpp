// A triangle mesh as plain data: vertex coordinates and faces of three vertex indices. The
// geometry layer only holds it; exact/closed_mesh.hpp reads and validates closed meshes.
#pragma once

#include <array>
#include <cstdint>
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

}  // namespace gjklab
