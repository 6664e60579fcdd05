// Basic value types of the geometry layer: points, directions and rigid poses, all in double.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace gjklab {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// True if every coordinate of v is finite. The same answer as v.allFinite(), in one test
/// the compiler inlines: x·0 is ±0 for finite x and NaN for ±∞ and NaN, and any NaN makes the
/// sum compare unequal to 0.
inline bool is_finite(const Vec3& v) {
  return v.x() * 0.0 + v.y() * 0.0 + v.z() * 0.0 == 0.0;
}

/// True if every coordinate of v is zero (either sign): v.isZero(0), inlined.
inline bool is_zero(const Vec3& v) {
  return v.x() == 0.0 && v.y() == 0.0 && v.z() == 0.0;
}

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
