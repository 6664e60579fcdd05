// Polytope's hill-climbing support (from the hull's adjacency): a walk over the vertex graph
// from the start a cube map of directions picks, instead of the full scan.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "gjklab/geometry/polytope.hpp"

namespace gjklab {

void Polytope::enable_hill_climbing(const std::vector<std::vector<int>>& adjacency) {
  const std::size_t n = vertices_.size();
  if (adjacency.size() != n)
    throw std::invalid_argument("hill climbing: adjacency has " + std::to_string(adjacency.size()) +
                                " rows for " + std::to_string(n) + " vertices");
  auto graph = std::make_shared<HullGraph>();
  graph->offsets.reserve(n + 1);
  graph->offsets.push_back(0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int j : adjacency[i]) {
      if (j < 0 || static_cast<std::size_t>(j) >= n || static_cast<std::size_t>(j) == i)
        throw std::invalid_argument("hill climbing: neighbour " + std::to_string(j) +
                                    " of vertex " + std::to_string(i) + " is out of range");
      graph->neighbours.push_back(static_cast<std::uint32_t>(j));
    }
    graph->offsets.push_back(static_cast<std::uint32_t>(graph->neighbours.size()));
  }
  graph_ = std::move(graph);
  build_start_table();
}

namespace {

/// Cell of direction d in a cube map with r × r cells per face, or -1 for d = 0.
[[gnu::always_inline]] inline int cube_map_cell(const Vec3& d, int r) {
  const double ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
  int axis = 0;
  double m = ax;
  if (ay > m) {
    axis = 1;
    m = ay;
  }
  if (az > m) {
    axis = 2;
    m = az;
  }
  if (!(m > 0)) return -1;
  const double inv = 0.5 * r / m;
  // u, v in [0, r]: the other two coordinates, projected on the face.
  const double u = (d[(axis + 1) % 3] + m) * inv, v = (d[(axis + 2) % 3] + m) * inv;
  const int iu = std::min(static_cast<int>(u), r - 1), iv = std::min(static_cast<int>(v), r - 1);
  const int face = 2 * axis + (d[axis] < 0);
  return (face * r + iu) * r + iv;
}

}  // namespace

void Polytope::build_start_table() {
  const HullGraph& g = *graph_;
  const std::size_t n = vertices_.size();
  // A walk must start on the graph, so points without neighbours are not candidates, unless no
  // point has any (a cloud of copies of one point, where every index is a maximiser).
  std::vector<std::uint32_t> on_graph;
  for (std::size_t i = 0; i < n; ++i)
    if (g.offsets[i + 1] > g.offsets[i]) on_graph.push_back(static_cast<std::uint32_t>(i));
  if (on_graph.empty()) on_graph.push_back(0);
  // About n/6 cells per face (as many cells as graph vertices), at most 32 × 32 (24 KiB): walks
  // from a cell's vertex then take a step or two even for directions unrelated to the hint
  // (n/24 per face measured 1.1–1.4× slower on random clouds of 128–8192 points).
  const int r =
      std::clamp(static_cast<int>(std::sqrt(static_cast<double>(on_graph.size()) / 6)), 1, 32);
  table_resolution_ = r;
  start_table_.assign(static_cast<std::size_t>(6 * r * r), on_graph[0]);
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    for (int iu = 0; iu < r; ++iu) {
      for (int iv = 0; iv < r; ++iv) {
        Vec3 d = Vec3::Zero();
        d[axis] = face % 2 ? -1.0 : 1.0;
        d[(axis + 1) % 3] = (2.0 * iu + 1) / r - 1;
        d[(axis + 2) % 3] = (2.0 * iv + 1) / r - 1;
        std::uint32_t best = on_graph[0];
        double best_dot = vertices_[best].dot(d);
        for (std::uint32_t i : on_graph) {
          if (const double dot = vertices_[i].dot(d); dot > best_dot) {
            best_dot = dot;
            best = i;
          }
        }
        start_table_[static_cast<std::size_t>(cube_map_cell(d, r))] = best;
      }
    }
  }
  hint_.store(start_table_[0]);
}

void Polytope::disable_hill_climbing() {
  graph_.reset();
}

std::size_t Polytope::climb_support_index(const Vec3& d) const {
  const HullGraph& g = *graph_;
  std::uint32_t current = hint_.load();
  double best = vertices_[current].dot(d);
  if (std::isnan(best)) return scan_support_index(d);
  if (const int cell = cube_map_cell(d, table_resolution_); cell >= 0) {
    const std::uint32_t s = start_table_[static_cast<std::size_t>(cell)];
    if (const double value = vertices_[s].dot(d); value > best) {
      best = value;
      current = s;
    }
  }
  // Steepest ascent: move to the best strictly better neighbour until there is none. The value
  // increases strictly at every step, so the walk ends; on a convex polytope a vertex with no
  // better neighbour maximises d·x over the whole polytope.
  for (;;) {
    std::uint32_t next = current;
    const std::uint32_t* it = g.neighbours.data() + g.offsets[current];
    const std::uint32_t* end = g.neighbours.data() + g.offsets[current + 1];
    for (; it != end; ++it) {
      const double value = vertices_[*it].dot(d);
      if (value > best) {
        best = value;
        next = *it;
      }
    }
    if (next == current) break;
    current = next;
  }
  hint_.store(current);
  return current;
}

}  // namespace gjklab
