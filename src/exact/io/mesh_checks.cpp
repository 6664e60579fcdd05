#include "exact/io/mesh_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "gjklab/exact/closed_mesh.hpp"

namespace gjklab::exact::detail {

namespace {

/// A double as its shortest round-trip text ("nan", "inf" for the non-finite).
std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

std::string point_text(const Vec3& p) {
  std::string text = "(";
  text.append(number(p.x())).append(", ").append(number(p.y())).append(", ");
  return text.append(number(p.z())).append(")");
}

/// The lowest index of a face that uses vertex v, or faces.size().
template <class Faces>
std::size_t first_face_using(const Faces& faces, std::size_t v) {
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (std::find(faces[f].begin(), faces[f].end(), v) != faces[f].end()) return f;
  return faces.size();
}

template <class Faces>
void check_coordinates_of(const std::vector<Vec3>& vertices, const Faces& faces,
                          std::string_view source) {
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const Vec3& p = vertices[v];
    const bool finite = p.allFinite();
    if (finite && p.cwiseAbs().maxCoeff() <= kMaxMeshCoordinate) continue;
    std::string problem = "vertex " + std::to_string(v) + " " + point_text(p);
    const std::size_t f = first_face_using(faces, v);
    problem += f < faces.size() ? ", used by face " + std::to_string(f) : ", used by no face";
    problem += finite ? ": a coordinate beyond the limit |x| <= " + number(kMaxMeshCoordinate)
                      : ": a non-finite coordinate";
    refuse(source, problem);
  }
}

/// One use of an edge by a face: the edge's vertices in increasing order, the face, and
/// whether the face traverses it from lo to hi.
struct EdgeUse {
  std::uint32_t lo, hi, face;
  std::uint8_t corner;  ///< the edge runs from the face's corner to the next one
  bool forward;
  auto key() const { return std::tie(lo, hi, face, corner); }
};

std::vector<EdgeUse> edge_uses(const TriangleMesh& mesh) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * mesh.faces.size());
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
    for (std::uint8_t k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), f, k, a < b});
    }
  std::sort(uses.begin(), uses.end(),
            [](const EdgeUse& x, const EdgeUse& y) { return x.key() < y.key(); });
  return uses;
}

/// Calls visit(first, count) for each run of uses of one edge (sorted by face within it).
template <class Visit>
void for_each_edge(const std::vector<EdgeUse>& uses, Visit visit) {
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi)
      ++j;
    visit(i, j - i);
    i = j;
  }
}

std::string edge_text(const EdgeUse& e) {
  return "the edge between vertices " + std::to_string(e.lo) + " and " + std::to_string(e.hi);
}

/// Check 5: each edge in exactly two faces; the message names the lowest offending face.
void check_closed(const TriangleMesh& mesh, const std::vector<EdgeUse>& uses,
                  std::string_view source) {
  std::size_t worst = uses.size(), worst_count = 0;
  for_each_edge(uses, [&](std::size_t first, std::size_t count) {
    if (count != 2 && (worst == uses.size() || uses[first].face < uses[worst].face)) {
      worst = first;
      worst_count = count;
    }
  });
  if (worst == uses.size()) return;
  const EdgeUse& e = uses[worst];
  const std::string where = face_label(mesh, e.face) + ": " + edge_text(e);
  if (worst_count == 1)
    refuse(source, where + " belongs to no other face: the mesh is not closed (a boundary edge)");
  refuse(source, where + " is shared by " + std::to_string(worst_count) +
                     " faces: the mesh is not closed (a non-manifold edge; a closed mesh has "
                     "exactly two faces at each edge)");
}

/// Check 6a: the two faces of each edge traverse it in opposite directions. Returns the face
/// across each face's edge k (index 3f + k).
std::vector<std::uint32_t> check_orientation(const TriangleMesh& mesh,
                                             const std::vector<EdgeUse>& uses,
                                             std::string_view source) {
  std::vector<std::uint32_t> across(uses.size());
  std::size_t worst = uses.size();
  for_each_edge(uses, [&](std::size_t i, std::size_t) {
    const EdgeUse &a = uses[i], &b = uses[i + 1];
    across[3 * std::size_t{a.face} + a.corner] = b.face;
    across[3 * std::size_t{b.face} + b.corner] = a.face;
    if (a.forward == b.forward && (worst == uses.size() || a.face < uses[worst].face)) worst = i;
  });
  if (worst == uses.size()) return across;
  const EdgeUse &a = uses[worst], &b = uses[worst + 1];
  refuse(source, face_label(mesh, a.face) + ": " + edge_text(a) +
                     " is traversed in the same direction by face " + std::to_string(b.face) +
                     ": the faces are not consistently oriented (one of them is flipped)");
}

std::uint8_t corner_of(const MeshFace& face, std::uint32_t v) {
  return face[0] == v ? 0 : face[1] == v ? 1 : 2;
}

