// Exact truth for two closed triangle meshes, taken as the solids they bound: whether the solids
// meet, and their squared distance as an exact rational, with the triangles that attain it.
//
// The vertices are the doubles as given (posed, as every query sees them), so the answers are
// exact for the meshes as given, with no tolerance anywhere. The meshes must be closed,
// consistently oriented and free of self-intersections (what the closed-mesh reader checks);
// the answer for any other triangle soup is that of its triangles and is not a solid's.
//
// Not all pairs of triangles are evaluated exactly: a bounding-box tree over each mesh's
// triangles culls the pairs, with floating-point lower bounds whose rounding is accounted for,
// and only the pairs that can still attain the minimum are evaluated in exact arithmetic. The
// implementation uses CGAL and lives in src/exact/mesh/.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/enum_names.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::exact {

/// A closed triangle mesh by reference: vertex coordinates and faces as vertex indices, counter-
/// clockwise seen from outside.
struct MeshView {
  MeshView(std::span<const Vec3> v, std::span<const MeshFace> f) : vertices(v), faces(f) {}
  MeshView(const TriangleMesh& m) : vertices(m.vertices), faces(m.faces) {}  // NOLINT: a view
  std::span<const Vec3> vertices;
  std::span<const MeshFace> faces;
};

/// How the answer was found.
enum class MeshContact : std::uint8_t {
  separated,       ///< no triangles meet and neither solid holds the other
  triangles_meet,  ///< two triangles share a point (face_a, face_b)
  a_inside_b,      ///< A's surface lies inside solid B (no triangles meet)
  b_inside_a,      ///< B's surface lies inside solid A
};

inline constexpr auto kMeshContactNames = std::to_array<EnumName<MeshContact>>({
    {MeshContact::separated, "separated"},
    {MeshContact::triangles_meet, "triangles_meet"},
    {MeshContact::a_inside_b, "a_inside_b"},
    {MeshContact::b_inside_a, "b_inside_a"},
});
static_assert(in_value_order(kMeshContactNames) &&
              ends_at(kMeshContactNames, MeshContact::b_inside_a));

constexpr std::string_view to_string(MeshContact c) {
  return name_of(kMeshContactNames, c);
}

struct MeshTruth {
  bool intersect = false;  ///< the closed solids share a point
  MeshContact contact = MeshContact::separated;
  Rational distance_squared;  ///< exact; 0 when intersecting
  double distance = 0;        ///< √distance_squared, correctly rounded
  /// The triangles that meet (triangles_meet) or attain the distance (separated); −1 when the
  /// answer is a containment.
  std::int64_t face_a = -1, face_b = -1;
  /// Triangle pairs whose boxes or bounds could not rule them out and that were evaluated in
  /// exact arithmetic (intersection tests, then squared distances), of |faces A| × |faces B|.
  std::uint64_t exact_intersection_tests = 0;
  std::uint64_t exact_distance_evaluations = 0;
};

/// The exact answer for the solids bounded by a and b. Throws std::invalid_argument for a mesh
/// without faces, a face index out of range, or a non-finite coordinate.
MeshTruth mesh_truth(const MeshView& a, const MeshView& b);

}  // namespace gjklab::exact
