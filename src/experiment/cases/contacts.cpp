#include "experiment/cases/contacts.hpp"

#include <cmath>
#include <stdexcept>

#include "experiment/cases/sampling.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/shapes.hpp"

namespace gjklab::experiment {

namespace {

// ---- contact families ----
//
// Each configuration is built with the contact plane z = 0, A below and B above, from
// coordinates that are small multiples of 1/8, so the pair is in exact contact (distance 0).
// B's lateral offset (dx, dy) is drawn from the multiples of 1/8 in [-7/8, 7/8], which keeps
// the contact feature inside the other shape's face or edge.

double dyadic_offset(gsl_rng* r) {
  return (static_cast<double>(gsl_rng_uniform_int(r, 15)) - 7.0) / 8.0;
}

/// Box [-1, 1]² × [-2, 0] (top face in the contact plane).
std::vector<Vec3> box_below() {
  std::vector<Vec3> v;
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0})
      for (double z : {-2.0, 0.0})
        v.emplace_back(x, y, z);
  return v;
}

/// Box [dx-1, dx+1] × [dy-1, dy+1] × [0, 2] (bottom face in the contact plane).
std::vector<Vec3> box_above(double dx, double dy) {
  std::vector<Vec3> v;
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0})
      for (double z : {0.0, 2.0})
        v.emplace_back(dx + x, dy + y, z);
  return v;
}

/// Triangular prism with its ridge along y at x = 0, z = 0, widening downwards.
std::vector<Vec3> roof_below() {
  return {Vec3(0, -1, 0),  Vec3(0, 1, 0),   Vec3(-1, -1, -1),
          Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(1, 1, -1)};
}

/// Triangular prism with its ridge along `axis` (unit, in the plane z = 0) through (dx, dy, 0),
/// widening upwards. Exact when axis is ±x or ±y.
std::vector<Vec3> ridge_above(const Vec3& axis, double dx, double dy) {
  const Vec3 across(-axis.y(), axis.x(), 0);
  const Vec3 c(dx, dy, 0);
  return {c - axis,
          c + axis,
          c - axis - across + Vec3(0, 0, 1),
          c - axis + across + Vec3(0, 0, 1),
          c + axis - across + Vec3(0, 0, 1),
          c + axis + across + Vec3(0, 0, 1)};
}

/// Square pyramid with its apex at (dx, dy, 0) and base at z = ±1 (sign: +1 above).
std::vector<Vec3> pyramid(double dx, double dy, double side) {
  std::vector<Vec3> v{Vec3(dx, dy, 0)};
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0})
      v.emplace_back(dx + x, dy + y, side);
  return v;
}


// ---- the thin contacts: A below z = 0, B above, touching at the origin ----------------------

/// The rotation by θ about the z axis.
Mat3 about_z(double theta) {
  return Eigen::AngleAxisd(theta, Vec3::UnitZ()).toRotationMatrix();
}

/// The segment (±1, 0, 0) turned by θ about z.
std::vector<Vec3> segment_at(double theta) {
  const Mat3 turn = about_z(theta);
  return {turn * Vec3(-1, 0, 0), turn * Vec3(1, 0, 0)};
}

/// The needle triangle (−1, 0, 0), (1, 0, 0), (1/2, 2/aspect, 0) in the plane z = 0.
std::vector<Vec3> needle_triangle(double aspect) {
  return {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 2 / aspect, 0)};
}

/// A k-gon prism of length 2 along x, radius ρ, with one vertex line on the x axis and the
/// rest on the side `side` (−1: below z = 0), turned by θ about z.
std::vector<Vec3> rod(int k, double rho, double side, double theta) {
  const Mat3 turn = about_z(theta);
  std::vector<Vec3> v;
  for (int j = 0; j < k; ++j) {
    const double phi = 2 * M_PI * j / k;
    // Vertex 0 is on the axis exactly; the others around the centre (0, 0, side·ρ).
    const double y = j == 0 ? 0.0 : -rho * std::sin(phi);
    const double z = j == 0 ? 0.0 : side * rho * (1 - std::cos(phi));
    for (double x : {-1.0, 1.0})
      v.push_back(turn * Vec3(x, y, z));
  }
  return v;
}

/// A triangular prism of length 2 along x whose ridge is the x axis and which widens to
/// ±1/aspect at z = side, turned by θ about z.
std::vector<Vec3> sharp_wedge(double aspect, double side, double theta) {
  const Mat3 turn = about_z(theta);
  std::vector<Vec3> v;
  for (double x : {-1.0, 1.0}) {
    v.push_back(turn * Vec3(x, 0, 0));
    for (double y : {-1.0, 1.0})
      v.push_back(turn * Vec3(x, y / aspect, side));
  }
  return v;
}

