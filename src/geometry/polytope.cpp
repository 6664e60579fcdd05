#include "gjklab/geometry/polytope.hpp"

#include <cmath>
#include <sstream>

namespace gjklab {

std::string describe_invalid_cloud(std::span<const Vec3> cloud) {
  if (cloud.empty()) return "empty point cloud";
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud[i].allFinite()) {
      std::ostringstream out;
      out << "non-finite coordinate in point " << i;
      return out.str();
    }
  }
  return {};
}

Polytope::Polytope(std::vector<Vec3> vertices) : vertices_(std::move(vertices)) {
  if (std::string problem = describe_invalid_cloud(vertices_); !problem.empty())
    throw InvalidGeometry(problem);
}

std::size_t Polytope::support_index(const Vec3& d) const {
  std::size_t best = 0;
  double best_dot = vertices_[0].dot(d);
  for (std::size_t i = 1; i < vertices_.size(); ++i) {
    const double dot = vertices_[i].dot(d);
    if (dot > best_dot) {
      best_dot = dot;
      best = i;
    }
  }
  return best;
}

Polytope Polytope::transformed(const Pose& pose) const {
  std::vector<Vec3> moved;
  moved.reserve(vertices_.size());
  for (const Vec3& v : vertices_) moved.push_back(pose.apply(v));
  return Polytope(std::move(moved));
}

Polytope Polytope::scaled(double factor) const {
  std::vector<Vec3> out;
  out.reserve(vertices_.size());
  for (const Vec3& v : vertices_) out.push_back(factor * v);
  return Polytope(std::move(out));
}

static double cloud_diagonal(std::span<const Vec3> cloud) {
  if (cloud.empty()) return 0;
  Vec3 lo = cloud[0], hi = cloud[0];
  for (const Vec3& v : cloud) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

double Polytope::bounding_box_diagonal() const { return cloud_diagonal(vertices_); }

Vec3 Polytope::vertex_mean() const {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : vertices_) sum += v;
  return sum / static_cast<double>(vertices_.size());
}

double pair_size(std::span<const Vec3> a, std::span<const Vec3> b) {
  return std::max(cloud_diagonal(a), cloud_diagonal(b));
}

}  // namespace gjklab
