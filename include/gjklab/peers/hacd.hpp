// Bullet's HACD (hierarchical approximate convex decomposition, K. Mamou, from Bullet's Extras;
// Debian: libbullet-extras-dev) as the `approximate` convex decomposition of a closed triangle
// mesh. Built only when CMake finds HACD's header and library (compile definition
// GJKLAB_HAVE_HACD); without it nothing here is defined.
//
// HACD clusters the mesh's triangles bottom-up: it starts from one cluster per triangle and
// merges adjacent clusters, cheapest first, while a merged cluster's concavity stays below the
// bound and more than min_clusters clusters remain. Each piece is the convex hull of (usually
// at most max_hull_vertices of) one cluster's vertices. Concavity is measured only at vertices
// along their normals (and, as options, at face centroids and a few more points), so HACD can
// call a non-convex cluster convex: an L of three cubes is one cluster unless face points are
// measured (tests/unit/test_hacd.cpp).
//
// The pieces are NOT proven to cover the solid, nor to lie inside it: a piece is the hull of a
// part of the surface, and neither the union of the pieces nor anything else is checked against
// the mesh's solid. This is what engines ship as a compound of convex shapes (Bullet's convex
// decomposition demo builds its btCompoundShape from exactly these hulls), and measuring how far
// it is from the solid is the point of studying it.
//
// Silent: no call-back is installed, and HACD writes to stdout only from its file and debug
// printing functions, which are never called. Deterministic: HACD draws no random numbers while
// decomposing (rand() only colours its VRML output) and walks only containers ordered by index,
// and the same mesh and options give bit-identical pieces, in the same order, from one call to
// the next (tests/unit/test_hacd.cpp) and from one process to the next (measured). The order
// of the faces matters, though: listing them in reverse can change the pieces (the six-spike
// star of the tests: 4 pieces, 5 with its faces reversed). HACD keeps
// process-wide state (a cancel flag that every run writes), so calls are serialised by a lock:
// threads may call hacd_decomposition, but one runs at a time.
#pragma once

#include <vector>

#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::peers {

/// HACD's parameters. The defaults are those of Bullet's ConvexDecompositionDemo (the library's
/// own example of use: min_clusters 2, concavity 100, compacity weight 0.1, volume weight 0,
/// at most 100 vertices per hull, no extra distance points, limited hulls) and, for the two it
/// does not set (connect_distance, scale), those of HACD's constructor.
///
/// Lengths marked "normalised" are in HACD's own frame: HACD moves the mesh's vertex centroid to
/// the origin and scales the mesh so that its bounding-box diagonal is 2·scale. A normalised
/// length L is therefore the fraction L / (2·scale) of the bounding-box diagonal, whatever the
/// mesh's size or units: with the defaults, concavity 100 is 5 % of the diagonal.
struct HacdOptions {
  /// The number of clusters at which merging stops (HACD's SetNClusters; it is a minimum, not a
  /// target): a mesh of at least this many triangles gives at least this many pieces, and more
  /// when the concavity bound stops the merging first. ≥ 1.
  int min_clusters = 2;
  /// The largest concavity a merged cluster may have: the largest distance, along a vertex's
  /// normal, from a cluster's (distance) point to its convex hull. Normalised length, finite,
  /// ≥ 0 (0 merges nothing: a merge needs a concavity strictly below the bound).
  double concavity = 100.0;
  /// Also measure concavity at the vertices of the triangle first hit by a ray cast inward from
  /// each triangle's centroid, so that thin parts (whose two sides are far apart in the surface
  /// but close through the solid) count as concave. Costs a ray cast against every triangle
  /// for every triangle: quadratic in the number of faces.
  bool add_extra_distance_points = false;
  /// Also measure a candidate merge's concavity at the points of its neighbouring clusters that
  /// fall inside its hull.
  bool add_neighbours_distance_points = false;
  /// Also measure concavity at each triangle's centroid (along the triangle's normal), not only
  /// at the vertices.
  bool add_faces_points = false;
  /// Weight of the shape term perimeter² / (8π·area) of a merged cluster (dimensionless, ½ for
  /// a disc: HACD divides by 4π times twice the area) in the merge cost, which adds it to the
  /// concavity: normalised length per unit of that ratio. Favours compact clusters. Finite, ≥ 0.
  double compacity_weight = 0.1;
  /// Weight of the merged hull's volume in the merge cost (HACD's beta). In the HACD that Bullet
  /// ships the term is computed but never added to the cost (a value > 0 only costs time), so
  /// it cannot change the pieces. Finite, ≥ 0.
  double volume_weight = 0.0;
  /// At most this many vertices per piece: each cluster's hull is grown from a first
  /// tetrahedron by adding, one at a time, the point that adds most volume, and stops at this
  /// count (the dropped points are left outside the piece). HACD can exceed it (see
  /// hacd_decomposition). ≥ 4, so that a piece can have volume. Ignored with full_hulls.
  int max_hull_vertices = 100;
  /// Give each piece the full convex hull of its cluster's vertices (HACD's Compute(fullCH)),
  /// with no bound on the number of vertices.
  bool full_hulls = false;
  /// Separate connected components of the mesh closer than this (between any two vertices)
  /// are linked so that HACD may merge them into one cluster. Normalised length, finite; a
  /// negative value links none. A connected mesh is not affected.
  double connect_distance = 30.0;
  /// Half the bounding-box diagonal in HACD's normalised frame: the unit of concavity and
  /// connect_distance (see above). Dimensionless, finite, > 0.
  double scale = 1000.0;

  friend bool operator==(const HacdOptions&, const HacdOptions&) = default;
};

/// Throws std::invalid_argument naming the first option out of its range (NaN included) and the
/// range allowed.
void validate(const HacdOptions& options);

/// HACD's pieces of a closed triangle mesh (validated closed elsewhere: exact/closed_mesh.hpp),
/// in HACD's cluster order, in the mesh's own frame: each piece is the convex hull of its
/// points, at least three (a cluster of one triangle gives that triangle, flat). The points are
/// those HACD returns for the piece, as the shapes engines build from them take them: normally
/// the vertices of the cluster's bounded hull; when HACD's incremental hull stops early on a
/// cluster, also the points it did not process, which may lie inside the hull and exceed
/// max_hull_vertices (anchor.off, 1 050 faces: a piece of 149 points with the bound 100). Every
/// point is, bit for bit, a vertex of the mesh (HACD's normalise / denormalise round trip moves
/// its copies by a few ulps; each is mapped back to the vertex of its cluster it came from).
/// Validates the options first. Throws std::runtime_error when the mesh has no face, a face
/// with an index out of range or a non-finite vertex, or when HACD fails or returns a point
/// that is no vertex of the piece's cluster.
///
/// Cost depends on the shape as much as on the size, and grows fast with the number of faces
/// (measured, default options): a third of a second for cactus.off (1 236 faces), a few seconds
/// for anchor.off (1 050) and elephant.off (5 558), nine minutes and 1.4 GB for bunny00.off
/// (75 408).
std::vector<std::vector<Vec3>> hacd_decomposition(const TriangleMesh& mesh,
                                                  const HacdOptions& options);

}  // namespace gjklab::peers
