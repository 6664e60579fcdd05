// gjklab._gjklab: the compiled half of the Python module.
//
// Every call goes to the public C++ API that the command line uses: the algorithm registry and
// its option schema (experiment/algorithms.hpp, algorithm_options.hpp), the case checks of
// `gjklab query --cases` (cloud_io.hpp), the experiment parser and driver of `gjklab run`
// (config.hpp, driver.hpp) and the family list (families.hpp). What lives here is only the
// translation between Python values and those calls, so an algorithm or option added to the
// registry appears in Python without a change to this file.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/cases/real_objects.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/registry/answer_fields.hpp"
#include "gjklab/experiment/run/driver.hpp"
#include "gjklab/experiment/run/summary.hpp"
#include "inputs.hpp"

namespace py = pybind11;

namespace gjklab::python {

namespace {

using experiment::AlgorithmInfo;
using experiment::AlgorithmSpec;
using experiment::Outcome;

// ---- answers out ---------------------------------------------------------------------------

/// One algorithm's answer, with the JSON names of `gjklab query`.
struct QueryResult {
  std::string algorithm;
  double radius_a = 0, radius_b = 0;
  Outcome outcome;
};

/// The exact oracle's answer, with the JSON names of `gjklab query --algorithms exact`.
struct ExactResult {
  exact::OracleAnswer answer;
};

/// The fields of `gjklab query`'s JSON line of one answer (experiment::answer_fields), as a
/// dict (fields_dict).
py::dict query_dict(const QueryResult& r) {
  return fields_dict(experiment::answer_fields(
      r.algorithm, r.outcome, ScalarPrecision::double_float, r.radius_a, r.radius_b));
}

// ---- the calls -----------------------------------------------------------------------------

/// A shape built once for many queries. Building a shape from an array (checking, copying,
/// and the Polytope's bounding box and SIMD blocks, in one pass of about 0.6 ns per point)
/// costs up to about as much as one GJK query on it; a study that queries the same shapes in
/// many poses or with many algorithms builds them once.
struct Shape {
  std::shared_ptr<const Polytope> polytope;
};

/// Polytopes of queries on arrays live in storage kept per thread, two slots (a query's two
/// sides): a query on fresh arrays then allocates nothing, and writes to memory that is mapped
/// and usually cached (fresh storage for a large cloud may come straight from the kernel, one
/// page fault per 4 KiB written). A slot is busy while a query uses it; a query that finds none
/// free (one started by Python code that converting another query's input ran) builds in its
/// own storage. Clouds above kPooledPoints are not kept (48 bytes per point: at most 12 MiB
/// per slot).
struct PoolSlot {
  std::optional<Polytope> polytope;
  bool busy = false;
};
constexpr std::size_t kPooledPoints = std::size_t{1} << 18;
thread_local PoolSlot pool[2];

/// A pool slot marked busy for the lease's lifetime (released also when a build throws).
struct SlotLease {
  PoolSlot* slot = nullptr;
  SlotLease() = default;
  SlotLease(const SlotLease&) = delete;
  SlotLease& operator=(const SlotLease&) = delete;
  ~SlotLease() {
    if (slot) slot->busy = false;
  }
};

/// One side of a query: a Shape's polytope, or one built from an array in a pool slot or in
/// its own storage. Not copied or moved: it owns its slot until it is destroyed.
class QueryInput {
 public:
  QueryInput(const py::handle& object, const char* name) {
    if (py::isinstance<Shape>(object)) {
      shape_ = object.cast<const Shape&>().polytope;
      return;
    }
    const CloudArray cloud = cloud_array(object, name);
    if (cloud.rows.count <= kPooledPoints) {
      for (PoolSlot& slot : pool) {
        if (!slot.busy) {
          slot.busy = true;
          lease_.slot = &slot;
          break;
        }
      }
    }
    build(cloud, name, lease_.slot ? lease_.slot->polytope : own_);
  }
  QueryInput(const QueryInput&) = delete;
  QueryInput& operator=(const QueryInput&) = delete;

