#include "gjklab/exact/mesh_io.hpp"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string>

#include "gjklab/geometry/polytope.hpp"

namespace gjklab::exact {

namespace {
using Point = CGAL::Simple_cartesian<double>::Point_3;

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}
}  // namespace

bool is_mesh_file(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  return ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl";
}

std::vector<Vec3> read_mesh_vertices(const std::filesystem::path& file) {
  const std::string name = file.string();
  if (!is_mesh_file(file))
    throw std::runtime_error(name + ": not a mesh file (use .off, .obj, .ply or .stl)");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error(name + ": no such file");
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  if (!CGAL::IO::read_polygon_soup(name, points, faces))
    throw std::runtime_error(name + ": cannot read the mesh (malformed file?)");
  std::vector<Vec3> cloud;
  cloud.reserve(points.size());
  for (const Point& p : points)
    cloud.emplace_back(p.x(), p.y(), p.z());
  if (const std::string problem = describe_invalid_cloud(cloud); !problem.empty())
    throw std::runtime_error(name + ": " + problem);
  return cloud;
}

}  // namespace gjklab::exact
