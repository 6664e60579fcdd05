// A point cloud in another precision than double, for precision studies: the GJK queries are
// templates on the scalar type of their shapes, and run in float or long double on these.
//
// The cloud is the double cloud rounded to T, coordinate by coordinate, to nearest: the input
// an engine that stores its shapes in float would have. Going to long double is exact. A
// coordinate beyond T's range becomes ±∞, which the queries report as a numerical failure.
//
// Support is the full scan of Polytope (the first vertex maximising d·x, each dot product
// evaluated as (x·dx + y·dy) + z·dz in T), without Polytope's blocked SIMD layout or hill
// climbing: these clouds serve accuracy studies, where the double Polytope serves speed.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

template <class T>
class ScalarCloud {
 public:
  using Scalar = T;
  using Point = Vec3T<T>;

  /// The cloud rounded to T. Precondition: not empty (a Polytope's vertices).
  explicit ScalarCloud(std::span<const Vec3> cloud) {
    vertices_.reserve(cloud.size());
    for (const Vec3& x : cloud)
      vertices_.push_back(x.cast<T>());
    measure();
  }

  std::span<const Point> vertices() const { return vertices_; }
  std::size_t size() const { return vertices_.size(); }

  /// Index of the first vertex maximising d·x (0 for a NaN d, as for Polytope's scan).
  std::size_t support_index(const Point& d) const {
    std::size_t best = 0;
    T best_value = vertices_[0].dot(d);
    for (std::size_t i = 1; i < vertices_.size(); ++i) {
      const T value = vertices_[i].dot(d);
      if (value > best_value) {
        best_value = value;
        best = i;
      }
    }
    return best;
  }
  Point support(const Point& d) const { return vertices_[support_index(d)]; }
  /// Mean of the vertices, summed in T (an interior point for the queries' centre starts).
  Point vertex_mean() const { return mean_; }

  /// Bounding box and scales, as Polytope's (for the exact re-centring, recentring.hpp).
  const Point& box_lower() const { return box_lower_; }
  const Point& box_upper() const { return box_upper_; }
  T box_extent() const { return box_extent_; }
  T max_magnitude() const { return max_magnitude_; }

  /// The same cloud moved by t, computed in T (exact where every x + t_i is representable).
  ScalarCloud translated(const Point& t) const {
    ScalarCloud out = *this;
    for (Point& x : out.vertices_)
      x += t;
    out.measure();
    return out;
  }

 private:
  void measure() {
    Point sum = Point::Zero();
    box_lower_ = box_upper_ = vertices_.empty() ? Point::Zero() : vertices_[0];
    for (const Point& x : vertices_) {
      sum += x;
      box_lower_ = box_lower_.cwiseMin(x);
      box_upper_ = box_upper_.cwiseMax(x);
    }
    mean_ = sum / static_cast<T>(vertices_.size());
    box_extent_ = (box_upper_ - box_lower_).maxCoeff();
    max_magnitude_ = std::max(box_lower_.cwiseAbs().maxCoeff(), box_upper_.cwiseAbs().maxCoeff());
  }

  std::vector<Point> vertices_;
  Point mean_ = Point::Zero();
  Point box_lower_ = Point::Zero();
  Point box_upper_ = Point::Zero();
  T box_extent_ = 0;
  T max_magnitude_ = 0;
};

}  // namespace gjklab
