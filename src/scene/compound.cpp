#include "gjklab/scene/compound.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "gjklab/exact/hull_features.hpp"

namespace gjklab::scene {

namespace {

/// The mesh's triangles as the face loops mass_properties takes (indices checked: the caller
/// validated the mesh, but an index out of range here would read out of bounds).
std::vector<std::vector<int>> face_loops(const TriangleMesh& mesh) {
  std::vector<std::vector<int>> loops;
  loops.reserve(mesh.faces.size());
  for (const MeshFace& f : mesh.faces) {
    for (std::uint32_t v : f)
      if (v >= mesh.vertices.size())
        throw std::invalid_argument("a compound's mesh has a face index out of range");
    loops.push_back({static_cast<int>(f[0]), static_cast<int>(f[1]), static_cast<int>(f[2])});
  }
  return loops;
}

/// A ConvexShape of the hull of `cloud` moved by −centroid (the solid's centre of mass): the
/// piece in the body frame. Its volume and unit inertia are its hull's own (informative only;
/// 0 for a flat piece).
ConvexShape piece_shape(std::vector<Vec3> cloud, const Vec3& centroid, std::size_t index) {
  const std::string name = "piece " + std::to_string(index);
  const std::string problem = describe_invalid_cloud(cloud);
  if (!problem.empty()) throw InvalidGeometry(name + ": " + problem);
  for (Vec3& v : cloud)
    v -= centroid;
  exact::HullFeatures hull = exact::hull_features(cloud);
  if (hull.dimension < 2)
    throw InvalidGeometry(name + " is not a polyhedron or a polygon (its points span " +
                          std::to_string(hull.dimension) + " dimensions)");
  // An approximate decomposition may give a flat piece (a cluster of coplanar triangles): it
  // collides as a polygon with two sides (its in-plane edge normals are not faces). It has no
  // volume, which the body does not miss: its mass is the solid's.
  if (hull.dimension == 2) hull.face_normals.resize(hull.faces.size());
  const MassProperties mp =
      hull.dimension == 3 ? mass_properties(hull.vertices, hull.faces) : MassProperties{};
  double radius = 0;
  for (const Vec3& v : hull.vertices)
    radius = std::max(radius, v.norm());
  ConvexShape piece{Polytope(std::move(hull.vertices)),
                    std::move(hull.faces),
                    std::move(hull.face_normals),
                    mp.volume,
                    mp.unit_inertia,
                    Vec3::Zero(),
                    radius,
                    0,
                    0};
  piece.size = piece.polytope.bounding_box_diagonal();
  return piece;
}

}  // namespace

std::shared_ptr<const CompoundShape> make_compound_shape(
    const TriangleMesh& solid, const std::vector<std::vector<Vec3>>& pieces) {
  if (pieces.empty()) throw std::invalid_argument("a compound needs at least one piece");
  const std::string problem = describe_invalid_cloud(solid.vertices);
  if (!problem.empty()) throw InvalidGeometry("the mesh: " + problem);
  const MassProperties mp = mass_properties(solid.vertices, face_loops(solid));
  auto out = std::make_shared<CompoundShape>();
  // The envelope covers the pieces and the mesh: an approximate piece may stick out of the
  // solid, and the bounding boxes must hold whatever collides.
  std::vector<Vec3> all;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    out->pieces.push_back(piece_shape(pieces[k], mp.centroid, k));
    const auto v = out->pieces.back().polytope.vertices();
    all.insert(all.end(), v.begin(), v.end());
  }
  for (const Vec3& v : solid.vertices)
    all.push_back(v - mp.centroid);
  ConvexShape envelope = piece_shape(std::move(all), Vec3::Zero(), pieces.size());
  envelope.volume = mp.volume;
  envelope.unit_inertia = mp.unit_inertia;
  envelope.input_origin = -mp.centroid;
  out->envelope = std::make_shared<const ConvexShape>(std::move(envelope));
  return out;
}

RigidBody make_dynamic_body(std::shared_ptr<const CompoundShape> compound, double density,
                            const Quat& orientation, const Vec3& position) {
  if (!compound) throw std::invalid_argument("a compound body needs a shape");
  RigidBody b = make_dynamic_body(compound->envelope, density, orientation, position);
  b.compound = std::move(compound);
  return b;
}

RigidBody make_static_body(std::shared_ptr<const CompoundShape> compound, const Quat& orientation,
                           const Vec3& position) {
  if (!compound) throw std::invalid_argument("a compound body needs a shape");
  RigidBody b = make_static_body(compound->envelope, orientation, position);
  b.compound = std::move(compound);
  return b;
}

}  // namespace gjklab::scene