  const Polytope& polytope() const {
    if (shape_) return *shape_;
    return lease_.slot ? *lease_.slot->polytope : *own_;
  }

 private:
  std::shared_ptr<const Polytope> shape_;
  SlotLease lease_;
  std::optional<Polytope> own_;
};

Outcome run_one(const AlgorithmInfo& info, const QueryInput& a, const QueryInput& b,
                double radius_a, double radius_b, const experiment::AlgorithmOptions& options) {
  experiment::check_case_radius(radius_a, "radius_a");
  experiment::check_case_radius(radius_b, "radius_b");
  const py::gil_scoped_release release;
  return experiment::run_algorithm(info, a.polytope(), b.polytope(), SweptRadii{radius_a, radius_b},
                                   options);
}

QueryResult query(const py::handle& a, const py::handle& b, const std::string& algorithm,
                  double radius_a, double radius_b, const py::kwargs& options) {
  const AlgorithmInfo& info = algorithm_named(algorithm);
  const AlgorithmSpec spec = spec_from(algorithm, options);
  QueryResult r{algorithm, radius_a, radius_b, {}};
  const QueryInput input_a(a, "a"), input_b(b, "b");
  r.outcome = run_one(info, input_a, input_b, radius_a, radius_b, spec.options);
  return r;
}

ExactResult exact_answer(const py::handle& a, const py::handle& b, bool depth, double radius_a,
                         double radius_b) {
  const AlgorithmInfo& info = algorithm_named("exact");
  experiment::AlgorithmOptions options;
  options.oracle.depth = depth;  // as `gjklab query --depth`
  const QueryInput input_a(a, "a"), input_b(b, "b");
  Outcome o = run_one(info, input_a, input_b, radius_a, radius_b, options);
  return {*o.exact};
}

/// An option's default as Python would write it, from the schema's text: true/false as bool,
/// "128" as int, "1e-12" as float, "1 0 0" as a list, any other word (a criterion) as str.
py::object typed_default(const std::string& text) {
  if (text == "true" || text == "false") return py::bool_(text == "true");
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string word; in >> word;)
    words.push_back(word);
  py::list numbers;
  for (const std::string& word : words) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(word, &used);
    } catch (const std::exception&) {
      return py::str(text);
    }
    if (used != word.size()) return py::str(text);
    const bool integral = word.find_first_of(".eEn") == std::string::npos;
    numbers.append(integral ? py::object(py::int_(std::stoll(word)))
                            : py::object(py::float_(value)));
  }
  if (numbers.size() == 1) return numbers[0];
  return numbers;
}

/// algorithms(): name → {kind, group, description, peer, depth, swept, options: {key: default}}.
py::dict algorithms() {
  py::dict out;
  for (const AlgorithmInfo& info : experiment::algorithms()) {
    AlgorithmSpec spec;
    spec.name = spec.label = std::string(info.name);
    py::dict options;
    for (const auto& [key, text] : experiment::describe_options(spec))
      options[py::str(key)] = typed_default(text);
    py::dict entry;
    entry["kind"] = std::string(to_string(info.kind));
    entry["group"] = std::string(to_string(experiment::group_of(info)));
    entry["description"] = std::string(info.description);
    entry["peer"] = info.peer;
    entry["depth"] = info.depth;
    entry["swept"] = info.can.swept;
    entry["options"] = options;
    out[py::str(std::string(info.name))] = entry;
  }
  return out;
}

py::list families() {
  py::list out;
  for (const experiment::FamilyShapeInfo& shape : experiment::family_shapes()) {
    py::dict entry;
    entry["shape"] = std::string(shape.name);
    entry["description"] = std::string(shape.description);
    out.append(entry);
  }
  return out;
}

