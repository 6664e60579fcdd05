// The vertex graph of a cloud's convex hull, decided with exact predicates, for hill-climbing
// support (Polytope::enable_hill_climbing). Plain types only: CGAL stays in src/exact/.
#pragma once

#include <span>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::exact {

/// For each point i of the cloud, the indices of its neighbours on the boundary of the
/// convex hull: the edges of the exact hull's triangulated surface (full-dimensional clouds),
/// of its polygon (flat clouds), or the segment (collinear clouds). Points that are not on that
/// graph (interior points, and every repeated copy of a point but its first) get no neighbours.
/// A triangulated surface may keep boundary points that are not extreme (inside a flat facet or
/// an edge); they stay on the graph, which is harmless for hill climbing. Every linear function
/// that is maximised at no neighbour of a graph vertex more than at the vertex itself is
/// maximised over the whole hull at that vertex.
/// Throws std::invalid_argument for an empty cloud or a non-finite coordinate.
std::vector<std::vector<int>> hull_vertex_adjacency(std::span<const Vec3> cloud);

}  // namespace gjklab::exact
