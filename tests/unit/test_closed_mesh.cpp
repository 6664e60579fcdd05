// Closed triangle meshes (exact/closed_mesh.hpp): good meshes of every format read back with
// their exact vertices and faces; each kind of bad mesh is refused with a message naming the
// file and the first offending face (tests/data/meshes_bad/, and meshes given as data).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/experiment/cases/real_objects.hpp"

using Catch::Contains;
using gjklab::MeshFace;
using gjklab::TriangleMesh;
using gjklab::Vec3;
using gjklab::exact::read_closed_mesh;
using gjklab::exact::validate_closed_mesh;
using gjklab::testing::ScratchDir;

namespace {

std::string data(const std::string& name) {
  return std::string(GJKLAB_TEST_DATA_DIR) + "/" + name;
}

/// The unit cube of tests/data/meshes_closed/box.off: 12 triangles, counter-clockwise seen
/// from outside.
TriangleMesh unit_box() {
  return {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
          {{0, 2, 1},
           {0, 3, 2},
           {4, 5, 6},
           {4, 6, 7},
           {0, 1, 5},
           {0, 5, 4},
           {3, 6, 2},
           {3, 7, 6},
           {0, 4, 7},
           {0, 7, 3},
           {1, 2, 6},
           {1, 6, 5}}};
}

/// a and b in one mesh, b's vertices scaled by `scale` and moved by `offset`.
TriangleMesh two_of(const TriangleMesh& a, const TriangleMesh& b, double scale,
                    const Vec3& offset) {
  TriangleMesh out = a;
  const auto base = static_cast<std::uint32_t>(a.vertices.size());
  for (const Vec3& p : b.vertices)
    out.vertices.push_back(scale * p + offset);
  for (const MeshFace& f : b.faces)
    out.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  return out;
}

std::string refusal(const TriangleMesh& mesh) {
  try {
    validate_closed_mesh(mesh, "line 7");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("closed mesh: a good mesh reads back with its exact vertices and faces",
          "[unit][closed_mesh]") {
  const TriangleMesh box = read_closed_mesh(data("meshes_closed/box.off"));
  CHECK(box == unit_box());
  // The test meshes of the other formats: an OFF tetrahedron, an OBJ octahedron.
  const TriangleMesh tetra = read_closed_mesh(data("meshes/tetrahedron.off"));
  CHECK(tetra.vertices.size() == 4);
  CHECK(tetra.faces == std::vector<MeshFace>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
  const TriangleMesh octahedron = read_closed_mesh(data("meshes/octahedron.obj"));
  CHECK(octahedron.vertices.size() == 6);
  CHECK(octahedron.faces.size() == 8);
  CHECK(octahedron.faces[0] == MeshFace{0, 2, 4});  // OBJ counts from 1, the mesh from 0
  CHECK_NOTHROW(validate_closed_mesh(unit_box(), "line 1"));
}

TEST_CASE("closed mesh: PLY and STL give the same box (STL's repeated vertices merged)",
          "[unit][closed_mesh]") {
  ScratchDir dir("closed-mesh");
  const TriangleMesh box = unit_box();
  std::ofstream ply(dir.file("box.ply"));
  ply << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
         "property float z\nelement face 12\nproperty list uchar uint vertex_indices\nend_header\n";
  for (const Vec3& p : box.vertices)
    ply << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const MeshFace& f : box.faces)
    ply << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  ply.close();
  CHECK(read_closed_mesh(dir.file("box.ply")) == box);

  std::ofstream stl(dir.file("box.stl"));
  stl << "solid box\n";
  for (const MeshFace& f : box.faces) {
    stl << "facet normal 0 0 0\nouter loop\n";
    for (std::uint32_t v : f)
      stl << "vertex " << box.vertices[v].x() << " " << box.vertices[v].y() << " "
          << box.vertices[v].z() << "\n";
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid box\n";
  stl.close();
  const TriangleMesh from_stl = read_closed_mesh(dir.file("box.stl"));
  // Vertices in order of first appearance: 0, 2, 1, 3, ... of the box.
  REQUIRE(from_stl.vertices.size() == 8);
  REQUIRE(from_stl.faces.size() == 12);
  for (std::size_t f = 0; f < 12; ++f)
    for (std::size_t k = 0; k < 3; ++k)
      CHECK(from_stl.vertices[from_stl.faces[f][k]] == box.vertices[box.faces[f][k]]);
}

TEST_CASE("closed mesh: bad files are refused naming the file and the first offending face",
          "[unit][closed_mesh]") {
  const auto refused = [](const std::string& name, const std::string& expected) {
    INFO(name);
    CHECK_THROWS_WITH(read_closed_mesh(data(name)), Contains(data(name)) && Contains(expected));
  };
  refused("meshes_bad/open_box.off",
          ": face 2 (vertices 4, 5, 6): the edge between vertices 5 and 6 belongs to no other "
          "face: the mesh is not closed");
  refused("meshes_bad/box_one_flipped.off",
          ": face 2 (vertices 4, 5, 6): the edge between vertices 5 and 6 is traversed in the same "
          "direction by face 11: the faces are not consistently oriented");
  refused("meshes_bad/box_inverted.off",
          ": face 0 (vertices 0, 1, 2): the mesh encloses a negative signed volume");
  refused("meshes_bad/two_tetrahedra.off", "(a self-intersecting mesh");
  refused("meshes_bad/degenerate_face.off",
          ": face 1 (vertices 0, 1, 3): a degenerate face (its three vertices are collinear");
  refused("meshes_bad/repeated_index.off",
          ": face 1 (vertices 0, 0, 3): a degenerate face (a repeated vertex index)");
  refused("meshes_bad/nan_coordinate.ply",
          ": vertex 2 (nan, 2, 0), used by face 0: a non-finite coordinate");
  refused("meshes_bad/index_out_of_range.ply",
          ": face 3 (vertices 1, 2, 4): vertex index 4 out of range (the mesh has 4 vertices");
  refused("meshes_bad/quad_box.obj",
          ": face 0 (vertices 0, 3, 2, 1): has 4 vertices; only triangles are accepted");
  // The test meshes: the wedge has quadrilaterals, the STL cube's triangles all face inward.
  refused("meshes/wedge.ply", ": face 2 (vertices 0, 1, 4, 3): has 4 vertices");
  refused("meshes/cube.stl", "encloses a negative signed volume");
}

TEST_CASE("closed mesh: bad meshes given as data are refused naming the source and the face",
          "[unit][closed_mesh]") {
  TriangleMesh box = unit_box();
  box.vertices[5].y() = 2e15;
  CHECK(refusal(box) ==
        "line 7: vertex 5 (1, 2000000000000000, 1), used by face 2: a coordinate "
        "beyond the limit |x| <= 1000000000000000");
  box = unit_box();
  box.vertices[6].z() = std::numeric_limits<double>::infinity();
  CHECK_THAT(refusal(box), Contains("vertex 6 (1, 1, inf), used by face 2: a non-finite"));
  box = unit_box();
  box.faces[4][1] = 8;
  CHECK_THAT(refusal(box), Contains("line 7: face 4 (vertices 0, 8, 5): vertex index 8 out of "
                                    "range (the mesh has 8 vertices, from 0)"));
  box = unit_box();
  box.vertices.push_back({5, 5, 5});
  CHECK_THAT(refusal(box), Contains("line 7: vertex 8 (5, 5, 5) is used by no face"));
  CHECK_THAT(refusal(TriangleMesh{}), Contains("line 7: no face"));
}

TEST_CASE("closed mesh: size limits", "[unit][closed_mesh]") {
  // 10^6 + 1 copies of one triangle: every face is good, their number is not.
  TriangleMesh many{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}};
  many.faces.assign(gjklab::exact::kMaxMeshFaces + 1, MeshFace{0, 1, 2});
  CHECK_THAT(refusal(many), Contains("line 7: face 1000000: more than the limit of 1000000 faces"));
}

TEST_CASE("closed mesh: several components, side by side or nested or touching",
          "[unit][closed_mesh]") {
  const TriangleMesh box = unit_box();
  // Two boxes apart: two separate solids, accepted.
  CHECK(refusal(two_of(box, box, 1, {3, 0, 0})) == "accepted");
  // A box inside a larger one (both outward): refused; the inner one named by its first face.
  CHECK_THAT(refusal(two_of(box, box, 0.25, {0.25, 0.25, 0.25})),
             Contains("line 7: face 12 (vertices 8, 10, 9): its connected component (1 of 2, "
                      "counted from 0 by lowest face) lies inside another component"));
  // A cavity: the inner box inward.
  TriangleMesh inner = box;
  for (MeshFace& f : inner.faces)
    std::swap(f[1], f[2]);
  CHECK_THAT(refusal(two_of(box, inner, 0.25, {0.25, 0.25, 0.25})),
             Contains("line 7: face 12 (vertices 8, 9, 10): its connected component (1 of 2"));
  // Two boxes overlapping: self-intersecting.
  CHECK_THAT(refusal(two_of(box, box, 1, {0.5, 0.5, 0.5})), Contains("(a self-intersecting mesh"));
  // Two boxes sharing vertex 6 (one corner): a non-manifold vertex.
  TriangleMesh corner = two_of(box, box, 1, {1, 1, 1});
  for (MeshFace& f : corner.faces)
    for (std::uint32_t& v : f)
      if (v == 8) v = 6;
  corner.vertices.erase(corner.vertices.begin() + 8);
  for (std::size_t f = 12; f < corner.faces.size(); ++f)
    for (std::uint32_t& v : corner.faces[f])
      if (v > 8) --v;
  CHECK_THAT(refusal(corner), Contains("line 7: face 2 (vertices 4, 5, 6): vertex 6 has 12 faces "
                                       "that form more than one fan"));
  // Three triangles on one edge: a non-manifold edge.
  const TriangleMesh fin{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}},
                         {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}};
  CHECK_THAT(refusal(fin), Contains("line 7: face 0 (vertices 0, 1, 2): the edge between vertices "
                                    "0 and 1 is shared by 3 faces"));
}

TEST_CASE("closed mesh: CGAL's demo meshes, closed ones accepted, the others refused",
          "[unit][closed_mesh][real_object]") {
  const std::filesystem::path folder = gjklab::experiment::real_object_meshes();
  // Closed, outward, without self-intersection; the sphere in all three formats it ships in.
  // Each with its Euler characteristic V - E + F = V - F/2 (every edge in two triangles):
  // 2 for a sphere-like surface, 0 for the knot (a torus), below 0 for more handles.
  const std::vector<std::pair<const char*, long>> closed = {
      {"elephant.off", -4}, {"fandisk.off", 2}, {"femur.off", -2},
      {"knot1.off", 0},     {"cube.off", 2},    {"sphere.off", 2},
      {"sphere.ply", 2},    {"sphere.stl", 2},  {"colored_tetra.ply", 2}};
  for (const auto& [name, euler] : closed) {
    INFO(name);
    const TriangleMesh mesh = read_closed_mesh(folder / name);
    CHECK(long(mesh.vertices.size()) - long(mesh.faces.size() / 2) == euler);
  }
  const auto refused = [&folder](const char* name, const std::string& expected) {
    INFO(name);
    CHECK_THROWS_WITH(read_closed_mesh(folder / name), Contains(expected));
  };
  refused("cube_quad.off", "face 0 (vertices 0, 3, 7, 4): has 4 vertices");
  refused("open_cube.off",
          "face 0 (vertices 0, 1, 2): the edge between vertices 0 and 1 "
          "belongs to no other face");
  refused("cube-shuffled.off",
          "face 0 (vertices 3, 1, 0): the edge between vertices 1 and 3 "
          "is traversed in the same direction by face 1");
  refused("degtri_sliding.off", "face 2 (vertices 3, 2, 4): a degenerate face");
  refused("cow.off",
          "face 264 (vertices 618, 57, 620): intersects face 4713 (vertices 2353, "
          "2294, 2354)");
  refused("tetrahedron.off", "face 0 (vertices 0, 1, 2): the mesh encloses a negative signed");
  refused("b9.ply", "no face");
}
