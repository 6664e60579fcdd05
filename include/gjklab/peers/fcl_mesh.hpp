// FCL (the Flexible Collision Library, 0.7) on closed triangle meshes: collide and distance
// between two fcl::BVHModel<fcl::OBBRSSd>, the way robotics code queries non-convex meshes. Built
// only when CMake finds FCL (compile definition GJKLAB_HAVE_FCL).
//
// Geometry. An FclMesh holds the mesh's vertices as given (doubles, already posed: the same
// numbers exact::mesh_truth sees) and its faces in their order, with the identity transform.
// FCL builds an OBBRSS tree over the triangles (mean split, as BVHModel does by default); the
// face ids FCL reports (face_a, face_b) are indices into TriangleMesh::faces.
//
// What FCL answers: it tests triangles, never solids. Both queries walk the two trees and
// evaluate triangle pairs; neither looks at the inside of a closed mesh. Measured with FCL 0.7.0
// against exact::mesh_truth on 3 000 random pairs of non-convex star meshes (radius ≤ 1); each
// behaviour is pinned in tests/unit/test_fcl_mesh.cpp:
//   - Separated meshes: the distance is the least triangle–triangle distance, off by rounding
//     only, about 1e-16 times the coordinates' magnitude (absolute): ≤ 4e-14 relative on the
//     1 354 pairs with gaps above 1e-3, 2e-7 relative at a gap of 1e-10. Collide answered false on
//     every separated pair.
//   - Crossing surfaces: collide is true (a separating-axis test on closed intervals, so
//     touching triangles collide too) and distance is exactly 0, never negative (1 544 of 1 544
//     crossing pairs); the faces reported meet.
//   - A mesh strictly inside the other (the solids meet, exact::MeshContact::a_inside_b or
//     b_inside_a): collide is FALSE, with no contact at any max_contacts, and distance is the
//     positive gap between the two surfaces (all 101 contained pairs). FCL does not report
//     containment; a caller that needs it must test it separately (e.g. one vertex of each mesh
//     against the other solid).
//   - DistanceRequest::enable_signed_distance changes nothing here: FCL takes its signed path
//     only on a negative distance, which its triangle distance never returns.
//   - Witnesses at distance 0: FCL's triangle distance returns 0 for overlapping triangles with
//     closest points left over from its edge–edge loop, not a common point (measured: up to 0.4
//     apart on meshes of radius 1). They are not reported (nullopt); at a positive distance
//     FCL's nearest points are reported, one on each mesh (on faces face_a and face_b).
//   - Small triangles: FCL's triangle distance tests a vertex against the other triangle's
//     face only when that face's |(b − a) × (c − a)|² exceeds 1e-15 (absolute, length⁴), i.e.
//     when twice its area exceeds 3.2e-8 (a right triangle's legs exceed 1.8e-4 length units).
//     Below that, a vertex facing such a face is missed, and FCL answered distance 0 (a contact)
//     for meshes 1e-5 apart whose triangles had legs of 1e-4, while collide, which has no such
//     threshold, answered false. Meshes with triangles that small should be scaled up first.
//
// Cost outside the query: building an FclMesh (the tree) is done once; the queries only read it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::peers {

/// FCL's query settings for meshes. The defaults are FCL's own (DistanceRequest,
/// CollisionRequest), under which the distance is the least triangle–triangle distance up to
/// the rounding of FCL's triangle distance.
struct FclMeshOptions {
  /// Early stop of the distance traversal (FCL's DistanceRequest::rel_err, abs_err, both ≥ 0,
  /// rel_err ≤ 1; abs_err in length units). FCL skips a pair of bounding volumes whose lower
  /// bound c has c ≥ d − abs_err and c·(1 + rel_err) ≥ d, d the least distance found so far.
  /// The answer d then satisfies d ≤ d* + abs_err and d ≤ (1 + rel_err)·d*, d* the true least
  /// triangle distance. 0 and 0 (FCL's defaults): no early stop.
  double rel_err = 0;
  double abs_err = 0;
  /// Collide stops after this many intersecting triangle pairs (FCL's
  /// CollisionRequest::num_max_contacts, ≥ 1). 1 (FCL's default): the boolean query.
  std::size_t max_contacts = 1;
};

/// A closed triangle mesh as an fcl::BVHModel<fcl::OBBRSSd>. Movable, not copyable.
class FclMesh {
 public:
  /// Throws std::invalid_argument for a mesh without faces, a face index out of range or a
  /// non-finite coordinate, std::runtime_error if FCL refuses the model.
  explicit FclMesh(const TriangleMesh& mesh);
  ~FclMesh();
  FclMesh(FclMesh&&) noexcept;
  FclMesh& operator=(FclMesh&&) noexcept;

  std::size_t triangle_count() const;
  /// Nodes of FCL's bounding-volume tree (2·triangles − 1 for a full build).
  std::size_t bounding_volume_count() const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// One FCL answer for two meshes A and B (frames: the meshes' own, length units as given).
struct FclMeshAnswer {
  /// collide: some triangle pairs intersect; distance: the distance is 0. Either way, false
  /// for a mesh strictly inside the other (see above).
  bool intersect = false;
  /// distance only: the least distance between the two surfaces (≥ 0, never signed).
  std::optional<double> distance;
  /// distance only, when distance > 0: FCL's nearest points on A and on B.
  std::optional<Vec3> witness_a, witness_b;
  /// collide: intersecting triangle pairs found before stopping (≤ max_contacts).
  std::size_t contacts = 0;
  /// The faces (indices into TriangleMesh::faces) of the first intersecting pair (collide) or
  /// of the nearest pair (distance); −1 when collide found none.
  std::int64_t face_a = -1, face_b = -1;
};

/// fcl::collide on the two meshes (no contact points, stops after options.max_contacts pairs).
/// Throws std::invalid_argument for invalid options.
FclMeshAnswer fcl_mesh_collide(const FclMesh& a, const FclMesh& b,
                               const FclMeshOptions& options = {});

/// fcl::distance on the two meshes with nearest points. Throws std::invalid_argument for
/// invalid options.
FclMeshAnswer fcl_mesh_distance(const FclMesh& a, const FclMesh& b,
                                const FclMeshOptions& options = {});

}  // namespace gjklab::peers
