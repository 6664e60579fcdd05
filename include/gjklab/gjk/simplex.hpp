// The GJK simplex: up to four points of the Minkowski difference A − B, each remembered with
// the support points of A and B that produced it (for witness points and traces).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <type_traits>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// A simplex point with scalar type T (double unless a query runs in another precision).
template <class T>
struct SimplexVertexT {
  Vec3T<T> w = Vec3T<T>::Zero();  ///< w = a − b, a point of the Minkowski difference
  Vec3T<T> a = Vec3T<T>::Zero();  ///< support point of A
  Vec3T<T> b = Vec3T<T>::Zero();  ///< support point of B
  /// Indices of a and b in their polytopes' vertex lists (−1 for shapes without indices).
  std::int32_t index_a = -1;
  std::int32_t index_b = -1;
};

using SimplexVertex = SimplexVertexT<double>;

template <class T>
class SimplexT {
 public:
  using Vertex = SimplexVertexT<T>;
  using Point = Vec3T<T>;

  static constexpr int kCapacity = 4;

  int size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == kCapacity; }
  const Vertex& operator[](int i) const { return vertices_[i]; }
  /// The points in order (oldest first): e.g. the start of a warm-started query.
  std::span<const Vertex> vertices() const {
    return {vertices_.data(), static_cast<std::size_t>(size_)};
  }

  /// The points w_i in order, stored contiguously (w_i = (*this)[i].w): the input of the
  /// sub-algorithms, read on every iteration without gathering them from the 80-byte vertices.
  const std::array<Point, kCapacity>& points() const { return points_; }

  void push(const Vertex& v) {
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
  bool contains(const Point& w) const {
    for (int i = 0; i < size_; ++i)
      if (points_[i] == w) return true;
    return false;
  }

  /// Largest ‖w_i‖² over the simplex points: the scale that rounding errors refer to.
  T max_norm_squared() const {
    T m = 0;
    for (int i = 0; i < size_; ++i)
      m = std::max(m, points_[i].squaredNorm());
    return m;
  }

 private:
  std::array<Vertex, kCapacity> vertices_{};
  // Zeroed explicitly: `{}` leaves Eigen vectors uninitialised, and a copy of the simplex reads
  // the unused slots too.
  std::array<Point, kCapacity> points_{Point::Zero(), Point::Zero(), Point::Zero(), Point::Zero()};
  int size_ = 0;
};

using Simplex = SimplexT<double>;

/// The simplex in double (exact from float; long double points are rounded to nearest): what
/// traces and results hold whatever the query's precision.
template <class T>
SimplexVertex to_double(const SimplexVertexT<T>& v) {
  SimplexVertex out;
  out.w = v.w.template cast<double>();
  out.a = v.a.template cast<double>();
  out.b = v.b.template cast<double>();
  out.index_a = v.index_a;
  out.index_b = v.index_b;
  return out;
}
template <class T>
Simplex to_double(const SimplexT<T>& s) {
  if constexpr (std::is_same_v<T, double>) {
    return s;
  } else {
    Simplex out;
    for (const auto& v : s.vertices())
      out.push(to_double(v));
    return out;
  }
}

}  // namespace gjklab
