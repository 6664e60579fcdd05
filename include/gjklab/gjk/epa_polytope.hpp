// The polytope of the expanding polytope algorithm (epa.hpp): a closed triangulated surface
// of points of A − B, faces with their outward planes and adjacency, and the expansion step
// (the faces a new point sees, their horizon, the cone of new faces). Not a template: the
// shapes enter only through the support points the driver adds. Its buffers are reserved once
// per query (prepare), so the expansion never allocates; one polytope per thread serves every
// query on that thread.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "gjklab/geometry/types.hpp"
#include "gjklab/gjk/simplex.hpp"

namespace gjklab {

/// In the scalar type T of the query (EpaPolytope: double); defined for float, double and
/// long double (epa_polytope.cpp).
template <class T>
class EpaPolytopeT {
 public:
  using Point = Vec3T<T>;
  struct Face {
    std::array<int, 3> v{};                 ///< vertex indices, counter-clockwise seen from outside
    std::array<int, 3> adj{};               ///< adj[i]: the face across edge (v[i], v[i+1 mod 3])
    std::array<std::int8_t, 3> adj_edge{};  ///< which edge of adj[i] is that edge
    Point normal = Point::Zero();           ///< outward unit normal
    T distance = 0;                         ///< normal·v[0]: signed distance of the plane
    int visible_stamp = -1;                 ///< step in which the face was found visible
    bool alive = false;
  };
  struct HorizonEdge {
    int from = 0, to = 0;  ///< vertex indices, in the orientation of the removed face
    int outside_face = 0;  ///< the kept face across the edge
    std::int8_t outside_edge = 0;
    int next = -1, prev = -1;  ///< neighbouring horizon edges along the loop
    int new_face = -1;
    Point normal = Point::Zero();
    T distance = 0;
  };

  /// Empties the polytope and reserves room for a query of at most `max_steps` expansions and
  /// `max_faces` faces.
  void prepare(int max_steps, int max_faces);

  /// Starts from a tetrahedron of four points (any order: the faces are oriented outward from
  /// its centroid). False if a face has no plane (a flat tetrahedron).
  bool start_tetrahedron(const std::array<SimplexVertexT<T>, 4>& p);

  /// The live face whose plane is nearest the origin (the first of equals).
  int closest_face() const;

  /// True if w is (bitwise) a vertex already.
  bool has_vertex(const Point& w) const;

  /// Marks the faces that w sees, by flood fill from `seed` (which w must see): a face sees w
  /// when n·w − d ≥ −plane_slack. Collects the horizon, the edges between seen and unseen
  /// faces, and returns the number of faces seen. `step` stamps this step's faces.
  int mark_visible(int seed, const Point& w, T plane_slack, int step);

  /// True if the last horizon is one simple loop (the seen region a disc), with each edge
  /// linked to its neighbours; otherwise rounding made visibility inconsistent.
  bool link_horizon();

  /// Replaces the faces seen in `step` by the cone from w over the horizon. False, changing
  /// nothing, if a new face has no plane or its plane is nearer the origin than
  /// lower_bound − slack (the polytope would stop being convex around the origin).
  bool add_cone(const SimplexVertexT<T>& w, int step, T lower_bound, T slack);

  /// Whether the cone over the last horizon fits: a vertex slot and the face budget.
  bool cone_fits(int visible, int max_faces) const;

  int alive() const { return alive_; }
  const std::vector<HorizonEdge>& horizon() const { return horizon_; }

  std::vector<SimplexVertexT<T>> vertices;
  std::vector<Face> faces;

 private:
  /// Normal and plane distance of the triangle (i, j, l); false if it has no normal.
  bool plane(int i, int j, int l, Point& normal, T& distance) const;
  int allocate_face();

  std::vector<int> free_faces_;
  std::vector<int> stack_;
  std::vector<HorizonEdge> horizon_;
  std::vector<int> edge_from_;  ///< per vertex: the horizon edge starting there, or −1
  int alive_ = 0;
};

using EpaPolytope = EpaPolytopeT<double>;

}  // namespace gjklab
