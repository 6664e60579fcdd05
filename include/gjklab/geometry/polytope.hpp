// A convex polytope given by its vertices: the convex hull of a finite point cloud.
//
// The cloud need not be in convex position, and may be flat, collinear or a single point:
// every point is a candidate support point. Vertices are stored contiguously.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// Thrown for clouds that cannot define a polytope (empty, or with a non-finite coordinate).
class InvalidGeometry : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class Polytope {
 public:
  /// Throws InvalidGeometry if the cloud is empty or has a NaN or infinite coordinate.
  explicit Polytope(std::vector<Vec3> vertices);

  std::span<const Vec3> vertices() const { return vertices_; }
  std::size_t size() const { return vertices_.size(); }

  /// Index of a vertex maximising d·x (the first such vertex on ties).
  std::size_t support_index(const Vec3& d) const;
  Vec3 support(const Vec3& d) const { return vertices_[support_index(d)]; }

  /// The same cloud with every vertex moved by the pose.
  Polytope transformed(const Pose& pose) const;
  /// The same cloud with every coordinate multiplied by factor.
  Polytope scaled(double factor) const;

  /// Length of the diagonal of the axis-aligned bounding box (length units).
  double bounding_box_diagonal() const;
  /// Mean of the vertices (not the volume centroid).
  Vec3 vertex_mean() const;

 private:
  std::vector<Vec3> vertices_;
};

/// Returns an empty string if the cloud is valid, else what is wrong with it (for messages).
std::string describe_invalid_cloud(std::span<const Vec3> cloud);

/// The larger bounding-box diagonal of two clouds: the size that relative errors refer to.
double pair_size(std::span<const Vec3> a, std::span<const Vec3> b);

}  // namespace gjklab
