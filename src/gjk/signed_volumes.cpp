#include "gjklab/gjk/signed_volumes.hpp"

#include <cmath>

#include "subsimplex_candidates.hpp"

namespace gjklab {

namespace {

using detail::nearer;
using detail::single_point;

/// Montanari et al.'s compareSigns: true when both are > 0 or both are < 0 (zero and NaN fail).
template <class T>
bool same_sign(T a, T b) {
  return (a > 0 && b > 0) || (a < 0 && b < 0);
}

/// Fills the solution of the sub-simplex `indices` with weights numerator[k] / denominator.
template <std::size_t N, class T>
SubsimplexSolutionT<T> weighted(const std::array<Vec3T<T>, 4>& y, const std::array<int, N>& indices,
                                const std::array<T, N>& numerator, T denominator) {
  SubsimplexSolutionT<T> s;
  s.found = true;
  for (std::size_t k = 0; k < N; ++k) {
    const int i = indices[k];
    s.subset = static_cast<std::uint8_t>(s.subset | (1u << i));
    s.weights[i] = numerator[k] / denominator;
    s.closest += s.weights[i] * y[i];
  }
  return s;
}

/// S1D: segment y_i y_j.
template <class T>
SubsimplexSolutionT<T> s1d(const std::array<Vec3T<T>, 4>& y, int i, int j) {
  const Vec3T<T> t = y[j] - y[i];
  const T tt = t.squaredNorm();
  if (!(tt > 0)) return single_point(y, i);  // coincident ends
  // The coordinate axis on which the segment is longest.
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(t[k]) > std::abs(t[axis])) axis = k;
  // p0: projection of the origin onto the segment's line.
  const Vec3T<T> p0 = y[i] - (y[i].dot(t) / tt) * t;
  // Signed lengths on that axis: μ = y_i − y_j, and the two with an end replaced by p0.
  const T mu = y[i][axis] - y[j][axis];
  const T c_i = p0[axis] - y[j][axis];
  const T c_j = y[i][axis] - p0[axis];
  const bool in_i = same_sign(mu, c_i), in_j = same_sign(mu, c_j);
  if (in_i && in_j) return weighted<2>(y, {i, j}, {c_i, c_j}, mu);
  if (in_i) return single_point(y, i);  // λ_j ≤ 0: the origin projects beyond y_i
  if (in_j) return single_point(y, j);
  return nearer(single_point(y, i), single_point(y, j));
}

/// Twice the signed area of the triangle (p, q, r) projected onto the coordinate plane (u, w):
/// the determinant of [1 1 1; p_u q_u r_u; p_w q_w r_w], expanded as in the paper.
template <class T>
T projected_area(const Vec3T<T>& p, const Vec3T<T>& q, const Vec3T<T>& r, int u, int w) {
  return q[u] * r[w] + p[u] * q[w] + r[u] * p[w] - q[u] * p[w] - r[u] * q[w] - p[u] * r[w];
}

/// S2D: triangle y_i y_j y_k.
template <class T>
SubsimplexSolutionT<T> s2d(const std::array<Vec3T<T>, 4>& y, int i, int j, int k) {
  // The coordinate plane on which the triangle's projection has the largest area. Dropping
  // axis a and keeping (a+1, a+2) makes the projected area the a-th component of the normal.
  int drop = 0;
  T mu_max = 0;
  for (int a = 0; a < 3; ++a) {
    const T mu = projected_area(y[i], y[j], y[k], (a + 1) % 3, (a + 2) % 3);
    if (std::abs(mu) > std::abs(mu_max)) mu_max = mu, drop = a;
  }
  const Vec3T<T> n = (y[j] - y[i]).cross(y[k] - y[i]);
  const T nn = n.squaredNorm();
  if (mu_max != 0 && nn > 0) {
    // p0: projection of the origin onto the triangle's plane.
    const Vec3T<T> p0 = (y[i].dot(n) / nn) * n;
    const int u = (drop + 1) % 3, w = (drop + 2) % 3;
    const std::array<T, 3> c = {projected_area(p0, y[j], y[k], u, w),
                                projected_area(y[i], p0, y[k], u, w),
                                projected_area(y[i], y[j], p0, u, w)};
    if (same_sign(mu_max, c[0]) && same_sign(mu_max, c[1]) && same_sign(mu_max, c[2])) {
      SubsimplexSolutionT<T> inside = weighted<3>(y, {i, j, k}, c, mu_max);
      refine_triangle_point(inside, y);
      return inside;
    }
    // The origin's projection is beyond the edges opposite the failing vertices.
    SubsimplexSolutionT<T> best;
    if (!same_sign(mu_max, c[0])) best = nearer(best, s1d(y, j, k));
    if (!same_sign(mu_max, c[1])) best = nearer(best, s1d(y, i, k));
    if (!same_sign(mu_max, c[2])) best = nearer(best, s1d(y, i, j));
    return best;
  }
  // Degenerate (collinear or NaN): the hull is the union of the edges.
  SubsimplexSolutionT<T> best = s1d(y, j, k);
  best = nearer(best, s1d(y, i, k));
  return nearer(best, s1d(y, i, j));
}

/// det[p q r] for columns p, q, r.
template <class T>
T det3(const Vec3T<T>& p, const Vec3T<T>& q, const Vec3T<T>& r) {
  return p.dot(q.cross(r));
}

/// S3D: tetrahedron y_0 … y_3.
template <class T>
SubsimplexSolutionT<T> s3d(const std::array<Vec3T<T>, 4>& y) {
  // Cofactors of the last row of M = [y_0 y_1 y_2 y_3; 1 1 1 1] and det M = their sum.
  const std::array<T, 4> c = {-det3(y[1], y[2], y[3]), det3(y[0], y[2], y[3]),
                              -det3(y[0], y[1], y[3]), det3(y[0], y[1], y[2])};
  const T det_m = c[0] + c[1] + c[2] + c[3];
  bool inside = true;
  for (T cj : c)
    inside = inside && same_sign(det_m, cj);
  if (inside) return weighted<4>(y, {0, 1, 2, 3}, c, det_m);
  // Faces opposite the failing vertices (all four when det M = 0: a flat tetrahedron's hull
  // is the union of its faces).
  static constexpr std::array<std::array<int, 3>, 4> kFaceOpposite = {
      {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}};
  SubsimplexSolutionT<T> best;
  for (int j = 0; j < 4; ++j) {
    if (same_sign(det_m, c[j])) continue;
    const auto& f = kFaceOpposite[j];
    best = nearer(best, s2d(y, f[0], f[1], f[2]));
  }
  return best;
}

}  // namespace

template <class T>
SubsimplexSolutionT<T> signed_volumes_closest_point(const std::array<Vec3T<T>, 4>& y, int count) {
  switch (count) {
    case 1:
      return single_point(y, 0);
    case 2:
      return s1d(y, 0, 1);
    case 3:
      return s2d(y, 0, 1, 2);
    case 4:
      return s3d(y);
  }
  return {};
}

template SubsimplexSolutionT<float> signed_volumes_closest_point(const std::array<Vec3T<float>, 4>&,
                                                                 int);
template SubsimplexSolutionT<double> signed_volumes_closest_point(
    const std::array<Vec3T<double>, 4>&, int);
template SubsimplexSolutionT<long double> signed_volumes_closest_point(
    const std::array<Vec3T<long double>, 4>&, int);

}  // namespace gjklab
