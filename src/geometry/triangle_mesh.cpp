#include "gjklab/geometry/triangle_mesh.hpp"

#include <cmath>
#include <stdexcept>

namespace gjklab {

TriangleMesh star_mesh(int rings, int segments, const std::function<double(const Vec3&)>& radius) {
  if (rings < 2 || segments < 3)
    throw std::invalid_argument("star_mesh: needs rings >= 2 and segments >= 3");
  TriangleMesh m;
  auto add = [&](const Vec3& direction) {
    const double r = radius(direction);
    if (!(r > 0) || !std::isfinite(r))
      throw std::invalid_argument("star_mesh: a radius must be positive and finite");
    m.vertices.push_back(r * direction);
  };
  add(Vec3::UnitZ());
  for (int i = 1; i < rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      add(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  add(-Vec3::UnitZ());
  const auto ring = [&](int i, int j) {
    return static_cast<std::uint32_t>(1 + (i - 1) * segments + (j % segments));
  };
  const auto south = static_cast<std::uint32_t>(m.vertices.size() - 1);
  for (int j = 0; j < segments; ++j) {
    m.faces.push_back({0, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i) {
      m.faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      m.faces.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
    m.faces.push_back({ring(rings - 1, j), south, ring(rings - 1, j + 1)});
  }
  return m;
}

}  // namespace gjklab
