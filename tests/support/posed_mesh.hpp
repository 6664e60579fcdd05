// A closed mesh moved rigidly and scaled, for the tests of the mesh queries.
#pragma once

#include <Eigen/Geometry>

#include "gjklab/geometry/triangle_mesh.hpp"

namespace gjklab::testing {

/// The mesh scaled, rotated about an axis and moved (vertices rounded to doubles: the mesh as
/// given is what every side of a test answers for).
inline TriangleMesh posed(const TriangleMesh& m, double scale, const Vec3& axis, double angle,
                          const Vec3& shift) {
  const Mat3 r = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  TriangleMesh out = m;
  for (Vec3& v : out.vertices)
    v = scale * (r * v) + shift;
  return out;
}

}  // namespace gjklab::testing
