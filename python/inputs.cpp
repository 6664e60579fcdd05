#include "inputs.hpp"

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"

namespace gjklab::python {

using experiment::AlgorithmInfo;
using experiment::AlgorithmSpec;

namespace {

/// "(4,)", "(2, 5)": an array's shape for messages.
std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t k = 0; k < array.ndim(); ++k)
    text += (k ? ", " : "") + std::to_string(array.shape(k));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

}  // namespace

CloudArray cloud_array(const py::handle& object, const char* name) {
  py::array array;
  if (py::isinstance<py::array>(object)) {
    array = py::reinterpret_borrow<py::array>(object);
    if (!array.dtype().equal(py::dtype::of<double>()))
      throw py::value_error(
          std::string("cloud ") + name + ": expected float64 coordinates, got dtype " +
          py::str(array.dtype()).cast<std::string>() + " (convert with .astype(numpy.float64))");
  } else {
    array = py::array_t<double, py::array::forcecast>::ensure(object);
    if (!array) {
      PyErr_Clear();
      throw py::value_error(std::string("cloud ") + name +
                            ": expected an n×3 array of float64 coordinates, got " +
                            py::str(py::type::of(object)).cast<std::string>());
    }
  }
  // No points at all ([] reads as shape (0,)) is an empty cloud, as in a cases line.
  if (array.size() == 0) experiment::check_case_cloud({}, name);
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error(std::string("cloud ") + name + ": expected an n×3 array, got shape " +
                          shape_text(array));
  const CoordinateRows rows{array.data(), static_cast<std::size_t>(array.shape(0)),
                            array.strides(0), array.strides(1)};
  return {std::move(array), rows};
}

py::object fraction(const exact::Rational& r) {
  static const py::object Fraction = py::module_::import("fractions").attr("Fraction");
  // Decimal strings of any length: Python's int parses them exactly.
  return Fraction(py::int_(py::str(r.numerator())), py::int_(py::str(r.denominator())));
}

std::vector<Vec3> points_of(const CloudArray& cloud) {
  std::vector<Vec3> points(cloud.rows.count);
  const auto* bytes = static_cast<const char*>(cloud.rows.data);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      std::memcpy(&points[i][k],
                  bytes + static_cast<std::ptrdiff_t>(i) * cloud.rows.row_stride +
                      k * cloud.rows.column_stride,
                  sizeof(double));
  return points;
}

namespace {

/// The checks of `gjklab query --cases` on an array's points, for the message of a cloud the
/// polytope refused (a NaN or infinite coordinate): the points copied, then check_case_cloud.
[[noreturn]] void refuse(const CloudArray& cloud, const char* name,
                         const InvalidGeometry& refused) {
  experiment::check_case_cloud(points_of(cloud), name);
  throw std::invalid_argument(std::string("cloud ") + name + ": " + refused.what());
}

/// Clouds from this many points on are built with the GIL released: the build then takes
/// microseconds (about 0.6 ns per point), against about 0.1 µs to release and take it back.
constexpr std::size_t kReleaseGilPoints = 4096;

}  // namespace

/// The polytope of a checked array, in `polytope` (built, or its storage reused), with the
/// messages of `gjklab query --cases`.
void build(const CloudArray& cloud, const char* name, std::optional<Polytope>& polytope) {
  std::optional<py::gil_scoped_release> release;
  if (cloud.rows.count >= kReleaseGilPoints) release.emplace();
  try {
    if (polytope)
      polytope->assign(cloud.rows);
    else
      polytope.emplace(cloud.rows);
  } catch (const InvalidGeometry& e) {
    refuse(cloud, name, e);
  }
}

namespace {

/// The text an experiment file would give for an option's value: a number, [x, y, z], a
/// boolean or a string (config.cpp's option_text), so that set_option checks it the same way.
std::string option_text(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  const bool is_array = py::isinstance<py::array>(value);
  const bool vector = is_array ? py::reinterpret_borrow<py::array>(value).ndim() > 0
                               : py::isinstance<py::sequence>(value);
  if (!vector && py::hasattr(value, "__float__"))  // int, float, NumPy scalars
    return experiment::round_trip(value.cast<double>());
  if (vector) {
    std::string text;
    for (const py::handle item : value) {
      if (py::isinstance<py::str>(item) || !py::hasattr(item, "__float__"))
        throw py::value_error("option '" + key + "': expected numbers in the list");
      text += (text.empty() ? "" : " ") + experiment::round_trip(item.cast<double>());
    }
    return text;
  }
  throw py::value_error("option '" + key + "': expected a number, a boolean, a string or " +
                        "[x, y, z], got " + py::str(py::type::of(value)).cast<std::string>());
}

}  // namespace

const AlgorithmInfo& algorithm_named(const std::string& name) {
  const AlgorithmInfo* info = experiment::find_algorithm(name);
  if (!info)
    throw py::value_error("unknown algorithm '" + name +
                          "'; valid names: " + experiment::algorithm_names());
  return *info;
}

namespace {

/// "a, b, c" of an algorithm's option keys, for messages.
std::string option_key_list(const std::string& algorithm) {
  std::string text;
  for (std::string_view key : experiment::option_keys(algorithm))
    text += (text.empty() ? "" : ", ") + std::string(key);
  return text.empty() ? "none" : text;
}

}  // namespace

/// The algorithm's options: its defaults with each keyword set through the registry's schema.
AlgorithmSpec spec_from(const std::string& algorithm, const py::kwargs& options) {
  AlgorithmSpec spec;
  spec.name = spec.label = algorithm;
  for (const auto& [key_object, value] : options) {
    const std::string key = key_object.cast<std::string>();
    const std::string text = option_text(key, value);
    try {
      experiment::set_option(spec, key, text);
    } catch (const std::invalid_argument& e) {
      std::string message = algorithm + ": option '" + key + "': " + e.what();
      if (std::string(e.what()).find("does not apply") != std::string::npos)
        message = std::string(e.what()) + "; valid: " + option_key_list(algorithm);
      throw py::value_error(message);
    }
  }
  return spec;
}

py::object vector_or_none(const std::optional<Vec3>& v) {
  if (!v) return py::none();
  py::array_t<double> out(3);
  auto w = out.mutable_unchecked<1>();
  for (int k = 0; k < 3; ++k)
    w(k) = (*v)[k];
  return out;
}

py::dict fields_dict(const experiment::AnswerFields& fields) {
  py::dict d;
  for (const auto& [key, value] : fields)
    std::visit(
        [&](const auto& x) {
          if constexpr (std::is_same_v<std::decay_t<decltype(x)>, Vec3>)
            d[py::str(key)] = vector_or_none(std::optional<Vec3>(x));
          else
            d[py::str(key)] = x;
        },
        value);
  return d;
}

}  // namespace gjklab::python