/// A plate [−1, 1]² × [−1/aspect, 0], and one on top of it tilted by θ about its edge x = −1.
ContactPair plates(double aspect, double theta) {
  const double t = 1 / aspect;
  const Mat3 tilt = Eigen::AngleAxisd(-theta, Vec3::UnitY()).toRotationMatrix();
  std::vector<Vec3> a, b;
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0})
      for (double z : {-t, 0.0}) {
        a.emplace_back(x, y, z);
        b.push_back(Vec3(-1, 0, 0) + tilt * Vec3(x + 1, y, z + t));
      }
  return {a, b, ShapeKind::plate, ShapeKind::plate};
}

ContactPair build_thin_contact(ContactType type, gsl_rng* r, const FamilySpec& family) {
  const double theta = log_uniform(r, family.angle);
  const double aspect = log_uniform(r, family.aspect);
  switch (type) {
    case ContactType::crossing_segments:
      return {segment_at(0), segment_at(theta), ShapeKind::segment, ShapeKind::segment};
    case ContactType::needle_point:
      return {needle_triangle(aspect),
              {Vec3(0.25, 0.5 / aspect, 0)},
              ShapeKind::needle,
              ShapeKind::single_point};
    case ContactType::needle_segment: {
      std::vector<Vec3> b = segment_at(theta);
      for (Vec3& p : b)
        p += Vec3(0.25, 1 / aspect, 0);
      return {needle_triangle(aspect), b, ShapeKind::needle, ShapeKind::segment};
    }
    case ContactType::thin_rods: {
      const int k = 3 + static_cast<int>(gsl_rng_uniform_int(r, 6));
      return {rod(k, 1 / aspect, -1, 0), rod(k, 1 / aspect, 1, theta), ShapeKind::rod,
              ShapeKind::rod};
    }
    case ContactType::crossing_wedges: {
      // Half the cases nearly parallel ridges, half ridges crossing at any angle.
      const double crossing = uniform(r) < 0.5 ? theta : 0.5 * M_PI * uniform(r);
      return {sharp_wedge(aspect, -1, 0), sharp_wedge(aspect, 1, crossing), ShapeKind::wedge,
              ShapeKind::wedge};
    }
    case ContactType::tilted_plates:
      return plates(aspect, theta);
    default:
      break;
  }
  throw std::invalid_argument("build_thin_contact: not a thin contact family");
}

}  // namespace


ContactPair build_contact(ContactType type, gsl_rng* r, const FamilySpec& family) {
  const double dx = dyadic_offset(r), dy = dyadic_offset(r);
  const Vec3 x_axis = Vec3::UnitX();
  switch (type) {
    case ContactType::face_face:
      return {box_below(), box_above(dx, dy), ShapeKind::box, ShapeKind::box};
    case ContactType::edge_edge:
      return {roof_below(), ridge_above(x_axis, dx, dy), ShapeKind::prism, ShapeKind::prism};
    case ContactType::vertex_face:
      return {box_below(), pyramid(dx, dy, 1), ShapeKind::box, ShapeKind::pyramid};
    case ContactType::edge_face:
      return {box_below(), ridge_above(x_axis, dx, dy), ShapeKind::box, ShapeKind::prism};
    case ContactType::vertex_edge:
      return {roof_below(), pyramid(0, dy, 1), ShapeKind::prism, ShapeKind::pyramid};
    case ContactType::vertex_vertex:
      return {pyramid(0, 0, -1), pyramid(0, 0, 1), ShapeKind::pyramid, ShapeKind::pyramid};
    case ContactType::parallel_edges: {
      // The ridges cross at the origin at a small angle θ: nearly parallel edges in contact.
      const double theta = log_uniform(r, family.angle);
      const Vec3 axis(-std::sin(theta), std::cos(theta), 0);
      return {roof_below(), ridge_above(axis, 0, 0), ShapeKind::prism, ShapeKind::prism};
    }
    case ContactType::none:
      break;
    default:
      return build_thin_contact(type, r, family);
  }
  throw std::invalid_argument("build_contact: not a contact family");
}

std::vector<Vec3> contact_piece(ShapeKind kind, double aspect) {
  switch (kind) {
    case ShapeKind::prism:
      return roof_below();
    case ShapeKind::pyramid:
      return pyramid(0, 0, -1);
    case ShapeKind::segment:
      return segment_at(0);
    case ShapeKind::needle:
      return needle_triangle(aspect);
    case ShapeKind::rod:
      return rod(6, 1 / aspect, -1, 0);
    case ShapeKind::wedge:
      return sharp_wedge(aspect, -1, 0);
    case ShapeKind::plate:
      return plates(aspect, 0).a;
    default:
      break;
  }
  throw std::invalid_argument("contact_piece: not a contact family's shape");
}

}  // namespace gjklab::experiment