/// An experiment from a file name, or from TOML text (anything with a newline or '=' that
/// names no file); relative paths inside text are relative to the working directory.
experiment::ExperimentConfig load(const std::string& path_or_text) {
  std::error_code ec;
  const bool looks_like_text = path_or_text.find_first_of("\n=") != std::string::npos;
  if (!looks_like_text || std::filesystem::is_regular_file(path_or_text, ec))
    return experiment::load_experiment(path_or_text);
  return experiment::parse_experiment(path_or_text, "<experiment text>");
}

/// What gjklab.run returns: where the archive is, how much ran, and the summary `gjklab run`
/// prints.
struct RunResult {
  std::string output;
  std::uint64_t cases = 0;
  double seconds = 0;
  bool complete = false;
  std::string summary;
};

RunResult run(const std::string& experiment_path_or_text, std::optional<std::string> out,
              std::optional<int> threads, std::optional<std::uint64_t> cases, bool force,
              bool progress) {
  const experiment::ExperimentConfig config = load(experiment_path_or_text);
  std::atomic<bool> stop{false};
  experiment::RunOptions options;
  options.output = out;
  options.threads = threads;
  options.cases = cases;
  options.force = force;
  options.progress = progress ? &std::cerr : nullptr;
  options.stop = &stop;
  // The run goes on a thread of its own while this one, without the GIL, wakes up now and
  // then to let Python handle signals: Ctrl-C then stops the run the way `gjklab run` stops
  // on SIGINT (finished cases written, the archive left incomplete and resumable).
  auto future =
      std::async(std::launch::async, [&] { return experiment::run_experiment(config, options); });
  for (;;) {
    std::future_status status;
    {
      const py::gil_scoped_release release;
      status = future.wait_for(std::chrono::milliseconds(100));
    }
    if (status == std::future_status::ready) break;
    if (PyErr_CheckSignals() != 0) {
      stop = true;
      {
        const py::gil_scoped_release release;
        future.wait();
      }
      throw py::error_already_set();
    }
  }
  const experiment::RunReport report = future.get();
  std::ostringstream summary;
  experiment::print_summary(summary, report.summary);
  if (!report.families.empty()) {
    summary << "\nper family:\n";
    experiment::print_family_table(summary, report.families);
  }
  return {report.output.string(), report.cases, report.seconds, report.complete, summary.str()};
}

/// Points as an n×3 float64 array.
py::array_t<double> points_array(std::span<const Vec3> points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  auto w = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < w.shape(0); ++i)
    for (int k = 0; k < 3; ++k)
      w(i, k) = points[static_cast<std::size_t>(i)][k];
  return out;
}

