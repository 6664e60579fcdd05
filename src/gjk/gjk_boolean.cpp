#include "gjklab/gjk/gjk_boolean.hpp"

#include <limits>

namespace gjklab::detail {

namespace {

/// x and y point into the same open half-space.
bool same_side(const Vec3& x, const Vec3& y) {
  return x.dot(y) > 0;
}

/// Direction perpendicular to edge e, in the plane of e and the origin offset o, towards o.
Vec3 towards_origin_from_edge(const Vec3& e, const Vec3& o) {
  return e.cross(o).cross(e);
}

void set(BooleanSimplex& s, const Vec3& p0) {
  s.points[0] = p0;
  s.size = 1;
}
void set(BooleanSimplex& s, const Vec3& p0, const Vec3& p1) {
  s.points[0] = p0;
  s.points[1] = p1;
  s.size = 2;
}
void set(BooleanSimplex& s, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  s.points[0] = p0;
  s.points[1] = p1;
  s.points[2] = p2;
  s.size = 3;
}

/// Relative size, in units of the rounding error, below which the triple product of an edge
/// and the origin offset is noise: |(ab × ao) × ab| ≤ this · ε · ‖ab‖² · ‖ao‖ (each of the
/// two cross products rounds with a relative error of a few ε).
constexpr double kCollinearNoise = 16 * std::numeric_limits<double>::epsilon();

/// The origin lies on segment ab's line within rounding, between a and b: the segment, a part
/// of A − B, holds the origin up to rounding (the shapes touch or overlap). The noise test
/// comes first and on squared lengths (no square root): it fails on nearly every call.
bool origin_on_segment(const Vec3& a, const Vec3& b, const Vec3& towards_origin) {
  const Vec3 ab = b - a;
  const double noise_over_a = kCollinearNoise * ab.squaredNorm();  // noise / ‖a‖
  return towards_origin.squaredNorm() <= noise_over_a * noise_over_a * a.squaredNorm() &&
         same_side(ab, -a) && same_side(a - b, -b);
}

bool segment_case(BooleanSimplex& s, Vec3& d) {
  const Vec3 a = s.points[0], b = s.points[1];
  const Vec3 ab = b - a, ao = -a;
  if (same_side(ab, ao)) {
    d = towards_origin_from_edge(ab, ao);
    // Without this, an origin on the line (e.g. from the centre start on a shape symmetric
    // about the centre line) leaves a direction of pure noise, and the walk can cycle.
    if (origin_on_segment(a, b, d)) return true;
  } else {
    set(s, a);
    d = ao;
  }
  return false;
}

bool triangle_case(BooleanSimplex& s, Vec3& d) {
  const Vec3 a = s.points[0], b = s.points[1], c = s.points[2];
  const Vec3 ab = b - a, ac = c - a, ao = -a;
  const Vec3 abc = ab.cross(ac);
  if (same_side(abc.cross(ac), ao)) {
    if (same_side(ac, ao)) {
      set(s, a, c);
      d = towards_origin_from_edge(ac, ao);
      return false;
    }
    set(s, a, b);
    return segment_case(s, d);
  }
  if (same_side(ab.cross(abc), ao)) {
    set(s, a, b);
    return segment_case(s, d);
  }
  // The origin projects inside the triangle: search above or below it, keeping the winding
  // so that the triangle's normal faces the origin (the tetrahedron case relies on it).
  if (same_side(abc, ao)) {
    d = abc;
  } else {
    set(s, a, c, b);
    d = -abc;
  }
  return false;
}

bool tetrahedron_case(BooleanSimplex& s, Vec3& d) {
  const Vec3 a = s.points[0], b = s.points[1], c = s.points[2], e = s.points[3];
  const Vec3 ab = b - a, ac = c - a, ae = e - a, ao = -a;
  if (same_side(ab.cross(ac), ao)) {
    set(s, a, b, c);
    return triangle_case(s, d);
  }
  if (same_side(ac.cross(ae), ao)) {
    set(s, a, c, e);
    return triangle_case(s, d);
  }
  if (same_side(ae.cross(ab), ao)) {
    set(s, a, e, b);
    return triangle_case(s, d);
  }
  return true;  // the origin is inside or on the tetrahedron
}

}  // namespace

bool boolean_gjk_step(BooleanSimplex& simplex, Vec3& direction) {
  switch (simplex.size) {
    case 2:
      return segment_case(simplex, direction);
    case 3:
      return triangle_case(simplex, direction);
    default:
      return tetrahedron_case(simplex, direction);
  }
}

}  // namespace gjklab::detail