/// Check 6b: the faces at each vertex form one fan (rotating around the vertex from one of its
/// faces, across the edges that leave it, reaches them all); and every vertex is used.
void check_vertex_fans(const TriangleMesh& mesh, const std::vector<std::uint32_t>& across,
                       std::string_view source) {
  std::vector<std::uint32_t> corners(mesh.vertices.size(), 0);
  for (const MeshFace& face : mesh.faces)
    for (std::uint32_t v : face)
      ++corners[v];
  std::vector<bool> done(mesh.vertices.size(), false);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
    for (std::uint8_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.faces[f][k];
      if (done[v]) continue;
      done[v] = true;
      std::uint32_t fan = 0, face = f;
      std::uint8_t corner = k;
      do {  // edge `corner` of `face` leaves v; the face across it is the next one around v
        ++fan;
        face = across[3 * std::size_t{face} + corner];
        corner = corner_of(mesh.faces[face], v);
      } while (face != f && fan <= corners[v]);
      if (fan != corners[v])
        refuse(source, face_label(mesh, f) + ": vertex " + std::to_string(v) + " has " +
                           std::to_string(corners[v]) +
                           " faces that form more than one fan: the surface touches itself "
                           "there (a non-manifold vertex)");
    }
  for (std::size_t v = 0; v < corners.size(); ++v)
    if (corners[v] == 0)
      refuse(source, "vertex " + std::to_string(v) + " " + point_text(mesh.vertices[v]) +
                         " is used by no face (a closed mesh has no loose vertex)");
}

MeshComponents components_of(const TriangleMesh& mesh, const std::vector<std::uint32_t>& across) {
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  MeshComponents c;
  c.of_face.assign(mesh.faces.size(), kNone);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (c.of_face[f] != kNone) continue;
    const auto id = static_cast<std::uint32_t>(c.first_face.size());
    c.first_face.push_back(f);
    c.of_face[f] = id;
    stack.assign(1, f);
    while (!stack.empty()) {
      const std::uint32_t g = stack.back();
      stack.pop_back();
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint32_t h = across[3 * std::size_t{g} + k];
        if (c.of_face[h] == kNone) {
          c.of_face[h] = id;
          stack.push_back(h);
        }
      }
    }
  }
  return c;
}

}  // namespace

void refuse(std::string_view source, const std::string& problem) {
  throw std::runtime_error(std::string(source) + ": " + problem);
}

std::string face_label(const TriangleMesh& mesh, std::size_t face) {
  const MeshFace& f = mesh.faces[face];
  return "face " + std::to_string(face) + " (vertices " + std::to_string(f[0]) + ", " +
         std::to_string(f[1]) + ", " + std::to_string(f[2]) + ")";
}

void check_coordinates(const MeshSoup& soup, std::string_view source) {
  check_coordinates_of(soup.vertices, soup.faces, source);
}

void check_coordinates(const TriangleMesh& mesh, std::string_view source) {
  check_coordinates_of(mesh.vertices, mesh.faces, source);
}

TriangleMesh triangles_of(MeshSoup soup, std::string_view source) {
  // Indices are 32-bit: a file of more vertices (far beyond the limit) is refused here.
  if (soup.vertices.size() > std::numeric_limits<std::uint32_t>::max())
    refuse(source, "more than the limit of " + std::to_string(kMaxMeshVertices) +
                       " vertices (the mesh has " + std::to_string(soup.vertices.size()) + ")");
  TriangleMesh mesh;
  mesh.faces.reserve(soup.faces.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const std::vector<std::size_t>& face = soup.faces[f];
    std::string label = "face " + std::to_string(f) + " (vertices";
    for (std::size_t i = 0; i < face.size() && i < 8; ++i)
      label += (i ? ", " : " ") + std::to_string(face[i]);
    label += face.size() > 8 ? ", ...)" : ")";
    if (face.size() != 3)
      refuse(source, label + ": has " + std::to_string(face.size()) +
                         " vertices; only triangles are accepted (nothing is triangulated)");
    for (std::size_t v : face)
      if (v >= soup.vertices.size())
        refuse(source, label + ": vertex index " + std::to_string(v) +
                           " out of range (the mesh has " + std::to_string(soup.vertices.size()) +
                           " vertices, from 0)");
    mesh.faces.push_back({static_cast<std::uint32_t>(face[0]), static_cast<std::uint32_t>(face[1]),
                          static_cast<std::uint32_t>(face[2])});
  }
  mesh.vertices = std::move(soup.vertices);
  return mesh;
}

void check_indices(const TriangleMesh& mesh, std::string_view source) {
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (std::uint32_t v : mesh.faces[f])
      if (v >= mesh.vertices.size())
        refuse(source, face_label(mesh, f) + ": vertex index " + std::to_string(v) +
                           " out of range (the mesh has " + std::to_string(mesh.vertices.size()) +
                           " vertices, from 0)");
}

void check_sizes(const TriangleMesh& mesh, std::string_view source) {
  if (mesh.faces.empty()) refuse(source, "no face (a closed mesh has at least four)");
  if (mesh.faces.size() > kMaxMeshFaces)
    refuse(source, "face " + std::to_string(kMaxMeshFaces) + ": more than the limit of " +
                       std::to_string(kMaxMeshFaces) + " faces (the mesh has " +
                       std::to_string(mesh.faces.size()) + ")");
  if (mesh.vertices.size() > kMaxMeshVertices)
    refuse(source, "vertex " + std::to_string(kMaxMeshVertices) + ": more than the limit of " +
                       std::to_string(kMaxMeshVertices) + " vertices (the mesh has " +
                       std::to_string(mesh.vertices.size()) + ")");
}

MeshComponents check_topology(const TriangleMesh& mesh, std::string_view source) {
  const std::vector<EdgeUse> uses = edge_uses(mesh);
  check_closed(mesh, uses, source);
  const std::vector<std::uint32_t> across = check_orientation(mesh, uses, source);
  check_vertex_fans(mesh, across, source);
  return components_of(mesh, across);
}

}  // namespace gjklab::exact::detail
