#include "gjklab/gjk/gjk_boolean.hpp"

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

void set(BooleanSimplex& s, std::initializer_list<Vec3> points) {
  s.size = 0;
  for (const Vec3& p : points)
    s.points[s.size++] = p;
}

bool segment_case(BooleanSimplex& s, Vec3& d) {
  const Vec3 a = s.points[0], b = s.points[1];
  const Vec3 ab = b - a, ao = -a;
  if (same_side(ab, ao)) {
    d = towards_origin_from_edge(ab, ao);
  } else {
    set(s, {a});
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
      set(s, {a, c});
      d = towards_origin_from_edge(ac, ao);
      return false;
    }
    set(s, {a, b});
    return segment_case(s, d);
  }
  if (same_side(ab.cross(abc), ao)) {
    set(s, {a, b});
    return segment_case(s, d);
  }
  // The origin projects inside the triangle: search above or below it, keeping the winding
  // so that the triangle's normal faces the origin (the tetrahedron case relies on it).
  if (same_side(abc, ao)) {
    d = abc;
  } else {
    set(s, {a, c, b});
    d = -abc;
  }
  return false;
}

bool tetrahedron_case(BooleanSimplex& s, Vec3& d) {
  const Vec3 a = s.points[0], b = s.points[1], c = s.points[2], e = s.points[3];
  const Vec3 ab = b - a, ac = c - a, ae = e - a, ao = -a;
  if (same_side(ab.cross(ac), ao)) {
    set(s, {a, b, c});
    return triangle_case(s, d);
  }
  if (same_side(ac.cross(ae), ao)) {
    set(s, {a, c, e});
    return triangle_case(s, d);
  }
  if (same_side(ae.cross(ab), ao)) {
    set(s, {a, e, b});
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
