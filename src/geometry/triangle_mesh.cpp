#include "gjklab/geometry/triangle_mesh.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

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

namespace {

void check_finite(std::span<const PlanePoint> points, const char* what) {
  for (const PlanePoint& p : points)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]))
      throw std::invalid_argument(std::string(what) + ": a coordinate is not finite");
}

}  // namespace

TriangleMesh prism_mesh(std::span<const PlanePoint> polygon, double z0, double z1) {
  if (polygon.size() < 3) throw std::invalid_argument("prism_mesh: needs at least 3 corners");
  check_finite(polygon, "prism_mesh");
  if (!(z0 < z1)) throw std::invalid_argument("prism_mesh: needs z0 < z1");
  TriangleMesh m;
  const auto n = static_cast<std::uint32_t>(polygon.size());
  for (const double z : {z0, z1})
    for (const PlanePoint& p : polygon)
      m.vertices.emplace_back(p[0], p[1], z);
  for (std::uint32_t k = 1; k + 1 < n; ++k) {
    m.faces.push_back({0, k + 1, k});          // bottom, counter-clockwise seen from −z
    m.faces.push_back({n, n + k, n + k + 1});  // top
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.faces.push_back({i, j, n + j});
    m.faces.push_back({i, n + j, n + i});
  }
  return m;
}

TriangleMesh lathe_mesh(std::span<const PlanePoint> profile, int segments, bool ring) {
  if (segments < 3) throw std::invalid_argument("lathe_mesh: needs segments >= 3");
  check_finite(profile, "lathe_mesh");
  const std::size_t n = profile.size();
  if (n < 3) throw std::invalid_argument("lathe_mesh: needs at least 3 profile points");
  const std::size_t first = ring ? 0 : 1, last = ring ? n : n - 1;  // the points off the axis
  if (!ring && (profile[0][0] != 0 || profile[n - 1][0] != 0))
    throw std::invalid_argument(
        "lathe_mesh: a profile that is not a ring starts and ends on "
        "the axis (r = 0)");
  for (std::size_t i = first; i < last; ++i)
    if (!(profile[i][0] > 0))
      throw std::invalid_argument("lathe_mesh: profile point " + std::to_string(i) +
                                  " must have r > 0");
  TriangleMesh m;
  // Ring vertex (i, j): profile point i turned by 2πj/segments; poles after them.
  for (std::size_t i = first; i < last; ++i)
    for (int j = 0; j < segments; ++j) {
      const double angle = 2 * M_PI * j / segments;
      m.vertices.emplace_back(profile[i][0] * std::cos(angle), profile[i][0] * std::sin(angle),
                              profile[i][1]);
    }
  const auto at = [&](std::size_t i, int j) {
    return static_cast<std::uint32_t>((i - first) * segments + (j % segments));
  };
  // A quad between profile points p → q and angles j → j + 1, outward: (p_j, q_j+1, q_j) and
  // (p_j, p_j+1, q_j+1) (a counter-clockwise profile turned counter-clockwise about +z).
  for (std::size_t i = first; i + 1 < last || (ring && i + 1 == last); ++i) {
    const std::size_t k = ring ? (i + 1) % n : i + 1;
    for (int j = 0; j < segments; ++j) {
      m.faces.push_back({at(i, j), at(k, j + 1), at(k, j)});
      m.faces.push_back({at(i, j), at(i, j + 1), at(k, j + 1)});
    }
    if (ring && i + 1 == last) break;
  }
  if (!ring) {
    const auto south = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.emplace_back(0, 0, profile[0][1]);
    const auto north = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.emplace_back(0, 0, profile[n - 1][1]);
    for (int j = 0; j < segments; ++j) {
      m.faces.push_back({south, at(first, j + 1), at(first, j)});
      m.faces.push_back({at(last - 1, j), at(last - 1, j + 1), north});
    }
  }
  return m;
}

}  // namespace gjklab
