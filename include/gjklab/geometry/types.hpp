// Basic value types of the geometry layer: points, directions and rigid poses, all in double.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace gjklab {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// A rigid motion x ↦ rotation·x + translation (rotation orthonormal with determinant +1).
struct Pose {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();

  static Pose identity() { return {}; }
  static Pose from_translation(const Vec3& t) { return {Mat3::Identity(), t}; }
  /// Builds a pose from a quaternion (w, x, y, z), normalising it first.
  static Pose from_quaternion(const Quat& q, const Vec3& t) {
    return {q.normalized().toRotationMatrix(), t};
  }

  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
  /// Rotates a direction into the body frame (the inverse rotation; no translation).
  Vec3 to_body_direction(const Vec3& d) const { return rotation.transpose() * d; }
};

}  // namespace gjklab
