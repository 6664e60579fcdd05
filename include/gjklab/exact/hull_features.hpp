// The faces and edges of a point cloud's convex hull, decided exactly, for algorithms that
// work on hull features (the separating axis test, peers that need a face list).
//
// The hull is computed with exact predicates (CGAL, behind this plain-types interface) and
// coplanar facets are merged, so every face of the polytope appears once, however its
// facets were triangulated. Normals and directions are computed in exact rational
// arithmetic and then reduced to a canonical form before rounding: a normal is divided by
// its largest absolute component, a direction by its largest component with sign (so that
// component becomes +1). Parallel vectors therefore round to bitwise equal doubles (and
// opposite normals to bitwise opposite ones) before the final normalisation to unit length,
// which lets callers detect exact parallelism with ==.
//
// Lower-dimensional clouds (documented per field below):
//   dimension 0 (one distinct point): one vertex; no faces, normals or edges.
//   dimension 1 (collinear): the two end points, one edge and its direction; no faces or
//                normals (a segment has no face normal; SAT-like users must add the axes
//                that depend on the other shape).
//   dimension 2 (coplanar): the polygon's corners in counter-clockwise order seen from
//                face_normals[0] = m; the face normals are m, −m (the polygon's two sides,
//                face_normals[0] and [1]) followed by the in-plane outward normal of every
//                polygon edge (edge × m, one per edge, in edge order); `faces` holds the polygon
//                twice (counter-clockwise seen from m, then from −m).
//   dimension 3: one outward normal per face of the polytope, faces in the lexicographic order
//                of their normals (faces whose normals round to the same double, such as the
//                two triangles of a nearly flat quad, in the order of their vertex loops),
//                vertices in lexicographic order, each face loop starting at
//                its smallest vertex index, edges as sorted (smaller, larger) index pairs: a
//                canonical form, whatever order the hull came in (CGAL's order depends on heap
//                addresses, and FCL's answers depend on the vertex order).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::exact {

struct HullFeatures {
  /// Affine dimension of the cloud: 0 (one distinct point), 1, 2 or 3.
  int dimension = 0;
  /// The extreme points of the cloud (exact input values), each once.
  std::vector<Vec3> vertices;
  /// Unit outward face normals, one per face (see the header comment for flat clouds).
  std::vector<Vec3> face_normals;
  /// Unit edge directions, one per class of parallel edges, in canonical sign (the component
  /// of largest magnitude is positive).
  std::vector<Vec3> edge_directions;
  /// Faces as loops of indices into `vertices`, counter-clockwise seen from outside, in the
  /// order of face_normals (dimension 2: the two sides only; dimensions 0 and 1: none).
  std::vector<std::vector<int>> faces;
  /// Hull edges as pairs of indices into `vertices`, each once (dimension 2: the polygon's).
  std::vector<std::array<int, 2>> edges;
};

/// Exact hull features of a non-empty cloud of finite points. Throws std::invalid_argument
/// (gjklab::InvalidGeometry) for an empty cloud or a non-finite coordinate.
HullFeatures hull_features(std::span<const Vec3> cloud);

}  // namespace gjklab::exact

namespace gjklab::exact {

/// The boundary of a full-dimensional cloud's convex hull as a closed triangle mesh (each face
/// of hull_features fanned from its first corner; counter-clockwise seen from outside), so that
/// a convex cloud can stand beside a non-convex mesh. Throws std::invalid_argument for a cloud
/// that spans fewer than three dimensions (it bounds no solid), and as hull_features does.
TriangleMesh hull_mesh(std::span<const Vec3> cloud);

}  // namespace gjklab::exact
