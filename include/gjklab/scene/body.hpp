// Rigid bodies of the scene layer: a convex shape (a Polytope) with its hull faces and mass
// properties, and the body state integrated by the world.
//
// Frames. A shape's vertices are stored in its *body frame*, whose origin is the hull's centre
// of mass (the volume centroid, not the vertex mean) and whose axes are those of the cloud it
// was made from. A body's pose maps the body frame to the world frame.
//
// Mass. The hull (exact, from exact::hull_features) is cut into tetrahedra, one per triangle of
// its fan-triangulated faces, with the body-frame origin as apex; volume, centroid and the
// second moment ∫ x xᵀ dV are sums over them. The inertia tensor about the centre of mass is
// density · (tr(C) I − C), C the second moment about the centroid (kg·m², for density in kg/m³
// and lengths in m; the layer is unit-agnostic, these are the units of the scene files).
//
// Sphere-swept shapes. A shape may carry a `swept_radius` r: the body is its core (the
// polytope, which may then be a point, a segment or flat) grown by a ball of radius r — a
// ball, a capsule, a rounded box. GJK runs on the cores and the radii are added to the answer.
// Mass properties come from the tetrahedra of the hull of the core's vertices each moved by r
// along kSweptMassDirections directions of a sphere, scaled so that a single point gives the
// ball's exact volume; the swept volume of other cores comes out slightly larger (the scaled
// facets bulge past the rounded edges: +1.0 % for a capsule, +1.1 % for a unit cube swept by
// 0.3, tested), and the inertia with it.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::scene {

/// A convex shape ready for simulation: vertices centred on the centre of mass, hull faces in
/// the body frame, and the mass properties of unit density.
struct ConvexShape {
  /// The vertices in the body frame (centre of mass at the origin).
  Polytope polytope;
  /// Hull faces as loops of indices into polytope.vertices(), counter-clockwise seen from
  /// outside, with their unit outward normals (body frame).
  std::vector<std::vector<int>> faces;
  std::vector<Vec3> face_normals;
  /// Hull volume (length³) and the inertia tensor of unit density about the centre of mass,
  /// in the body frame (length⁵: multiply by the density for kg·m²).
  double volume = 0;
  Mat3 unit_inertia = Mat3::Zero();
  /// Where the input cloud's origin lies in the body frame (−centroid in input coordinates):
  /// callers that placed the cloud by its own origin add pose.rotation · this to the position.
  Vec3 input_origin = Vec3::Zero();
  /// Radius of the smallest origin-centred ball holding the vertices (length units).
  double radius = 0;
  /// Bounding-box diagonal of the vertices: the size penetrations are measured against.
  /// Both include the swept radius.
  double size = 0;
  /// Radius of the ball the core is swept by (length units; 0: the polytope itself).
  double swept_radius = 0;
};

/// Directions of the sphere sampled for a swept shape's mass properties (see the file comment).
inline constexpr int kSweptMassDirections = 64;

/// Mass properties of a convex hull of unit density, from its tetrahedra (see the file comment).
struct MassProperties {
  double volume = 0;
  Vec3 centroid = Vec3::Zero();
  /// About the centroid, in the cloud's axes (length⁵).
  Mat3 unit_inertia = Mat3::Zero();
};

/// Mass properties of a closed polyhedron given by its vertices and its faces (index loops,
/// counter-clockwise seen from outside). Throws InvalidGeometry for a non-positive volume.
MassProperties mass_properties(std::span<const Vec3> vertices,
                               const std::vector<std::vector<int>>& faces);

/// Builds a shape from a cloud: the exact hull, its faces and mass properties; the vertices
/// are re-expressed about the centroid. Throws InvalidGeometry for an invalid cloud or one
/// whose hull has no volume (flat, collinear or a single point).
std::shared_ptr<const ConvexShape> make_convex_shape(std::vector<Vec3> cloud);

/// The shape of `cloud` swept by a ball of radius `radius` (> 0, finite; length units): the
/// core's vertices (its hull's, or the distinct points of a lower-dimensional cloud: a point
/// gives a ball, two a capsule) about the swept shape's centre of mass, with mass properties
/// as the file comment says. A core with volume keeps its hull faces (contact manifolds are
/// clipped on them); a lower-dimensional core has none. Throws InvalidGeometry for an invalid
/// cloud and std::invalid_argument for a bad radius.
std::shared_ptr<const ConvexShape> make_swept_shape(std::vector<Vec3> cloud, double radius);

struct CompoundShape;

/// A rigid body. Static bodies (inverse mass 0) never move and collide with dynamic ones only.
struct RigidBody {
  /// The convex shape; for a compound body its envelope (bounds and mass, see compound.hpp).
  std::shared_ptr<const ConvexShape> shape;
  /// Set for a body made of convex pieces (compound.hpp): contacts come from its pieces.
  std::shared_ptr<const CompoundShape> compound;
  Pose pose;                             ///< body frame → world frame
  Quat orientation = Quat::Identity();   ///< the rotation of `pose`, kept for integration
  Vec3 velocity = Vec3::Zero();          ///< of the centre of mass, world frame (length/s)
  Vec3 angular_velocity = Vec3::Zero();  ///< world frame (rad/s)
  double mass = 0;                       ///< 0 for static bodies
  double inverse_mass = 0;
  Mat3 inverse_inertia_body = Mat3::Zero();  ///< body frame; zero for static bodies
  double friction = 0.5;     ///< Coulomb coefficient (the pair uses the geometric mean)
  double restitution = 0.0;  ///< the pair uses the larger of the two
  /// The collision state of the last step: true when the body had at least one contact.
  bool touching = false;

  bool is_static() const { return inverse_mass == 0; }
  /// Inverse inertia in the world frame: R I⁻¹ Rᵀ.
  Mat3 inverse_inertia_world() const {
    return pose.rotation * inverse_inertia_body * pose.rotation.transpose();
  }
  /// Velocity of the material point at world position p (length/s).
  Vec3 point_velocity(const Vec3& p) const {
    return velocity + angular_velocity.cross(p - pose.translation);
  }
};

/// A dynamic body of the given density (mass/length³) at a pose given by a unit quaternion and
/// the world position of its centre of mass. Throws std::invalid_argument for a density that is
/// not positive and finite.
RigidBody make_dynamic_body(std::shared_ptr<const ConvexShape> shape, double density,
                            const Quat& orientation, const Vec3& position);
/// A static body (infinite mass) at the given pose.
RigidBody make_static_body(std::shared_ptr<const ConvexShape> shape, const Quat& orientation,
                           const Vec3& position);

}  // namespace gjklab::scene
