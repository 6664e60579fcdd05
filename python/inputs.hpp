// Python values into the C++ API's (private to python/): point clouds from numpy arrays, checked
// as `gjklab query --cases` checks a cases line, and an algorithm with its options from keyword
// arguments, checked as an experiment file's are.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/registry/answer_fields.hpp"
#include "gjklab/geometry/polytope.hpp"

namespace gjklab::python {

namespace py = pybind11;

/// An n×3 float64 NumPy array (any strides, so slices and transposes work) from the array or
/// from anything numpy.asarray turns into float64 numbers (nested lists), and its rows. Other
/// dtypes are refused rather than converted: a float32 or integer array is usually a mistake
/// upstream, and GJK's answers depend on every bit of the input. The array is kept alive with
/// the rows. An empty cloud is refused here with the message of `gjklab query --cases`; the
/// other checks of a cases line (finite coordinates) are made where the polytope is built.
struct CloudArray {
  py::array array;
  CoordinateRows rows;
};

/// The array `object` as a cloud named `name` in messages ("a" or "b"): float64, n×3, not empty.
CloudArray cloud_array(const py::handle& object, const char* name);

/// An exact rational as a fractions.Fraction (for the answers of the exact functions).
py::object fraction(const exact::Rational& r);

/// The array's points, copied (any strides).
std::vector<Vec3> points_of(const CloudArray& cloud);

/// The polytope of a checked array, in `polytope` (built, or its storage reused), with the
/// messages of `gjklab query --cases`.
void build(const CloudArray& cloud, const char* name, std::optional<Polytope>& polytope);

/// The registered algorithm `name`, or a ValueError listing the names.
const experiment::AlgorithmInfo& algorithm_named(const std::string& name);

/// The algorithm and its options from keyword arguments, checked as an experiment file's.
experiment::AlgorithmSpec spec_from(const std::string& algorithm, const py::kwargs& options);

/// A point or direction as a float64 array of 3, or None.
py::object vector_or_none(const std::optional<Vec3>& v);
/// An answer's fields (`gjklab query`'s JSON line) as a dict, in their order; points and
/// directions as float64 arrays of 3.
py::dict fields_dict(const experiment::AnswerFields& fields);
/// gjklab.read_closed_mesh, gjklab.exact_mesh, gjklab.decompose and gjklab.query_mesh
/// (meshes.cpp).
void def_meshes(py::module_& m);

}  // namespace gjklab::python
