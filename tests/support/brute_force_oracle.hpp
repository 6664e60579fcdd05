// A brute-force exact oracle for the tests (GMP rationals, by enumerating the Minkowski
// difference's points and the simplices and planes they span): squared distance, squared
// penetration depth and hull vertex counts of small clouds, independent of the library's
// oracle and its certificates.
#pragma once

#include <gmpxx.h>

#include <optional>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::testing::brute_force {

/// The double x as an exact rational (exact for finite doubles).
inline mpq_class exact(double x) {
  return mpq_class(x);
}

struct Q3 {
  mpq_class x, y, z;
};
inline Q3 exact(const Vec3& v) {
  return {exact(v.x()), exact(v.y()), exact(v.z())};
}
inline Q3 operator-(const Q3& a, const Q3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Q3 operator+(const Q3& a, const Q3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Q3 operator*(const mpq_class& s, const Q3& a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline mpq_class dot(const Q3& a, const Q3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Q3 cross(const Q3& a, const Q3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline bool is_zero(const Q3& a) {
  return sgn(a.x) == 0 && sgn(a.y) == 0 && sgn(a.z) == 0;
}

/// Exact squared distance from the point p to the segment [s0, s1].
inline mpq_class point_segment_distance2(const Q3& p, const Q3& s0, const Q3& s1) {
  const Q3 e = s1 - s0;
  mpq_class t = 0;
  if (!is_zero(e)) t = dot(p - s0, e) / dot(e, e);
  if (t < 0) t = 0;
  if (t > 1) t = 1;
  const Q3 v = p - (s0 + t * e);
  return dot(v, v);
}

inline std::vector<Q3> differences(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  std::vector<Q3> d;
  for (const Vec3& p : a)
    for (const Vec3& q : b)
      d.push_back(exact(p) - exact(q));
  return d;
}

inline mpq_class det(const Q3& a, const Q3& b, const Q3& c) {
  return dot(a, cross(b, c));
}

/// Does the closed tetrahedron of some four points of d contain the origin?
inline bool tetrahedron_contains_origin(const std::vector<Q3>& d) {
  const std::size_t n = d.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k)
        for (std::size_t l = k + 1; l < n; ++l) {
          // -d[i] = a·e1 + b·e2 + c·e3 by Cramer's rule; inside iff a, b, c ≥ 0, a + b + c ≤ 1.
          const Q3 e1 = d[j] - d[i], e2 = d[k] - d[i], e3 = d[l] - d[i];
          const mpq_class v = det(e1, e2, e3);
          if (sgn(v) == 0) continue;
          const Q3 r = Q3{0, 0, 0} - d[i];
          const mpq_class a = det(r, e2, e3) / v, b = det(e1, r, e3) / v, c = det(e1, e2, r) / v;
          if (sgn(a) >= 0 && sgn(b) >= 0 && sgn(c) >= 0 && a + b + c <= 1) return true;
        }
  return false;
}

/// Exact squared distance from the origin to the hull of d (brute force over simplices: 0 if
/// a tetrahedron contains the origin, else the nearest point lies in a point, segment or
/// triangle of d).
inline mpq_class origin_distance2(const std::vector<Q3>& d) {
  if (tetrahedron_contains_origin(d)) return 0;
  mpq_class best = dot(d[0], d[0]);
  auto consider = [&best](const Q3& v) {
    const mpq_class v2 = dot(v, v);
    if (v2 < best) best = v2;
  };
  const std::size_t n = d.size();
  for (std::size_t i = 0; i < n; ++i)
    consider(d[i]);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const Q3 e = d[j] - d[i];
      const mpq_class ee = dot(e, e);
      if (sgn(ee) == 0) continue;
      const mpq_class t = -dot(d[i], e) / ee;
      if (t > 0 && t < 1) consider(d[i] + t * e);
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        const Q3 e1 = d[j] - d[i], e2 = d[k] - d[i];
        const mpq_class a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
        const mpq_class det = a11 * a22 - a12 * a12;
        if (sgn(det) == 0) continue;
        const mpq_class b1 = -dot(d[i], e1), b2 = -dot(d[i], e2);
        const mpq_class s = (b1 * a22 - b2 * a12) / det, t = (a11 * b2 - a12 * b1) / det;
        if (s > 0 && t > 0 && s + t < 1) consider(d[i] + s * e1 + t * e2);
      }
  return best;
}

inline mpq_class brute_distance2(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return origin_distance2(differences(a, b));
}

/// Exact squared depth: minimum over supporting planes of the difference cloud (which must
/// contain the origin); 0 if the difference cloud is flat.
inline mpq_class brute_depth2(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  const std::vector<Q3> d = differences(a, b);
  std::optional<mpq_class> best;
  const std::size_t n = d.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        const Q3 normal = cross(d[j] - d[i], d[k] - d[i]);
        if (is_zero(normal)) continue;
        bool below = false, above = false;
        for (const Q3& p : d) {
          const int side = sgn(dot(normal, p - d[i]));
          below = below || side < 0;
          above = above || side > 0;
        }
        if (below && above) continue;
        if (!below && !above) return 0;  // all of d in one plane: no interior
        const mpq_class s = dot(normal, d[i]);
        const mpq_class v = s * s / dot(normal, normal);
        if (!best || v < *best) best = v;
      }
  return best ? *best : mpq_class(0);
}

inline int brute_hull_vertex_count(const std::vector<Vec3>& cloud) {
  std::vector<Vec3> distinct;
  for (const Vec3& p : cloud) {
    bool seen = false;
    for (const Vec3& q : distinct)
      seen = seen || q == p;
    if (!seen) distinct.push_back(p);
  }
  int count = 0;
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    std::vector<Vec3> others;
    for (std::size_t j = 0; j < distinct.size(); ++j)
      if (j != i) others.push_back(distinct[j]);
    if (others.empty() || sgn(brute_distance2({distinct[i]}, others)) > 0) ++count;
  }
  return count;
}

}  // namespace gjklab::testing::brute_force
