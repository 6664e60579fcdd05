#include "gjklab/experiment/records.hpp"

#include <array>
#include <cmath>

namespace gjklab::experiment {

namespace {

// One name per enumerator, in value order (these enums count from 0 without gaps). to_string
// reads them, and through it the archive's HDF5 enum types, the summaries and the experiment
// parser's lists of valid names.
constexpr std::array<std::string_view, 5> kPlacementNames = {"separated", "overlapping", "random",
                                                             "touching", "as_given"};
constexpr std::array<std::string_view, 3> kContactClassNames = {"separated", "touching_band",
                                                                "intersecting"};
constexpr std::array<std::string_view, 19> kShapeKindNames = {"sphere_points",
                                                              "ball_points",
                                                              "cube_points",
                                                              "gaussian",
                                                              "box",
                                                              "cone",
                                                              "cylinder",
                                                              "uv_sphere",
                                                              "flat_points",
                                                              "collinear_points",
                                                              "duplicate_points",
                                                              "single_point",
                                                              "sliver",
                                                              "prism",
                                                              "pyramid",
                                                              "from_file",
                                                              "mesh",
                                                              "sphere",
                                                              "capsule"};
constexpr std::array<std::string_view, 8> kContactTypeNames = {
    "none",      "face-face",   "edge-edge",     "vertex-face",
    "edge-face", "vertex-edge", "vertex-vertex", "parallel-edges"};
constexpr std::array<std::string_view, 9> kFailureClassNames = {
    "none",    "touching_band", "step_limit",    "no_progress",   "degenerate_simplex",
    "cycling", "non_finite",    "wrong_boolean", "distance_error"};

// Each table ends at the enum's last enumerator.
static_assert(kPlacementNames.size() == static_cast<std::size_t>(Placement::as_given) + 1);
static_assert(kContactClassNames.size() ==
              static_cast<std::size_t>(ContactClass::intersecting) + 1);
static_assert(kShapeKindNames.size() == static_cast<std::size_t>(ShapeKind::capsule) + 1);
static_assert(kContactTypeNames.size() ==
              static_cast<std::size_t>(ContactType::parallel_edges) + 1);
static_assert(kFailureClassNames.size() ==
              static_cast<std::size_t>(FailureClass::distance_error) + 1);

/// The value's name, or "unknown" for a value past the table (a corrupt or foreign byte).
template <class E, std::size_t N>
std::string_view name_in(const std::array<std::string_view, N>& names, E value) {
  const auto i = static_cast<std::size_t>(value);
  return i < N ? names[i] : "unknown";
}

}  // namespace

std::string_view to_string(Placement p) {
  return name_in(kPlacementNames, p);
}
std::string_view to_string(ContactClass c) {
  return name_in(kContactClassNames, c);
}
std::string_view to_string(ShapeKind s) {
  return name_in(kShapeKindNames, s);
}
std::string_view to_string(ContactType c) {
  return name_in(kContactTypeNames, c);
}
std::string_view to_string(FailureClass f) {
  return name_in(kFailureClassNames, f);
}

FailureClass classify_failure(const AlgorithmRecord& r, const ExactRecord* exact, double band) {
  const bool wrong_distance = !std::isnan(r.rel_error) && r.rel_error > band;
  const bool wrong_boolean = exact && r.intersect != exact->intersect;
  if (exact && exact->contact == ContactClass::touching_band && (wrong_boolean || wrong_distance))
    return FailureClass::touching_band;
  switch (r.termination) {
    case Termination::converged:
      break;
    case Termination::step_limit:
      return FailureClass::step_limit;
    case Termination::no_progress:
      return FailureClass::no_progress;
    case Termination::degenerate_simplex:
      return FailureClass::degenerate_simplex;
    case Termination::cycling:
      return FailureClass::cycling;
    case Termination::numerical_failure:
    case Termination::invalid_input:
      return FailureClass::non_finite;
  }
  if (!std::isfinite(r.distance) && !std::isnan(r.distance)) return FailureClass::non_finite;
  if (!r.boolean_correct) return FailureClass::wrong_boolean;
  if (wrong_distance) return FailureClass::distance_error;
  return FailureClass::none;
}

}  // namespace gjklab::experiment
