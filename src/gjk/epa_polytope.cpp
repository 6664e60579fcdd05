#include "gjklab/gjk/epa_polytope.hpp"

#include <cmath>
#include <cstddef>
#include <utility>

namespace gjklab {

template <class T>
void EpaPolytopeT<T>::prepare(int max_steps, int max_faces) {
  const std::size_t vertex_capacity = 4 + static_cast<std::size_t>(max_steps);
  const std::size_t face_capacity = static_cast<std::size_t>(max_faces);
  vertices.clear();
  vertices.reserve(vertex_capacity);
  faces.clear();
  faces.reserve(face_capacity);
  free_faces_.clear();
  free_faces_.reserve(face_capacity);
  stack_.clear();
  stack_.reserve(face_capacity);
  horizon_.clear();
  horizon_.reserve(3 * face_capacity);
  edge_from_.assign(vertex_capacity, -1);
  alive_ = 0;
}

template <class T>
bool EpaPolytopeT<T>::plane(int i, int j, int l, Vec3T<T>& normal, T& distance) const {
  const Vec3T<T>& pi = vertices[i].w;
  const Vec3T<T> n = (vertices[j].w - pi).cross(vertices[l].w - pi);
  const T len = n.norm();
  if (!(len > 0) || !std::isfinite(len)) return false;
  normal = n / len;
  distance = normal.dot(pi);
  return std::isfinite(distance);
}

template <class T>
int EpaPolytopeT<T>::allocate_face() {
  if (!free_faces_.empty()) {
    const int f = free_faces_.back();
    free_faces_.pop_back();
    return f;
  }
  faces.emplace_back();  // within the reserved capacity (cone_fits checks the budget)
  return static_cast<int>(faces.size()) - 1;
}

template <class T>
bool EpaPolytopeT<T>::start_tetrahedron(const std::array<SimplexVertexT<T>, 4>& p) {
  for (const SimplexVertexT<T>& v : p)
    vertices.push_back(v);
  const Vec3T<T> centroid = T(0.25) * (p[0].w + p[1].w + p[2].w + p[3].w);
  std::array<std::array<int, 3>, 4> tri = {{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}}};
  for (auto& t : tri) {
    const Vec3T<T>& p0 = vertices[t[0]].w;
    const Vec3T<T> n = (vertices[t[1]].w - p0).cross(vertices[t[2]].w - p0);
    if (n.dot(centroid - p0) > 0) std::swap(t[1], t[2]);  // make the normal point outward
  }
  for (const auto& t : tri) {
    const int f = allocate_face();
    Face& face = faces[f];
    face.v = t;
    face.alive = true;
    if (!plane(t[0], t[1], t[2], face.normal, face.distance)) return false;
    ++alive_;
  }
  // Adjacency: the face across edge (x, y) is the one holding the edge (y, x).
  for (int f = 0; f < 4; ++f)
    for (int e = 0; e < 3; ++e) {
      const int x = faces[f].v[e], y = faces[f].v[(e + 1) % 3];
      for (int g = 0; g < 4; ++g)
        for (int h = 0; h < 3; ++h)
          if (faces[g].v[h] == y && faces[g].v[(h + 1) % 3] == x) {
            faces[f].adj[e] = g;
            faces[f].adj_edge[e] = static_cast<std::int8_t>(h);
          }
    }
  return true;
}

template <class T>
int EpaPolytopeT<T>::closest_face() const {
  int closest = -1;
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    if (faces[f].alive && (closest < 0 || faces[f].distance < faces[closest].distance)) closest = f;
  return closest;
}

template <class T>
bool EpaPolytopeT<T>::has_vertex(const Vec3T<T>& w) const {
  for (const SimplexVertexT<T>& v : vertices)
    if (v.w == w) return true;
  return false;
}

template <class T>
int EpaPolytopeT<T>::mark_visible(int seed, const Vec3T<T>& w, T plane_slack, int step) {
  auto sees = [&](const Face& f) { return f.normal.dot(w) - f.distance >= -plane_slack; };
  stack_.clear();
  horizon_.clear();
  stack_.push_back(seed);
  faces[seed].visible_stamp = step;
  int visible = 0;
  while (!stack_.empty()) {
    const int f = stack_.back();
    stack_.pop_back();
    ++visible;
    for (int e = 0; e < 3; ++e) {
      const int g = faces[f].adj[e];
      if (faces[g].visible_stamp == step) continue;
      if (sees(faces[g])) {
        faces[g].visible_stamp = step;
        stack_.push_back(g);
      } else {
        HorizonEdge h;
        h.from = faces[f].v[e];
        h.to = faces[f].v[(e + 1) % 3];
        h.outside_face = g;
        h.outside_edge = faces[f].adj_edge[e];
        horizon_.push_back(h);
      }
    }
  }
  return visible;
}

template <class T>
bool EpaPolytopeT<T>::cone_fits(int visible, int max_faces) const {
  const int h_count = static_cast<int>(horizon_.size());
  return vertices.size() < edge_from_.size() && alive_ - visible + h_count <= max_faces;
}

template <class T>
bool EpaPolytopeT<T>::link_horizon() {
  const int h_count = static_cast<int>(horizon_.size());
  bool simple = h_count >= 3;
  for (int i = 0; i < h_count && simple; ++i) {
    int& slot = edge_from_[horizon_[i].from];
    if (slot >= 0) simple = false;
    slot = i;
  }
  if (simple) {
    for (int i = 0; i < h_count && simple; ++i) {
      const int next = edge_from_[horizon_[i].to];
      if (next < 0) {
        simple = false;
      } else {
        horizon_[i].next = next;
        horizon_[next].prev = i;
      }
    }
    int length = 0;
    for (int i = 0; simple && length <= h_count;) {
      i = horizon_[i].next;
      ++length;
      if (i == 0) break;
    }
    simple = simple && length == h_count;
  }
  for (const HorizonEdge& h : horizon_)
    edge_from_[h.from] = -1;
  return simple;
}

template <class T>
bool EpaPolytopeT<T>::add_cone(const SimplexVertexT<T>& w, int step, T lower_bound, T slack) {
  // New faces (from, to, w): check them all before changing the polytope.
  const int wi = static_cast<int>(vertices.size());
  vertices.push_back(w);
  bool consistent = true;
  for (HorizonEdge& h : horizon_)
    consistent = consistent && plane(h.from, h.to, wi, h.normal, h.distance) &&
                 h.distance >= lower_bound - slack;
  if (!consistent) {
    vertices.pop_back();
    return false;
  }
  // Remove the visible faces (exactly those stamped in this step) and add the cone.
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    if (faces[f].alive && faces[f].visible_stamp == step) {
      faces[f].alive = false;
      free_faces_.push_back(f);
      --alive_;
    }
  for (HorizonEdge& h : horizon_)
    h.new_face = allocate_face();
  for (const HorizonEdge& h : horizon_) {
    Face& f = faces[h.new_face];
    f.v = {h.from, h.to, wi};
    f.normal = h.normal;
    f.distance = h.distance;
    f.alive = true;
    f.visible_stamp = -1;
    f.adj = {h.outside_face, horizon_[h.next].new_face, horizon_[h.prev].new_face};
    f.adj_edge = {h.outside_edge, 2, 1};
    faces[h.outside_face].adj[h.outside_edge] = h.new_face;
    faces[h.outside_face].adj_edge[h.outside_edge] = 0;
  }
  alive_ += static_cast<int>(horizon_.size());
  return true;
}

template class EpaPolytopeT<float>;
template class EpaPolytopeT<double>;
template class EpaPolytopeT<long double>;

}  // namespace gjklab
