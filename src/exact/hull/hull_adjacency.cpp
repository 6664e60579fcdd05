// The hull's vertex graph for hill climbing. The dimension and, for flat and collinear clouds,
// the extreme points come from hull_summary (exact predicates); a full-dimensional cloud's graph
// is the edge set of CGAL::convex_hull_3's triangulated surface, built on the input doubles
// with the Epick kernel (exact predicates, no constructions needed).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <numeric>
#include <string>

#include "exact/hull/hull.hpp"
#include "gjklab/exact/hull_adjacency.hpp"
#include "gjklab/geometry/polytope.hpp"

namespace gjklab::exact {

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

bool lex_less(const Vec3& a, const Vec3& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

/// Maps a point back to the first index of the cloud holding exactly that point.
class FirstIndex {
 public:
  explicit FirstIndex(std::span<const Vec3> cloud) : cloud_(cloud), order_(cloud.size()) {
    std::iota(order_.begin(), order_.end(), 0);
    std::stable_sort(order_.begin(), order_.end(),
                     [&](int i, int j) { return lex_less(cloud_[i], cloud_[j]); });
  }
  int operator()(const Vec3& p) const {
    const auto it = std::lower_bound(order_.begin(), order_.end(), p,
                                     [&](int i, const Vec3& q) { return lex_less(cloud_[i], q); });
    return *it;  // p is a point of the cloud, so it is found; stable order: its first copy
  }

 private:
  std::span<const Vec3> cloud_;
  std::vector<int> order_;
};

void link(std::vector<std::vector<int>>& adjacency, int i, int j) {
  if (i == j) return;
  if (std::find(adjacency[i].begin(), adjacency[i].end(), j) == adjacency[i].end())
    adjacency[i].push_back(j);
  if (std::find(adjacency[j].begin(), adjacency[j].end(), i) == adjacency[j].end())
    adjacency[j].push_back(i);
}

}  // namespace

std::vector<std::vector<int>> hull_vertex_adjacency(std::span<const Vec3> cloud) {
  if (std::string problem = describe_invalid_cloud(cloud); !problem.empty())
    throw InvalidGeometry(problem);
  std::vector<std::vector<int>> adjacency(cloud.size());
  const FirstIndex first_index(cloud);
  const detail::HullSummary summary = detail::hull_summary(cloud);
  const std::vector<Vec3>& ext = summary.extreme_points;
  if (summary.dimension == 1) {
    link(adjacency, first_index(ext[0]), first_index(ext[1]));
  } else if (summary.dimension == 2) {
    // hull_summary returns a flat cloud's extreme points in order around the polygon.
    for (std::size_t k = 0; k < ext.size(); ++k)
      link(adjacency, first_index(ext[k]), first_index(ext[(k + 1) % ext.size()]));
  } else if (summary.dimension == 3) {
    std::vector<Epick::Point_3> points;
    points.reserve(cloud.size());
    for (const Vec3& p : cloud)
      points.emplace_back(p.x(), p.y(), p.z());
    using Mesh = CGAL::Surface_mesh<Epick::Point_3>;
    Mesh mesh;
    CGAL::convex_hull_3(points.begin(), points.end(), mesh);
    std::vector<int> index_of(mesh.number_of_vertices());
    for (Mesh::Vertex_index v : mesh.vertices()) {
      const Epick::Point_3& p = mesh.point(v);
      index_of[v] = first_index(Vec3(p.x(), p.y(), p.z()));
    }
    for (Mesh::Edge_index e : mesh.edges())
      link(adjacency, index_of[mesh.vertex(e, 0)], index_of[mesh.vertex(e, 1)]);
  }
  for (auto& row : adjacency)
    std::sort(row.begin(), row.end());
  return adjacency;
}

}  // namespace gjklab::exact
