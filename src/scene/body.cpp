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

namespace {

/// kSweptMassDirections directions on the unit sphere: a Fibonacci lattice on the upper
/// half and its mirror image through the centre (a centrally symmetric set, so that a swept
/// point's centre of mass is the point), scaled so that the hull of the points has the volume
/// of the unit ball (a swept point then has the ball's exact volume; computed once).
const std::vector<Vec3>& swept_mass_directions() {
  static const std::vector<Vec3> directions = [] {
    std::vector<Vec3> d;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));  // the golden angle (rad)
    const int half = kSweptMassDirections / 2;
    for (int k = 0; k < half; ++k) {
      const double z = 1.0 - (k + 0.5) / half;  // in (0, 1): the upper half only
      const double r = std::sqrt(1.0 - z * z);
      d.emplace_back(r * std::cos(golden * k), r * std::sin(golden * k), z);
    }
    for (int k = 0; k < half; ++k)
      d.push_back(-d[k]);
    const exact::HullFeatures hull = exact::hull_features(d);
    const double volume = mass_properties(hull.vertices, hull.faces).volume;
    const double scale = std::cbrt((4.0 / 3.0) * M_PI / volume);
    for (Vec3& v : d)
      v *= scale;
    return d;
  }();
  return directions;
}

}  // namespace

std::shared_ptr<const ConvexShape> make_swept_shape(std::vector<Vec3> cloud, double radius) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw std::invalid_argument("a swept radius must be positive and finite, not " +
                                std::to_string(radius));
  const std::string problem = describe_invalid_cloud(cloud);
  if (!problem.empty()) throw InvalidGeometry(problem);
  exact::HullFeatures core = exact::hull_features(cloud);
  // The swept body's mass: the hull of every core vertex moved along every direction.
  std::vector<Vec3> grown;
  grown.reserve(core.vertices.size() * kSweptMassDirections);
  for (const Vec3& v : core.vertices)
    for (const Vec3& d : swept_mass_directions())
      grown.push_back(v + radius * d);
  const exact::HullFeatures outer = exact::hull_features(grown);
  const MassProperties mp = mass_properties(outer.vertices, outer.faces);
  std::vector<Vec3> centred = core.vertices;
  double reach = 0;
  for (Vec3& v : centred) {
    v -= mp.centroid;
    reach = std::max(reach, v.norm());
  }
  // Faces for manifold clipping: a solid core's, or a flat core's two sides (its in-plane
  // edge normals are not faces).
  if (core.dimension < 3) core.face_normals.resize(core.faces.size());
  auto shape = std::make_shared<ConvexShape>(
      ConvexShape{Polytope(std::move(centred)), std::move(core.faces), std::move(core.face_normals),
                  mp.volume, mp.unit_inertia, -mp.centroid, reach + radius, 0, radius});
  const Vec3 extent =
      shape->polytope.box_upper() - shape->polytope.box_lower() + Vec3::Constant(2 * radius);
  shape->size = extent.norm();
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
