#include "gjklab/scene/body.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "gjklab/exact/hull_features.hpp"

namespace gjklab::scene {

namespace {

/// ∫ x xᵀ dV over the tetrahedron (0, a, b, c), of signed volume det[a b c]/6: the canonical
/// tetrahedron's second moment (1/120)·[[2,1,1],[1,2,1],[1,1,2]] mapped by the linear map
/// whose columns are a, b, c (the Jacobian is det[a b c]).
Mat3 tetrahedron_second_moment(const Vec3& a, const Vec3& b, const Vec3& c) {
  Mat3 m;
  m.col(0) = a;
  m.col(1) = b;
  m.col(2) = c;
  Mat3 canonical;
  canonical << 2, 1, 1, 1, 2, 1, 1, 1, 2;
  canonical /= 120.0;
  return m.determinant() * (m * canonical * m.transpose());
}

}  // namespace

MassProperties mass_properties(std::span<const Vec3> vertices,
                               const std::vector<std::vector<int>>& faces) {
  // Apex at the vertex mean keeps the tetrahedra's coordinates small (less cancellation than
  // an apex at a far-away origin); the moments are shifted back at the end.
  Vec3 apex = Vec3::Zero();
  for (const Vec3& v : vertices)
    apex += v;
  apex /= static_cast<double>(vertices.size());
  double volume = 0;
  Vec3 first_moment = Vec3::Zero();
  Mat3 second_moment = Mat3::Zero();
  for (const auto& loop : faces) {
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      const Vec3 a = vertices[loop[0]] - apex;
      const Vec3 b = vertices[loop[k]] - apex;
      const Vec3 c = vertices[loop[k + 1]] - apex;
      const double v = a.dot(b.cross(c)) / 6.0;
      volume += v;
      first_moment += v * (a + b + c) / 4.0;
      second_moment += tetrahedron_second_moment(a, b, c);
    }
  }
  if (!(volume > 0) || !std::isfinite(volume))
    throw InvalidGeometry("the hull has no volume (" + std::to_string(volume) + ")");
  MassProperties out;
  out.volume = volume;
  const Vec3 centroid = first_moment / volume;  // relative to the apex
  out.centroid = apex + centroid;
  // Parallel-axis shift of the second moment from the apex to the centroid.
  const Mat3 c = second_moment - volume * centroid * centroid.transpose();
  out.unit_inertia = c.trace() * Mat3::Identity() - c;
  return out;
}

std::shared_ptr<const ConvexShape> make_convex_shape(std::vector<Vec3> cloud) {
  const std::string problem = describe_invalid_cloud(cloud);
  if (!problem.empty()) throw InvalidGeometry(problem);
  exact::HullFeatures hull = exact::hull_features(cloud);
  if (hull.dimension != 3)
    throw InvalidGeometry("the hull has no volume (its points span " +
                          std::to_string(hull.dimension) + " dimensions)");
  const MassProperties mp = mass_properties(hull.vertices, hull.faces);
  std::vector<Vec3> centred = hull.vertices;
  double radius = 0;
  for (Vec3& v : centred) {
    v -= mp.centroid;
    radius = std::max(radius, v.norm());
  }
  auto shape = std::make_shared<ConvexShape>(
      ConvexShape{Polytope(std::move(centred)), std::move(hull.faces), std::move(hull.face_normals),
                  mp.volume, mp.unit_inertia, -mp.centroid, radius, 0});
  shape->size = shape->polytope.bounding_box_diagonal();
  return shape;
}

RigidBody make_dynamic_body(std::shared_ptr<const ConvexShape> shape, double density,
                            const Quat& orientation, const Vec3& position) {
  if (!(density > 0) || !std::isfinite(density))
    throw std::invalid_argument("density must be positive and finite, not " +
                                std::to_string(density));
  RigidBody b = make_static_body(std::move(shape), orientation, position);
  b.mass = density * b.shape->volume;
  b.inverse_mass = 1.0 / b.mass;
  b.inverse_inertia_body = (density * b.shape->unit_inertia).inverse();
  return b;
}

RigidBody make_static_body(std::shared_ptr<const ConvexShape> shape, const Quat& orientation,
                           const Vec3& position) {
  RigidBody b;
  b.shape = std::move(shape);
  b.orientation = orientation.normalized();
  b.pose = Pose{b.orientation.toRotationMatrix(), position};
  return b;
}

}  // namespace gjklab::scene
