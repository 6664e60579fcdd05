// Compound bodies: a closed non-convex solid (a triangle mesh) that collides as a set of convex
// pieces, the pieces a convex decomposition gave for it (the scene layer takes the pieces as
// plain point clouds and names no decomposition: the caller chose one).
//
// Frames. The body frame's origin is the SOLID's centre of mass (from the mesh's triangles, not
// from the pieces), its axes the mesh's. Every piece's vertices are in that body frame, so one
// pose places them all.
//
// Mass. Volume, centroid and inertia come from the closed mesh itself: one tetrahedron per
// triangle with a common apex (the divergence theorem, summed in double by mass_properties;
// relative error about 1e-15 per triangle, far below any scene's tolerance). They are not the
// sum over the pieces: an approximate decomposition's pieces may overlap or leave gaps, and even
// the exact one's corners are rounded.
//
// Contacts. A pair with a compound body is queried piece pair by piece pair (pieces whose world
// boxes, grown by the pair's contact margin, overlap); each piece pair gets the contacts two
// convex bodies get, with its own normal. Piece pairs run cold (no warm start carried between
// steps), so a checkpoint needs nothing of them but the body pair's contact points.
#pragma once

#include <memory>
#include <vector>

#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/geometry/types.hpp"
#include "gjklab/scene/body.hpp"

namespace gjklab::scene {

/// A body made of convex pieces (see the file comment).
struct CompoundShape {
  /// What the body is for everything but contacts: the convex hull of every piece's vertices
  /// (body frame), for bounding boxes, reach and size, with the SOLID's volume and unit inertia
  /// (not the hull's) and input_origin the mesh's origin in the body frame.
  std::shared_ptr<const ConvexShape> envelope;
  /// The pieces, each a ConvexShape whose vertices and faces are in the body frame (not about
  /// its own centroid; its volume and unit_inertia are its own hull's and unused).
  std::vector<ConvexShape> pieces;
};

/// The compound of a closed, outward-oriented, non-self-intersecting mesh (the caller validated
/// it) and its convex pieces (clouds in the mesh's frame, each spanning a volume or, as an
/// approximate decomposition's may, a plane). Throws InvalidGeometry naming the piece for a
/// cloud that is invalid or collinear, and for a mesh of non-positive volume;
/// std::invalid_argument for no piece or a face index out of range.
std::shared_ptr<const CompoundShape> make_compound_shape(
    const TriangleMesh& solid, const std::vector<std::vector<Vec3>>& pieces);

/// A dynamic compound body (see make_dynamic_body): shape is the envelope, compound is set.
RigidBody make_dynamic_body(std::shared_ptr<const CompoundShape> compound, double density,
                            const Quat& orientation, const Vec3& position);
/// A static compound body (see make_static_body).
RigidBody make_static_body(std::shared_ptr<const CompoundShape> compound, const Quat& orientation,
                           const Vec3& position);

}  // namespace gjklab::scene
