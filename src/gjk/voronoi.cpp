#include "gjklab/gjk/voronoi.hpp"

#include <cmath>

#include "subsimplex_candidates.hpp"

namespace gjklab {

namespace {

using detail::nearer;
using detail::single_point;

/// y_i + t (y_j − y_i): weights 1 − t and t.
template <class T>
SubsimplexSolutionT<T> on_edge(const std::array<Vec3T<T>, 4>& y, int i, int j, T t) {
  SubsimplexSolutionT<T> s;
  s.found = true;
  s.subset = static_cast<std::uint8_t>((1u << i) | (1u << j));
  s.weights[i] = 1 - t;
  s.weights[j] = t;
  s.closest = y[i] + t * (y[j] - y[i]);
  return s;
}

/// Closest point of segment y_i y_j (Ericson 5.1.2, query point at the origin).
template <class T>
SubsimplexSolutionT<T> segment(const std::array<Vec3T<T>, 4>& y, int i, int j) {
  const Vec3T<T> ab = y[j] - y[i];
  const T t = (-y[i]).dot(ab);
  if (t <= 0) return single_point(y, i);
  const T denom = ab.dot(ab);
  if (t >= denom) return single_point(y, j);
  return on_edge(y, i, j, t / denom);
}

/// Closest point of triangle a = y_i, b = y_j, c = y_k (Ericson 5.1.5, ClosestPtPointTriangle,
/// query point at the origin). Edge regions of zero-length edges are skipped, and a face case
/// without a positive area falls back to the three edges.
template <class T>
SubsimplexSolutionT<T> triangle(const std::array<Vec3T<T>, 4>& y, int i, int j, int k) {
  const Vec3T<T>&a = y[i], &b = y[j], &c = y[k];
  const Vec3T<T> ab = b - a, ac = c - a;
  // Vertex region of a.
  const Vec3T<T> ap = -a;
  const T d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return single_point(y, i);
  // Vertex region of b.
  const Vec3T<T> bp = -b;
  const T d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return single_point(y, j);
  // Edge region of ab (d1 − d3 = ‖ab‖²).
  const T vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) return on_edge(y, i, j, d1 / (d1 - d3));
  // Vertex region of c.
  const Vec3T<T> cp = -c;
  const T d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return single_point(y, k);
  // Edge region of ac (d2 − d6 = ‖ac‖²).
  const T vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) return on_edge(y, i, k, d2 / (d2 - d6));
  // Edge region of bc ((d4 − d3) + (d5 − d6) = ‖bc‖²).
  const T va = d3 * d6 - d5 * d4;
  const T e4 = d4 - d3, e5 = d5 - d6;
  if (va <= 0 && e4 >= 0 && e5 >= 0 && e4 + e5 > 0) return on_edge(y, j, k, e4 / (e4 + e5));
  // Face region: barycentric weights (va, vb, vc) / (va + vb + vc).
  const T sum = va + vb + vc;
  if (!(sum > 0)) {
    if (std::isnan(sum)) {  // let the caller see the NaN
      SubsimplexSolutionT<T> s = single_point(y, i);
      s.closest = Vec3T<T>::Constant(sum);
      return s;
    }
    SubsimplexSolutionT<T> best = segment(y, i, j);
    best = nearer(best, segment(y, i, k));
    return nearer(best, segment(y, j, k));
  }
  const T denom = 1 / sum;
  const T v = vb * denom, w = vc * denom;
  SubsimplexSolutionT<T> s;
  s.found = true;
  s.subset = static_cast<std::uint8_t>((1u << i) | (1u << j) | (1u << k));
  s.weights[i] = 1 - v - w;
  s.weights[j] = v;
  s.weights[k] = w;
  s.closest = a + ab * v + ac * w;
  refine_triangle_point(s, y);
  return s;
}

/// Strictly opposite signs, without forming the product (which could under- or overflow).
template <class T>
bool opposite_signs(T p, T q) {
  return (p < 0 && q > 0) || (p > 0 && q < 0);
}

/// Closest point of the tetrahedron y_0 … y_3 (Ericson 5.1.6, ClosestPtPointTetrahedron).
template <class T>
SubsimplexSolutionT<T> tetrahedron(const std::array<Vec3T<T>, 4>& y) {
  // Faces with the vertex opposite each (Ericson's abc/d, acd/b, adb/c, bdc/a).
  static constexpr std::array<std::array<int, 4>, 4> kFaces = {
      {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}}};
  SubsimplexSolutionT<T> best;
  bool outside_any = false;
  for (const auto& f : kFaces) {
    const Vec3T<T>&a = y[f[0]], &b = y[f[1]], &c = y[f[2]], &d = y[f[3]];
    const Vec3T<T> normal = (b - a).cross(c - a);
    const T sign_p = (-a).dot(normal);  // [AP AB AC] with P the origin
    const T sign_d = (d - a).dot(normal);
    // Flat tetrahedron (sign_d = 0) or NaN: every face is a candidate.
    const bool test = opposite_signs(sign_p, sign_d) || !(sign_d != 0);
    if (!test) continue;
    outside_any = true;
    best = nearer(best, triangle(y, f[0], f[1], f[2]));
  }
  if (outside_any) return best;
  // Inside: barycentric weights from the signed volumes with each vertex replaced by the origin.
  const Vec3T<T>&a = y[0], &b = y[1], &c = y[2], &d = y[3];
  const Vec3T<T> ab = b - a, ac = c - a, ad = d - a, ao = -a;
  const T volume = ab.dot(ac.cross(ad));
  SubsimplexSolutionT<T> s;
  s.found = true;
  s.subset = 0b1111;
  s.weights[1] = ao.dot(ac.cross(ad)) / volume;
  s.weights[2] = ab.dot(ao.cross(ad)) / volume;
  s.weights[3] = ab.dot(ac.cross(ao)) / volume;
  s.weights[0] = 1 - s.weights[1] - s.weights[2] - s.weights[3];
  for (int i = 0; i < 4; ++i)
    s.closest += s.weights[i] * y[i];
  return s;
}

}  // namespace

template <class T>
SubsimplexSolutionT<T> voronoi_closest_point(const std::array<Vec3T<T>, 4>& y, int count) {
  SubsimplexSolutionT<T> s;
  switch (count) {
    case 1:
      s = single_point(y, 0);
      break;
    case 2:
      s = segment(y, 0, 1);
      break;
    case 3:
      s = triangle(y, 0, 1, 2);
      break;
    case 4:
      s = tetrahedron(y);
      break;
    default:
      return s;
  }
  // Points with weight exactly 0 (the origin on a region boundary) do not contribute: drop
  // them to keep the sub-simplex minimal (GJK reads a kept tetrahedron as contact).
  for (int i = 0; i < count; ++i) {
    const unsigned bit = 1u << i;
    if ((s.subset & bit) && s.weights[i] == 0 && (s.subset & ~bit)) {
      s.subset = static_cast<std::uint8_t>(s.subset & ~bit);
    }
  }
  return s;
}

template SubsimplexSolutionT<float> voronoi_closest_point(const std::array<Vec3T<float>, 4>&, int);
template SubsimplexSolutionT<double> voronoi_closest_point(const std::array<Vec3T<double>, 4>&,
                                                           int);
template SubsimplexSolutionT<long double> voronoi_closest_point(
    const std::array<Vec3T<long double>, 4>&, int);

}  // namespace gjklab
