#include "gjklab/experiment/cases/records.hpp"

#include <array>
#include <cmath>

#include "gjklab/geometry/enum_names.hpp"

namespace gjklab::experiment {

namespace {

// One name table per enum (geometry/enum_names.hpp). to_string reads them, and through it the
// archive's HDF5 enum types, the summaries and the experiment parser's lists of valid names.
constexpr auto kPlacementNames = std::to_array<EnumName<Placement>>({
    {Placement::separated, "separated"},
    {Placement::overlapping, "overlapping"},
    {Placement::random, "random"},
    {Placement::touching, "touching"},
    {Placement::as_given, "as_given"},
});
constexpr auto kContactClassNames = std::to_array<EnumName<ContactClass>>({
    {ContactClass::separated, "separated"},
    {ContactClass::touching_band, "touching_band"},
    {ContactClass::intersecting, "intersecting"},
});
constexpr auto kShapeKindNames = std::to_array<EnumName<ShapeKind>>({
    {ShapeKind::sphere_points, "sphere_points"},
    {ShapeKind::ball_points, "ball_points"},
    {ShapeKind::cube_points, "cube_points"},
    {ShapeKind::gaussian, "gaussian"},
    {ShapeKind::box, "box"},
    {ShapeKind::cone, "cone"},
    {ShapeKind::cylinder, "cylinder"},
    {ShapeKind::uv_sphere, "uv_sphere"},
    {ShapeKind::flat_points, "flat_points"},
    {ShapeKind::collinear_points, "collinear_points"},
    {ShapeKind::duplicate_points, "duplicate_points"},
    {ShapeKind::single_point, "single_point"},
    {ShapeKind::sliver, "sliver"},
    {ShapeKind::prism, "prism"},
    {ShapeKind::pyramid, "pyramid"},
    {ShapeKind::from_file, "from_file"},
    {ShapeKind::mesh, "mesh"},
    {ShapeKind::sphere, "sphere"},
    {ShapeKind::capsule, "capsule"},
    {ShapeKind::segment, "segment"},
    {ShapeKind::needle, "needle"},
    {ShapeKind::rod, "rod"},
    {ShapeKind::wedge, "wedge"},
    {ShapeKind::plate, "plate"},
});
constexpr auto kContactTypeNames = std::to_array<EnumName<ContactType>>({
    {ContactType::none, "none"},
    {ContactType::face_face, "face-face"},
    {ContactType::edge_edge, "edge-edge"},
    {ContactType::vertex_face, "vertex-face"},
    {ContactType::edge_face, "edge-face"},
    {ContactType::vertex_edge, "vertex-edge"},
    {ContactType::vertex_vertex, "vertex-vertex"},
    {ContactType::parallel_edges, "parallel-edges"},
    {ContactType::crossing_segments, "crossing-segments"},
    {ContactType::needle_point, "needle-point"},
    {ContactType::needle_segment, "needle-segment"},
    {ContactType::thin_rods, "thin-rods"},
    {ContactType::crossing_wedges, "crossing-wedges"},
    {ContactType::tilted_plates, "tilted-plates"},
});
constexpr auto kFailureClassNames = std::to_array<EnumName<FailureClass>>({
    {FailureClass::none, "none"},
    {FailureClass::touching_band, "touching_band"},
    {FailureClass::step_limit, "step_limit"},
    {FailureClass::no_progress, "no_progress"},
    {FailureClass::degenerate_simplex, "degenerate_simplex"},
    {FailureClass::cycling, "cycling"},
    {FailureClass::non_finite, "non_finite"},
    {FailureClass::wrong_boolean, "wrong_boolean"},
    {FailureClass::distance_error, "distance_error"},
});

// Each table names every enumerator, in value order.
static_assert(in_value_order(kPlacementNames) && ends_at(kPlacementNames, Placement::as_given));
static_assert(in_value_order(kContactClassNames) &&
              ends_at(kContactClassNames, ContactClass::intersecting));
static_assert(in_value_order(kShapeKindNames) && ends_at(kShapeKindNames, ShapeKind::plate));
static_assert(in_value_order(kContactTypeNames) &&
              ends_at(kContactTypeNames, ContactType::tilted_plates));
static_assert(in_value_order(kFailureClassNames) &&
              ends_at(kFailureClassNames, FailureClass::distance_error));

}  // namespace

std::string_view to_string(Placement p) {
  return name_of(kPlacementNames, p);
}
std::string_view to_string(ContactClass c) {
  return name_of(kContactClassNames, c);
}
std::string_view to_string(ShapeKind s) {
  return name_of(kShapeKindNames, s);
}
std::string_view to_string(ContactType c) {
  return name_of(kContactTypeNames, c);
}
std::string_view to_string(FailureClass f) {
  return name_of(kFailureClassNames, f);
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
