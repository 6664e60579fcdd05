#include "gjklab/gjk/gjk_boolean.hpp"

#include <limits>

namespace gjklab::detail {

namespace {

/// x and y point into the same open half-space.
template <class T>
bool same_side(const Vec3T<T>& x, const Vec3T<T>& y) {
  return x.dot(y) > 0;
}

/// Direction perpendicular to edge e, in the plane of e and the origin offset o, towards o.
template <class T>
Vec3T<T> towards_origin_from_edge(const Vec3T<T>& e, const Vec3T<T>& o) {
  return e.cross(o).cross(e);
}

template <class T>
void set(BooleanSimplexT<T>& s, const Vec3T<T>& p0) {
  s.points[0] = p0;
  s.size = 1;
}
template <class T>
void set(BooleanSimplexT<T>& s, const Vec3T<T>& p0, const Vec3T<T>& p1) {
  s.points[0] = p0;
  s.points[1] = p1;
  s.size = 2;
}
template <class T>
void set(BooleanSimplexT<T>& s, const Vec3T<T>& p0, const Vec3T<T>& p1, const Vec3T<T>& p2) {
  s.points[0] = p0;
  s.points[1] = p1;
  s.points[2] = p2;
  s.size = 3;
}

/// Relative size, in units of the rounding error, below which the triple product of an edge
/// and the origin offset is noise: |(ab × ao) × ab| ≤ this · ε · ‖ab‖² · ‖ao‖ (each of the
/// two cross products rounds with a relative error of a few ε; ε of the query's precision).
template <class T>
constexpr T kCollinearNoise = 16 * std::numeric_limits<T>::epsilon();

/// The origin lies on segment ab's line within rounding, between a and b: the segment, a part
/// of A − B, holds the origin up to rounding (the shapes touch or overlap). The noise test
/// comes first and on squared lengths (no square root): it fails on nearly every call.
template <class T>
bool origin_on_segment(const Vec3T<T>& a, const Vec3T<T>& b, const Vec3T<T>& towards_origin) {
  const Vec3T<T> ab = b - a;
  const T noise_over_a = kCollinearNoise<T> * ab.squaredNorm();  // noise / ‖a‖
  return towards_origin.squaredNorm() <= noise_over_a * noise_over_a * a.squaredNorm() &&
         same_side<T>(ab, -a) && same_side<T>(a - b, -b);
}

template <class T>
bool segment_case(BooleanSimplexT<T>& s, Vec3T<T>& d) {
  const Vec3T<T> a = s.points[0], b = s.points[1];
  const Vec3T<T> ab = b - a, ao = -a;
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

template <class T>
bool triangle_case(BooleanSimplexT<T>& s, Vec3T<T>& d) {
  const Vec3T<T> a = s.points[0], b = s.points[1], c = s.points[2];
  const Vec3T<T> ab = b - a, ac = c - a, ao = -a;
  const Vec3T<T> abc = ab.cross(ac);
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

template <class T>
bool tetrahedron_case(BooleanSimplexT<T>& s, Vec3T<T>& d) {
  const Vec3T<T> a = s.points[0], b = s.points[1], c = s.points[2], e = s.points[3];
  const Vec3T<T> ab = b - a, ac = c - a, ae = e - a, ao = -a;
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

template <class T>
bool boolean_gjk_step(BooleanSimplexT<T>& simplex, Vec3T<T>& direction) {
  switch (simplex.size) {
    case 2:
      return segment_case(simplex, direction);
    case 3:
      return triangle_case(simplex, direction);
    default:
      return tetrahedron_case(simplex, direction);
  }
}

template bool boolean_gjk_step(BooleanSimplexT<float>&, Vec3T<float>&);
template bool boolean_gjk_step(BooleanSimplexT<double>&, Vec3T<double>&);
template bool boolean_gjk_step(BooleanSimplexT<long double>&, Vec3T<long double>&);

}  // namespace gjklab::detail
