#include "gjklab/experiment/records.hpp"

namespace gjklab::experiment {

std::string_view to_string(Placement p) {
  switch (p) {
    case Placement::separated: return "separated";
    case Placement::overlapping: return "overlapping";
    case Placement::random: return "random";
  }
  return "unknown";
}

std::string_view to_string(ContactClass c) {
  switch (c) {
    case ContactClass::separated: return "separated";
    case ContactClass::touching_band: return "touching_band";
    case ContactClass::intersecting: return "intersecting";
  }
  return "unknown";
}

std::string_view to_string(ShapeKind s) {
  switch (s) {
    case ShapeKind::sphere_points: return "sphere_points";
    case ShapeKind::ball_points: return "ball_points";
    case ShapeKind::cube_points: return "cube_points";
    case ShapeKind::gaussian: return "gaussian";
    case ShapeKind::box: return "box";
    case ShapeKind::cone: return "cone";
    case ShapeKind::cylinder: return "cylinder";
    case ShapeKind::uv_sphere: return "uv_sphere";
  }
  return "unknown";
}

}  // namespace gjklab::experiment
