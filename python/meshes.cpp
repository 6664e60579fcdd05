// Closed triangle meshes in Python: reading one, and the exact truth for the solids two of them
// bound (gjklab.read_closed_mesh, gjklab.exact_mesh).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/meshes/mesh_query.hpp"
#include "inputs.hpp"

namespace gjklab::python {

namespace {

/// Faces from an m×3 integer array (any integer dtype; values checked against uint32).
std::vector<MeshFace> faces_of(const py::handle& object, const std::string& name) {
  const auto array = py::array_t<std::int64_t, py::array::forcecast>::ensure(object);
  if (!array || array.ndim() != 2 || array.shape(1) != 3) {
    PyErr_Clear();
    throw py::value_error(name + ": faces must be an m×3 array of vertex indices");
  }
  const auto r = array.unchecked<2>();
  std::vector<MeshFace> faces(static_cast<std::size_t>(r.shape(0)));
  for (py::ssize_t f = 0; f < r.shape(0); ++f)
    for (int k = 0; k < 3; ++k) {
      if (r(f, k) < 0 || r(f, k) > 0xffffffffLL)
        throw py::value_error(name + ": face " + std::to_string(f) + " has index " +
                              std::to_string(r(f, k)));
      faces[static_cast<std::size_t>(f)][k] = static_cast<std::uint32_t>(r(f, k));
    }
  return faces;
}

/// A mesh from a path (read and validated as gjklab reads mesh files) or from a pair
/// (vertices n×3 float64, faces m×3 integers), validated the same way.
TriangleMesh mesh_of(const py::handle& object, const char* side) {
  const std::string name = std::string("mesh ") + side;
  try {
    if (py::isinstance<py::str>(object) || py::hasattr(object, "__fspath__")) {
      const auto path = py::module_::import("os").attr("fspath")(object).cast<std::string>();
      return exact::read_closed_mesh(path);
    }
    if (!py::isinstance<py::tuple>(object) && !py::isinstance<py::list>(object))
      throw py::value_error(name + ": expected a mesh file path or (vertices, faces)");
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(object);
    if (pair.size() != 2)
      throw py::value_error(name + ": expected a mesh file path or (vertices, faces)");
    TriangleMesh mesh;
    mesh.vertices = points_of(cloud_array(pair[0], side));
    mesh.faces = faces_of(pair[1], name);
    exact::validate_closed_mesh(mesh, name);
    return mesh;
  } catch (const std::runtime_error& e) {
    throw py::value_error(e.what());
  }
}

/// A mesh as (vertices n×3 float64, faces m×3 uint32).
py::tuple mesh_arrays(const TriangleMesh& mesh) {
  py::array_t<double> vertices({static_cast<py::ssize_t>(mesh.vertices.size()), py::ssize_t{3}});
  py::array_t<std::uint32_t> faces({static_cast<py::ssize_t>(mesh.faces.size()), py::ssize_t{3}});
  auto v = vertices.mutable_unchecked<2>();
  auto f = faces.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < v.shape(0); ++i)
    for (int k = 0; k < 3; ++k)
      v(i, k) = mesh.vertices[static_cast<std::size_t>(i)][k];
  for (py::ssize_t i = 0; i < f.shape(0); ++i)
    for (int k = 0; k < 3; ++k)
      f(i, k) = mesh.faces[static_cast<std::size_t>(i)][k];
  return py::make_tuple(vertices, faces);
}

/// Points of a plane from a k×2 float64 array (or nested lists); ValueError otherwise.
std::vector<PlanePoint> plane_points(const py::handle& object, const char* name) {
  const auto array = py::array_t<double, py::array::forcecast>::ensure(object);
  if (!array || array.ndim() != 2 || array.shape(1) != 2)
    throw py::value_error(std::string(name) + ": expected a k×2 array of numbers");
  const auto r = array.unchecked<2>();
  std::vector<PlanePoint> out(static_cast<std::size_t>(r.shape(0)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    out[static_cast<std::size_t>(i)] = {r(i, 0), r(i, 1)};
  return out;
}

/// A decomposition's options from Python values (numbers, booleans), by their text.
experiment::DecompositionOptions decomposition_options_of(const experiment::DecompositionInfo& d,
                                                          const py::dict& values) {
  experiment::DecompositionOptions out;
  for (const auto& [key, value] : values) {
    const std::string text = py::isinstance<py::bool_>(value)
                                 ? (value.cast<bool>() ? "true" : "false")
                                 : py::str(value).cast<std::string>();
    experiment::set_decomposition_option(d, out, py::str(key).cast<std::string>(), text);
  }
  return out;
}

experiment::DecompositionOptions decomposition_options(const experiment::DecompositionInfo& d,
                                                       const py::kwargs& values) {
  return decomposition_options_of(d, py::dict(values));
}

py::dict truth_dict(const exact::MeshTruth& t) {
  py::dict d;
  d["intersect"] = t.intersect;
  d["contact"] = std::string(to_string(t.contact));
  d["distance"] = t.distance;
  d["distance_squared"] = fraction(t.distance_squared);
  d["face_a"] = t.face_a;
  d["face_b"] = t.face_b;
  d["exact_intersection_tests"] = t.exact_intersection_tests;
  d["exact_distance_evaluations"] = t.exact_distance_evaluations;
  return d;
}

/// gjklab.read_closed_mesh and gjklab.exact_mesh: closed meshes and their exact truth.
void def_mesh_truth(py::module_& m) {
  m.def(
      "read_closed_mesh", [](const py::handle& path) { return mesh_arrays(mesh_of(path, "a")); },
      py::arg("path"),
      R"(A closed triangle mesh file (.off, .obj, .ply or .stl) as (vertices, faces): an n×3
float64 array and an m×3 uint32 array, counter-clockwise seen from outside. Raises ValueError
naming the file and the first offending face when the mesh is not closed, not consistently
oriented, self-intersecting, inverted or degenerate.)");
  m.def(
      "exact_mesh",
      [](const py::handle& a, const py::handle& b) {
        const TriangleMesh ma = mesh_of(a, "a"), mb = mesh_of(b, "b");
        return truth_dict(exact::mesh_truth(ma, mb));
      },
      py::arg("a"), py::arg("b"),
      R"(The exact answer for the solids two closed meshes bound; each mesh is a file path or
(vertices, faces). Returns a dict: intersect, contact ('separated', 'triangles_meet',
'a_inside_b', 'b_inside_a'), distance_squared (fractions.Fraction, exact), distance (correctly
rounded), face_a and face_b (the triangles that meet or attain the distance; -1 for a
containment), and the exact evaluations the answer took.)");
}

/// gjklab.decompose and gjklab.query_mesh: convex pieces and the algorithms over them.
void def_mesh_pieces(py::module_& m) {
  m.def(
      "decompose",
      [](const py::handle& mesh, const std::string& method, const py::kwargs& options) {
        const TriangleMesh closed = mesh_of(mesh, "a");
        experiment::Decomposition d;
        try {
          const auto& chosen = experiment::decomposition_named(method);
          d = chosen.decompose(closed, "mesh", decomposition_options(chosen, options));
        } catch (const std::exception& e) {
          throw py::value_error(e.what());
        }
        py::list pieces;
        for (const std::vector<Vec3>& piece : d.pieces) {
          py::array_t<double> corners({static_cast<py::ssize_t>(piece.size()), py::ssize_t{3}});
          auto c = corners.mutable_unchecked<2>();
          for (py::ssize_t i = 0; i < c.shape(0); ++i)
            for (int k = 0; k < 3; ++k)
              c(i, k) = piece[static_cast<std::size_t>(i)][k];
          pieces.append(corners);
        }
        py::dict out;
        out["method"] = d.method;
        out["pieces"] = pieces;
        out["proven"] = d.proven;
        out["max_rounding"] = d.max_rounding;
        return out;
      },
      py::arg("mesh"), py::arg("method") = "exact",
      R"(The convex pieces of a closed mesh (a file path or (vertices, faces)) by a named
decomposition: 'hull' (one piece, the convex hull), 'exact' (CGAL's decomposition, its union
proven equal to the solid; at most 2 000 faces) or 'approximate' (Bullet's HACD with its default
parameters, when built). Returns a dict: method, pieces (a list of k×3 float64 arrays, each
piece the convex hull of its rows), proven (the union is proven to be the solid) and
max_rounding (how far rounding the exact pieces' corners to doubles moved them, length units).
Keyword arguments are the decomposition's options (approximate: HACD's parameters, e.g.
concavity=50, min_clusters=4). Raises ValueError when the mesh is bad or the decomposition fails, saying why.)");
  m.def(
      "query_mesh",
      [](const py::handle& a, const py::handle& b, const py::handle& algorithm,
         const std::string& decomposition, const py::dict& decomposition_options,
         const py::kwargs& options) -> py::object {
        const bool one = py::isinstance<py::str>(algorithm);
        const auto names = one ? std::vector<std::string>{algorithm.cast<std::string>()}
                               : algorithm.cast<std::vector<std::string>>();
        experiment::MeshSide sa{mesh_of(a, "a"), std::nullopt, {}};
        experiment::MeshSide sb{mesh_of(b, "b"), std::nullopt, {}};
        py::list answers;
        for (const std::string& name : names) {
          if (const experiment::MeshPeerInfo* peer = experiment::find_mesh_peer(name)) {
            answers.append(
                fields_dict(experiment::mesh_peer_fields(*peer, peer->run(sa.mesh, sb.mesh))));
            continue;
          }
          const experiment::AlgorithmSpec spec = spec_from(name, options);
          const experiment::AlgorithmInfo& info = algorithm_named(spec.name);
          try {
            const auto& chosen = experiment::decomposition_named(decomposition);
            if (info.kind != experiment::AnswerKind::exact) {
              const auto set = decomposition_options_of(chosen, decomposition_options);
              experiment::decompose_side(sa, chosen, "mesh a", set);
              experiment::decompose_side(sb, chosen, "mesh b", set);
            }
            answers.append(fields_dict(experiment::mesh_answer_fields(info, sa, sb, spec.options)));
          } catch (const std::exception& e) {
            throw py::value_error(e.what());
          }
        }
        return one ? answers[0] : py::object(answers);
      },
      py::arg("a"), py::arg("b"), py::arg("algorithm") = "gjk-johnson",
      py::arg("decomposition") = "hull", py::arg("decomposition_options") = py::dict(),
      R"(An algorithm's answer for two closed meshes (file paths or (vertices, faces)), as
`gjklab query` prints it: 'exact' answers the solids (mesh truth); any other algorithm runs over
the pairs of pieces of the named decomposition and its answer says which, with pieces_a,
pieces_b, piece_pairs and piece_pairs_tested; a mesh peer ('fcl-bvh', with FCL) answers for
the meshes themselves. With a list of algorithm names, a list of
answers (the meshes decomposed once). decomposition_options: a dict of the decomposition's
options (as gjklab.decompose takes them). Keyword arguments are the algorithms' options.)");
}

/// gjklab.prism_mesh and gjklab.lathe_mesh: generated closed meshes.
void def_mesh_builders(py::module_& m) {
  m.def(
      "prism_mesh",
      [](const py::handle& polygon, double z0, double z1) {
        return mesh_arrays(prism_mesh(plane_points(polygon, "polygon"), z0, z1));
      },
      py::arg("polygon"), py::arg("z0"), py::arg("z1"),
      R"(The prism over a polygon (k×2 corners, counter-clockwise seen from +z, star-shaped from
its first corner) between heights z0 < z1, as (vertices, faces).)");
  m.def(
      "lathe_mesh",
      [](const py::handle& profile, int segments, bool ring) {
        return mesh_arrays(lathe_mesh(plane_points(profile, "profile"), segments, ring));
      },
      py::arg("profile"), py::arg("segments"), py::arg("ring"),
      R"(The solid of revolution of a profile (k×2 points (r, z), counter-clockwise around the
region, r >= 0) about the z axis in `segments` steps, as (vertices, faces). ring=True: every
r > 0, the profile closed (a torus, a tube); ring=False: the first and last points on the axis
(a ball, a peg, a cup).)");
}

}  // namespace

void def_meshes(py::module_& m) {
  def_mesh_truth(m);
  def_mesh_pieces(m);
  def_mesh_builders(m);
}

}  // namespace gjklab::python
