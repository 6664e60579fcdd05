// The GJK simplex: up to four points of the Minkowski difference A − B, each remembered with
// the support points of A and B that produced it (for witness points and traces).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

struct SimplexVertex {
  Vec3 w = Vec3::Zero();  ///< w = a − b, a point of the Minkowski difference
  Vec3 a = Vec3::Zero();  ///< support point of A
  Vec3 b = Vec3::Zero();  ///< support point of B
  /// Indices of a and b in their polytopes' vertex lists (−1 for shapes without indices).
  std::int32_t index_a = -1;
  std::int32_t index_b = -1;
};

class Simplex {
 public:
  static constexpr int kCapacity = 4;

  int size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == kCapacity; }
  const SimplexVertex& operator[](int i) const { return vertices_[i]; }
  /// The points in order (oldest first): e.g. the start of a warm-started query.
  std::span<const SimplexVertex> vertices() const {
    return {vertices_.data(), static_cast<std::size_t>(size_)};
  }

  /// The points w_i in order, stored contiguously (w_i = (*this)[i].w): the input of the
  /// sub-algorithms, read on every iteration without gathering them from the 80-byte vertices.
  const std::array<Vec3, kCapacity>& points() const { return points_; }

  void push(const SimplexVertex& v) {
    points_[size_] = v.w;
    vertices_[size_++] = v;
  }
  void clear() { size_ = 0; }

  /// Keeps the vertices whose bit is set in mask (bit i ↔ vertex i), preserving their order.
  void keep(std::uint8_t mask) {
    int out = 0;
    for (int i = 0; i < size_; ++i) {
      if (!(mask & (1u << i))) continue;
      if (out != i) {  // the leading kept vertices are already in place
        points_[out] = points_[i];
        vertices_[out] = vertices_[i];
      }
      ++out;
    }
    size_ = out;
  }

  /// True if w equals (bitwise) one of the simplex points.
  bool contains(const Vec3& w) const {
    for (int i = 0; i < size_; ++i)
      if (points_[i] == w) return true;
    return false;
  }

  /// Largest ‖w_i‖² over the simplex points: the scale that rounding errors refer to.
  double max_norm_squared() const {
    double m = 0;
    for (int i = 0; i < size_; ++i)
      m = std::max(m, points_[i].squaredNorm());
    return m;
  }

 private:
  std::array<SimplexVertex, kCapacity> vertices_{};
  // Zeroed explicitly: `{}` leaves Eigen vectors uninitialised, and a copy of the simplex reads
  // the unused slots too.
  std::array<Vec3, kCapacity> points_{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  int size_ = 0;
};

}  // namespace gjklab