/// Experiment-file errors read as the command line prints them, as ValueError.
void register_error_translator() {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const experiment::ConfigError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const experiment::RealObjectError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const experiment::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

/// gjklab.Shape.
void def_shape(py::module_& m) {
  py::class_<Shape>(m, "Shape",
                    "A shape built once from an n×3 float64 array (its convex hull), for many "
                    "queries: query() and exact() take it wherever they take an array")
      .def(py::init([](const py::handle& points) {
             const CloudArray cloud = cloud_array(points, "shape");
             std::optional<gjklab::Polytope> polytope;
             build(cloud, "shape", polytope);
             return Shape{std::make_shared<const gjklab::Polytope>(std::move(*polytope))};
           }),
           py::arg("points"))
      .def_property_readonly("vertices",
                             [](const Shape& s) { return points_array(s.polytope->vertices()); })
      .def("__len__", [](const Shape& s) { return s.polytope->vertices().size(); })
      .def("__repr__", [](const Shape& s) {
        return "gjklab.Shape(" + std::to_string(s.polytope->vertices().size()) + " points)";
      });
}

/// gjklab.Result.
void def_result(py::module_& m) {
  py::class_<QueryResult>(m, "Result", "One algorithm's answer (the JSON names of gjklab query)")
      .def_readonly("algorithm", &QueryResult::algorithm)
      .def_property_readonly("intersect", [](const QueryResult& r) { return r.outcome.intersect; })
      .def_property_readonly("distance", [](const QueryResult& r) { return r.outcome.distance; })
      .def_property_readonly("depth", [](const QueryResult& r) { return r.outcome.depth; })
      .def_property_readonly("normal",
                             [](const QueryResult& r) { return vector_or_none(r.outcome.normal); })
      .def_property_readonly(
          "witness_a", [](const QueryResult& r) { return vector_or_none(r.outcome.witness_a); })
      .def_property_readonly(
          "witness_b", [](const QueryResult& r) { return vector_or_none(r.outcome.witness_b); })
      .def_property_readonly("lower_bound",
                             [](const QueryResult& r) { return r.outcome.lower_bound; })
      .def_property_readonly("upper_bound",
                             [](const QueryResult& r) { return r.outcome.upper_bound; })
      .def_property_readonly("iterations",
                             [](const QueryResult& r) { return r.outcome.iterations; })
      .def_property_readonly("support_calls",
                             [](const QueryResult& r) { return r.outcome.support_calls; })
      .def_property_readonly("termination",
                             [](const QueryResult& r) {
                               return std::string(gjklab::to_string(r.outcome.termination));
                             })
      .def_property_readonly(
          "exact",
          [](const QueryResult& r) -> py::object {
            if (!r.outcome.exact) return py::none();
            return py::cast(ExactResult{*r.outcome.exact});
          },
          "the full exact answer (algorithm 'exact' only), else None")
      .def("to_dict", &query_dict, "the answer as the JSON object gjklab query prints")
      .def("__repr__", [](const QueryResult& r) {
        return "gjklab.Result(" + py::repr(query_dict(r)).cast<std::string>() + ")";
      });
}

/// gjklab.ExactAnswer.
void def_exact_answer(py::module_& m) {
  py::class_<ExactResult>(m, "ExactAnswer", "The exact oracle's answer for two clouds")
      .def_property_readonly("intersect", [](const ExactResult& e) { return e.answer.intersect; })
      .def_property_readonly(
          "distance_squared",
          [](const ExactResult& e) { return fraction(e.answer.distance_squared); })
      .def_property_readonly("distance", [](const ExactResult& e) { return e.answer.distance; })
      .def_property_readonly("depth_squared",
                             [](const ExactResult& e) -> py::object {
                               if (!e.answer.depth_squared) return py::none();
                               return fraction(*e.answer.depth_squared);
                             })
      .def_property_readonly("depth", [](const ExactResult& e) { return e.answer.depth; })
      .def_property_readonly("hull_vertices_a",
                             [](const ExactResult& e) { return e.answer.hull_vertices_a; })
      .def_property_readonly("hull_vertices_b",
                             [](const ExactResult& e) { return e.answer.hull_vertices_b; })
      .def_property_readonly(
          "method", [](const ExactResult& e) { return std::string(to_string(e.answer.method)); },
          "how distance_squared was obtained: 'certified' or 'qp'")
      .def_property_readonly("depth_method",
                             [](const ExactResult& e) -> py::object {
                               if (!e.answer.depth_squared) return py::none();
                               return py::str(std::string(to_string(e.answer.depth_method)));
                             })
      .def_property_readonly(
          "witness_a", [](const ExactResult& e) { return vector_or_none(e.answer.witness_a); })
      .def_property_readonly(
          "witness_b", [](const ExactResult& e) { return vector_or_none(e.answer.witness_b); })
      .def_property_readonly(
          "normal", [](const ExactResult& e) { return vector_or_none(e.answer.depth_normal); })
      .def_property_readonly("swept", [](const ExactResult& e) { return e.answer.swept; })
      .def("__repr__", [](const ExactResult& e) {
        const auto& a = e.answer;
        std::string text =
            "gjklab.ExactAnswer(intersect=" + std::string(a.intersect ? "True" : "False") +
            ", distance_squared=" + a.distance_squared.numerator() + "/" +
            a.distance_squared.denominator();
        if (a.depth_squared)
          text += ", depth_squared=" + a.depth_squared->numerator() + "/" +
                  a.depth_squared->denominator();
        return text + ", method='" + std::string(to_string(a.method)) + "')";
      });
}

/// gjklab.RunReport.
void def_run_report(py::module_& m) {
  py::class_<RunResult>(m, "RunReport", "What gjklab.run did")
      .def_readonly("output", &RunResult::output)
      .def_readonly("cases", &RunResult::cases)
      .def_readonly("seconds", &RunResult::seconds)
      .def_readonly("complete", &RunResult::complete)
      .def_readonly("summary", &RunResult::summary)
      .def("__repr__", [](const RunResult& r) {
        return "gjklab.RunReport(output='" + r.output + "', cases=" + std::to_string(r.cases) +
               ", complete=" + (r.complete ? "True" : "False") + ")";
      });
}

/// The module's functions.
void def_functions(py::module_& m) {
  m.def("query", &query, py::arg("a"), py::arg("b"), py::arg("algorithm") = "gjk-johnson",
        py::kw_only(), py::arg("radius_a") = 0.0, py::arg("radius_b") = 0.0,
        R"(Runs one algorithm on two point clouds (n×3 float64 arrays; their convex hulls are the
shapes, swept by balls of radius_a and radius_b when given). Other keyword arguments are the
algorithm's options, by the names experiment files use (see algorithms()). Raises ValueError
for an unknown algorithm or option, a bad value, or an invalid cloud.)");
  m.def("exact", &exact_answer, py::arg("a"), py::arg("b"), py::arg("depth") = false, py::kw_only(),
        py::arg("radius_a") = 0.0, py::arg("radius_b") = 0.0,
        R"(The exact oracle's answer for two point clouds: distance_squared (and depth_squared
with depth=True) as fractions.Fraction, intersect, distance, hull vertex counts, and how the
answer was obtained (method: 'certified' or 'qp').)");
  m.def(
      "read_points",
      [](const std::string& path) { return points_array(experiment::read_point_file(path)); },
      py::arg("path"),
      "The points of a .xyz, .off, .obj, .ply or .stl file (an n×3 float64 array), read as "
      "gjklab query reads them");
  m.def(
      "algorithms", &algorithms,
      "Every registered algorithm: name -> kind, group (gjk, own, peer, oracle), description, and "
      "its options with defaults");
  m.def("families", &families, "Every shape a [[family]] of an experiment can name");
  m.def("real_objects", &experiment::real_object_names,
        "Names of the real objects (Debian package libcgal-demo), for shape = \"real_object\"");
  m.def(
      "real_object_folder", [] { return experiment::real_object_meshes().string(); },
      "The folder of the real objects' mesh files (extracted from the package's archive on "
      "first use), to read them with their faces (read_closed_mesh)");
  m.def("run", &run, py::arg("experiment"), py::kw_only(), py::arg("out") = py::none(),
        py::arg("threads") = py::none(), py::arg("cases") = py::none(), py::arg("force") = false,
        py::arg("progress") = false,
        R"(Runs an experiment (a TOML file's path, or TOML text) like `gjklab run` and writes its
HDF5 archive (out: default the experiment's output). Returns a RunReport; read the archive with
read_archive(). Ctrl-C stops the run, leaving a resumable archive.)");
}

}  // namespace

}  // namespace gjklab::python

PYBIND11_MODULE(_gjklab, m) {
  using namespace gjklab::python;
  m.doc() = "gjklab: GJK collision and distance algorithms, their peers and an exact oracle";
  register_error_translator();
  def_shape(m);
  def_result(m);
  def_exact_answer(m);
  def_run_report(m);
  def_functions(m);
  def_meshes(m);
}
