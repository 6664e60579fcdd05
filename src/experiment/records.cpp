#include "gjklab/experiment/records.hpp"

#include <cmath>

namespace gjklab::experiment {

std::string_view to_string(Placement p) {
  switch (p) {
    case Placement::separated:
      return "separated";
    case Placement::overlapping:
      return "overlapping";
    case Placement::random:
      return "random";
    case Placement::touching:
      return "touching";
    case Placement::as_given:
      return "as_given";
  }
  return "unknown";
}

std::string_view to_string(ContactClass c) {
  switch (c) {
    case ContactClass::separated:
      return "separated";
    case ContactClass::touching_band:
      return "touching_band";
    case ContactClass::intersecting:
      return "intersecting";
  }
  return "unknown";
}

std::string_view to_string(ShapeKind s) {
  switch (s) {
    case ShapeKind::sphere_points:
      return "sphere_points";
    case ShapeKind::ball_points:
      return "ball_points";
    case ShapeKind::cube_points:
      return "cube_points";
    case ShapeKind::gaussian:
      return "gaussian";
    case ShapeKind::box:
      return "box";
    case ShapeKind::cone:
      return "cone";
    case ShapeKind::cylinder:
      return "cylinder";
    case ShapeKind::uv_sphere:
      return "uv_sphere";
    case ShapeKind::flat_points:
      return "flat_points";
    case ShapeKind::collinear_points:
      return "collinear_points";
    case ShapeKind::duplicate_points:
      return "duplicate_points";
    case ShapeKind::single_point:
      return "single_point";
    case ShapeKind::sliver:
      return "sliver";
    case ShapeKind::prism:
      return "prism";
    case ShapeKind::pyramid:
      return "pyramid";
    case ShapeKind::from_file:
      return "from_file";
    case ShapeKind::mesh:
      return "mesh";
    case ShapeKind::sphere:
      return "sphere";
    case ShapeKind::capsule:
      return "capsule";
  }
  return "unknown";
}

std::string_view to_string(ContactType c) {
  switch (c) {
    case ContactType::none:
      return "none";
    case ContactType::face_face:
      return "face-face";
    case ContactType::edge_edge:
      return "edge-edge";
    case ContactType::vertex_face:
      return "vertex-face";
    case ContactType::edge_face:
      return "edge-face";
    case ContactType::vertex_edge:
      return "vertex-edge";
    case ContactType::vertex_vertex:
      return "vertex-vertex";
    case ContactType::parallel_edges:
      return "parallel-edges";
  }
  return "unknown";
}

std::string_view to_string(FailureClass f) {
  switch (f) {
    case FailureClass::none:
      return "none";
    case FailureClass::touching_band:
      return "touching_band";
    case FailureClass::step_limit:
      return "step_limit";
    case FailureClass::no_progress:
      return "no_progress";
    case FailureClass::degenerate_simplex:
      return "degenerate_simplex";
    case FailureClass::cycling:
      return "cycling";
    case FailureClass::non_finite:
      return "non_finite";
    case FailureClass::wrong_boolean:
      return "wrong_boolean";
    case FailureClass::distance_error:
      return "distance_error";
  }
  return "unknown";
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
