#include "gjklab/query_answers.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <variant>

#include "gjklab/exact/hull_features.hpp"
#include "gjklab/experiment/registry/answer_fields.hpp"

namespace gjklab::cli {

namespace {

using experiment::AlgorithmInfo;
using experiment::PointCase;
using Json = nlohmann::ordered_json;

/// A field's value as JSON: a point or direction as [x, y, z].
Json json_of(const experiment::AnswerValue& v) {
  return std::visit(
      [](const auto& x) -> Json {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, Vec3>)
          return Json::array({x.x(), x.y(), x.z()});
        else
          return Json(x);
      },
      v);
}

/// The JSON line of one answer for one case: its id, then the fields.
std::string fields_line(const std::string& id, const experiment::AnswerFields& fields) {
  Json j;
  j["id"] = id;
  for (const auto& [key, value] : fields)
    j[key] = json_of(value);
  return experiment::json_line(j);
}

/// The JSON line of one algorithm's answer for one case: its id, then answer_fields.
std::string answer_line(const PointCase& c, const AlgorithmInfo& algorithm,
                        const experiment::Outcome& o, ScalarPrecision precision) {
  return fields_line(
      c.id, experiment::answer_fields(algorithm.name, o, precision, c.radius_a, c.radius_b));
}

/// The JSON line of a problem with a case, naming the algorithm when one is given.
std::string problem_line(const std::string& id, const std::string& problem,
                         std::string_view algorithm = {}) {
  Json j;
  j["id"] = id;
  if (!algorithm.empty()) j["algorithm"] = algorithm;
  j["error"] = problem;
  return experiment::json_line(j);
}

/// A side of a non-convex case: its mesh, or the boundary of a point cloud's hull.
experiment::MeshSide mesh_side(const std::optional<TriangleMesh>& mesh,
                               const std::vector<Vec3>& cloud) {
  return {mesh ? *mesh : exact::hull_mesh(cloud), std::nullopt, {}};
}

/// Every selected algorithm on a case with a mesh side: `exact` answers the solids, the others
/// the pieces of the decomposition (one error line each when a side cannot be decomposed).
std::vector<std::string> answer_mesh_case(const PointCase& c, const QueryAsked& asked) {
  const auto& selected = asked.algorithms;
  const experiment::DecompositionInfo& decomposition = *asked.decomposition;
  std::vector<std::string> lines;
  std::optional<experiment::MeshSide> a, b;
  try {
    a = mesh_side(c.mesh_a, c.a);
    b = mesh_side(c.mesh_b, c.b);
  } catch (const std::exception& e) {
    return {problem_line(c.id, std::string(a ? "side b: " : "side a: ") + e.what())};
  }
  const bool convex = std::any_of(selected.begin(), selected.end(), [](const AlgorithmInfo* x) {
    return x->kind != experiment::AnswerKind::exact;
  });
  std::string not_decomposed;
  try {
    if (convex) {
      experiment::decompose_side(*a, decomposition, "case '" + c.id + "' side a",
                                 asked.decomposition_options);
      experiment::decompose_side(*b, decomposition, "case '" + c.id + "' side b",
                                 asked.decomposition_options);
    }
  } catch (const std::exception& e) {
    not_decomposed = e.what();
  }
  for (const AlgorithmInfo* algorithm : selected) {
    try {
      if (algorithm->kind != experiment::AnswerKind::exact && !not_decomposed.empty())
        throw std::runtime_error(not_decomposed);
      lines.push_back(
          fields_line(c.id, experiment::mesh_answer_fields(*algorithm, *a, *b, asked.options)));
    } catch (const std::exception& e) {
      lines.push_back(problem_line(c.id, e.what(), algorithm->name));
    }
  }
  for (const experiment::MeshPeerInfo* peer : asked.mesh_peers) {
    try {
      lines.push_back(
          fields_line(c.id, experiment::mesh_peer_fields(*peer, peer->run(a->mesh, b->mesh))));
    } catch (const std::exception& e) {
      lines.push_back(problem_line(c.id, e.what(), peer->name));
    }
  }
  return lines;
}

/// Every selected algorithm on one valid case: one output line each. Unless the algorithms
/// were named, those that answer for polytopes only skip sphere-swept cases.
std::vector<std::string> answer_case(const PointCase& c, const QueryAsked& asked) {
  const auto& selected = asked.algorithms;
  const auto& options = asked.options;
  const bool named = asked.named;
  std::vector<std::string> lines;
  const Polytope a(c.a), b(c.b);
  const SweptRadii radii{c.radius_a, c.radius_b};
  const bool other_precision = options.precision != ScalarPrecision::double_float;
  for (const AlgorithmInfo* algorithm : selected) {
    if (!named && !experiment::handles(*algorithm, radii)) continue;
    if (!named && other_precision && !experiment::takes_precision(*algorithm)) continue;
    try {
      lines.push_back(
          answer_line(c, *algorithm, experiment::run_algorithm(*algorithm, a, b, radii, options),
                      experiment::takes_precision(*algorithm) ? options.precision
                                                              : ScalarPrecision::double_float));
    } catch (const std::exception& e) {
      lines.push_back(problem_line(c.id, e.what(), algorithm->name));
    }
  }
  return lines;
}

}  // namespace

std::vector<std::string> answer_lines(const PointCase& c, const QueryAsked& asked) {
  if (c.mesh_a || c.mesh_b) return answer_mesh_case(c, asked);
  std::vector<std::string> lines = answer_case(c, asked);
  if (asked.named)
    for (const experiment::MeshPeerInfo* peer : asked.mesh_peers)
      lines.push_back(problem_line(c.id, "answers for two meshes only", peer->name));
  return lines;
}

std::string error_line(const std::string& id, const std::string& problem,
                       const AlgorithmInfo* algorithm) {
  return problem_line(id, problem, algorithm ? algorithm->name : std::string_view{});
}

}  // namespace gjklab::cli
