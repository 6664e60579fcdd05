// A point cloud in another precision than double, for precision studies: the GJK queries are
// templates on the scalar type of their shapes, and run in float or long double on these.
//
// The cloud is the double cloud rounded to T, coordinate by coordinate, to nearest: the input
// an engine that stores its shapes in float would have. Going to long double is exact. A
// coordinate beyond T's range becomes ±∞, which the queries report as a numerical failure.
//
// Support is the full scan of Polytope: the first vertex maximising d·x, each dot product
// evaluated as (x·dx + y·dy) + z·dz in T, over coordinates laid out in lanes (kLanes vertices
// side by side, each lane keeping its own best) that the compiler turns into packed
// arithmetic; no hill climbing.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
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

  /// Index of the first vertex maximising d·x; 0 when vertex 0's dot product is NaN (a NaN
  /// d), as for Polytope's scan.
  std::size_t support_index(const Point& d) const {
    const T dx = d.x(), dy = d.y(), dz = d.z();
    auto dot = [&](std::size_t i) { return (xs_[i] * dx + ys_[i] * dy) + zs_[i] * dz; };
    if (std::isnan(dot(0))) return 0;
    // Each lane keeps the first maximiser of its vertices (strictly greater replaces; a NaN
    // never does, and −∞ lets a lane's first finite value in).
    T best[kLanes];
    std::uint32_t index[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      best[l] = -std::numeric_limits<T>::infinity();
      index[l] = static_cast<std::uint32_t>(l);
    }
    for (std::size_t i = 0; i < xs_.size(); i += kLanes) {
      for (int l = 0; l < kLanes; ++l) {
        const T v = dot(i + l);
        const bool better = v > best[l];
        best[l] = better ? v : best[l];
        index[l] = better ? static_cast<std::uint32_t>(i + l) : index[l];
      }
    }
    // The largest value, the smallest index among equals: the first maximiser overall.
    int winner = 0;
    for (int l = 1; l < kLanes; ++l)
      if (best[l] > best[winner] || (best[l] == best[winner] && index[l] < index[winner]))
        winner = l;
    return index[winner];
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
    build_lanes();
    box_extent_ = (box_upper_ - box_lower_).maxCoeff();
    max_magnitude_ = std::max(box_lower_.cwiseAbs().maxCoeff(), box_upper_.cwiseAbs().maxCoeff());
  }

  /// Vertices side by side in the scan (a multiple of kLanes; padded with copies of the last
  /// vertex, which never win: the real one has the same value and a smaller index).
  static constexpr int kLanes = 8;
  void build_lanes() {
    const std::size_t n = vertices_.size();
    const std::size_t padded = (n + kLanes - 1) / kLanes * kLanes;
    xs_.resize(padded);
    ys_.resize(padded);
    zs_.resize(padded);
    for (std::size_t i = 0; i < padded; ++i) {
      const Point& v = vertices_[std::min(i, n - 1)];
      xs_[i] = v.x();
      ys_[i] = v.y();
      zs_[i] = v.z();
    }
  }

  std::vector<Point> vertices_;
  std::vector<T> xs_, ys_, zs_;
  Point mean_ = Point::Zero();
  Point box_lower_ = Point::Zero();
  Point box_upper_ = Point::Zero();
  T box_extent_ = 0;
  T max_magnitude_ = 0;
};

}  // namespace gjklab
