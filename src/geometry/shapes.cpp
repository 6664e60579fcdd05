#include "gjklab/geometry/shapes.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace gjklab::shapes {

namespace {
constexpr double kRadius = 0.5;
constexpr double kHalfHeight = 0.5;

/// Appends a regular n-gon of radius kRadius in the plane z = height.
void append_ring(std::vector<Vec3>& out, int n, double height) {
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * std::numbers::pi * i / n;
    out.emplace_back(kRadius * std::cos(angle), kRadius * std::sin(angle), height);
  }
}
}  // namespace

Polytope box(const Vec3& extents) {
  if (!(extents.array() > 0).all() || !extents.allFinite())
    throw std::invalid_argument("box extents must be positive and finite");
  const Vec3 h = 0.5 * extents;
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i)
    v.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  return Polytope(std::move(v));
}

Polytope cone(int vertices) {
  if (vertices < 4) throw std::invalid_argument("cone needs at least 4 vertices");
  std::vector<Vec3> v{Vec3(0, 0, kHalfHeight)};
  append_ring(v, vertices - 1, -kHalfHeight);
  return Polytope(std::move(v));
}

Polytope cylinder(int vertices) {
  if (vertices < 6 || vertices % 2 != 0)
    throw std::invalid_argument("cylinder needs an even vertex count of at least 6");
  std::vector<Vec3> v;
  append_ring(v, vertices / 2, -kHalfHeight);
  append_ring(v, vertices / 2, kHalfHeight);
  return Polytope(std::move(v));
}

Polytope uv_sphere(int vertices) {
  if (vertices < 6) throw std::invalid_argument("uv sphere needs at least 6 vertices");
  // Largest even segment count s with 2 + (s/2 − 1)·s ≤ vertices.
  int segments = 4;
  while (2 + (segments / 2) * (segments + 2) <= vertices)
    segments += 2;
  const int rings = segments / 2 - 1;
  std::vector<Vec3> v{Vec3(0, 0, kRadius), Vec3(0, 0, -kRadius)};
  for (int r = 1; r <= rings; ++r) {
    const double polar = std::numbers::pi * r / (rings + 1);
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2 * std::numbers::pi * s / segments;
      v.emplace_back(kRadius * std::sin(polar) * std::cos(azimuth),
                     kRadius * std::sin(polar) * std::sin(azimuth), kRadius * std::cos(polar));
    }
  }
  return Polytope(std::move(v));
}

}  // namespace gjklab::shapes
