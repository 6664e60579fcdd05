#include <stdexcept>
#include <string>
#include <utility>

#include "gjklab/exact/hull_features.hpp"

namespace gjklab::exact {

TriangleMesh hull_mesh(std::span<const Vec3> cloud) {
  HullFeatures hull = hull_features(cloud);
  if (hull.dimension != 3)
    throw std::invalid_argument("the point cloud spans " + std::to_string(hull.dimension) +
                                " dimensions; a solid needs 3");
  TriangleMesh mesh;
  mesh.vertices = std::move(hull.vertices);
  // A face is a convex loop of extreme points, no three of them collinear, so its fan has no
  // degenerate triangle.
  for (const std::vector<int>& loop : hull.faces)
    for (std::size_t k = 1; k + 1 < loop.size(); ++k)
      mesh.faces.push_back({static_cast<std::uint32_t>(loop[0]),
                            static_cast<std::uint32_t>(loop[k]),
                            static_cast<std::uint32_t>(loop[k + 1])});
  return mesh;
}

}  // namespace gjklab::exact
