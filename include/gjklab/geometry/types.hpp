// Basic value types of the geometry layer: points, directions and rigid poses, in double.
// The GJK queries are templates on the scalar type (double by default; float and long double
// for precision studies, see geometry/scalar_cloud.hpp): Vec3T<T> is their point type.
#pragma once

#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace gjklab {

template <class T>
using Vec3T = Eigen::Matrix<T, 3, 1>;
using Vec3 = Vec3T<double>;
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

/// The same tests in any scalar type (the double overloads above take Eigen expressions too).
template <class T>
bool is_finite(const Vec3T<T>& v) {
  return v.x() * T(0) + v.y() * T(0) + v.z() * T(0) == T(0);
}
template <class T>
bool is_zero(const Vec3T<T>& v) {
  return v.x() == T(0) && v.y() == T(0) && v.z() == T(0);
}

/// Scales a tolerance stated for double that measures rounding (a multiple of double's unit
/// roundoff) to the scalar type T: multiplied by ε_T/ε_double, a power of two (2^29 for float,
/// 2^-11 for x87 long double, exactly 1 for double), so double's answers are unchanged and
/// the tolerance keeps its meaning relative to T's rounding.
template <class T>
constexpr T rounding_scaled(double tolerance) {
  return static_cast<T>(tolerance * (static_cast<double>(std::numeric_limits<T>::epsilon()) /
                                     std::numeric_limits<double>::epsilon()));
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
