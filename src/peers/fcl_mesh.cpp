// Adapter from gjklab's triangle meshes to FCL 0.7's BVHModel<OBBRSS> (see peers/fcl_mesh.hpp).
#include "gjklab/peers/fcl_mesh.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace gjklab::peers {

struct FclMesh::Impl {
  fcl::BVHModel<fcl::OBBRSSd> model;
};

namespace {

void validate(const TriangleMesh& mesh) {
  if (mesh.faces.empty()) throw std::invalid_argument("fcl mesh: the mesh has no faces");
  for (const Vec3& v : mesh.vertices)
    if (!v.allFinite()) throw std::invalid_argument("fcl mesh: a coordinate is not finite");
  for (const MeshFace& f : mesh.faces)
    for (const std::uint32_t i : f)
      if (i >= mesh.vertices.size())
        throw std::invalid_argument("fcl mesh: face index " + std::to_string(i) + " out of range");
}

void validate(const FclMeshOptions& o) {
  if (!(o.rel_err >= 0 && o.rel_err <= 1) || !(o.abs_err >= 0) || o.max_contacts < 1)
    throw std::invalid_argument(
        "fcl mesh: needs 0 <= rel_err <= 1, abs_err >= 0 and max_contacts >= 1");
}

/// Throws if FCL reports a failure while building (its return codes, BVH_OK = 0).
void check(int status, const char* step) {
  if (status != fcl::BVH_OK)
    throw std::runtime_error(std::string("fcl mesh: ") + step + " failed with code " +
                             std::to_string(status));
}

Vec3 to_vec(const fcl::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

FclMesh::FclMesh(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  validate(mesh);
  std::vector<fcl::Vector3d> points;
  points.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices)
    points.emplace_back(v.x(), v.y(), v.z());
  // Triangles in the mesh's face order: FCL reports a triangle by its index in this list.
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.faces.size());
  for (const MeshFace& f : mesh.faces)
    triangles.emplace_back(f[0], f[1], f[2]);
  fcl::BVHModel<fcl::OBBRSSd>& m = impl_->model;
  check(m.beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size())),
        "beginModel");
  check(m.addSubModel(points, triangles), "addSubModel");
  check(m.endModel(), "endModel");
}

FclMesh::~FclMesh() = default;
FclMesh::FclMesh(FclMesh&&) noexcept = default;
FclMesh& FclMesh::operator=(FclMesh&&) noexcept = default;

std::size_t FclMesh::triangle_count() const {
  return static_cast<std::size_t>(impl_->model.num_tris);
}

std::size_t FclMesh::bounding_volume_count() const {
  return static_cast<std::size_t>(impl_->model.getNumBVs());
}

FclMeshAnswer fcl_mesh_collide(const FclMesh& a, const FclMesh& b, const FclMeshOptions& options) {
  validate(options);
  // No contact points: FCL then runs its boolean triangle test and records the face ids only.
  const fcl::CollisionRequestd request(options.max_contacts, /*enable_contact=*/false);
  fcl::CollisionResultd result;
  const fcl::Transform3d identity = fcl::Transform3d::Identity();
  fcl::collide(&a.impl().model, identity, &b.impl().model, identity, request, result);
  FclMeshAnswer answer;
  answer.intersect = result.isCollision();
  answer.contacts = result.numContacts();
  if (answer.contacts > 0) {
    answer.face_a = static_cast<std::int64_t>(result.getContact(0).b1);
    answer.face_b = static_cast<std::int64_t>(result.getContact(0).b2);
  }
  return answer;
}

FclMeshAnswer fcl_mesh_distance(const FclMesh& a, const FclMesh& b, const FclMeshOptions& options) {
  validate(options);
  fcl::DistanceRequestd request(/*enable_nearest_points=*/true);
  request.rel_err = options.rel_err;
  request.abs_err = options.abs_err;
  fcl::DistanceResultd result;
  const fcl::Transform3d identity = fcl::Transform3d::Identity();
  fcl::distance(&a.impl().model, identity, &b.impl().model, identity, request, result);
  FclMeshAnswer answer;
  answer.distance = result.min_distance;
  answer.intersect = result.min_distance <= 0;
  answer.face_a = static_cast<std::int64_t>(result.b1);
  answer.face_b = static_cast<std::int64_t>(result.b2);
  // At distance 0 FCL's points are leftovers of its edge–edge loop, not a common point.
  if (!answer.intersect) {
    answer.witness_a = to_vec(result.nearest_points[0]);
    answer.witness_b = to_vec(result.nearest_points[1]);
  }
  return answer;
}

}  // namespace gjklab::peers
