#include "exact/mesh/triangle_tree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gjklab::exact::mesh {

namespace {

/// The unit roundoff of double: |fl(x ∘ y) − x ∘ y| ≤ u·|x ∘ y| without underflow.
constexpr double u = std::numeric_limits<double>::epsilon() / 2;
/// Below this a gap is taken as 0: its square could be subnormal, where relative error bounds
/// fail (length units; any smaller bound is still a lower bound).
constexpr double kTinyGap = 1e-150;

/// A proven lower bound from a computed squared sum of n rounded terms: each term and the sum
/// lose at most a factor (1 + u) per operation, and (1 − 8u) covers the few operations here.
double lower_from_computed(double value) {
  return std::isfinite(value) && value > 0 ? value * (1 - 8 * u) : 0.0;
}

Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

/// The point of triangle t nearest to p (by regions of the triangle's plane, in double).
Vec3 closest_on_triangle(const Vec3& p, const Triangle& t) {
  const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
  const double n2 = n.squaredNorm();
  if (n2 > 0) {
    const Vec3 q = p - (p - t[0]).dot(n) / n2 * n;  // projection on the plane
    bool inside = true;
    for (int i = 0; i < 3; ++i)
      inside = inside && (t[(i + 1) % 3] - t[i]).cross(q - t[i]).dot(n) >= 0;
    if (inside) return q;
  }
  Vec3 best = closest_on_segment(p, t[0], t[1]);
  for (int i = 1; i < 3; ++i) {
    const Vec3 c = closest_on_segment(p, t[i], t[(i + 1) % 3]);
    if ((c - p).squaredNorm() < (best - p).squaredNorm()) best = c;
  }
  return best;
}

/// Closest points of segments [p1, q1] and [p2, q2] (clamped parameters, in double).
std::pair<Vec3, Vec3> closest_of_segments(const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                          const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a > 0 && e > 0) {
    const double b = d1.dot(d2), c = d1.dot(r), denom = a * e - b * b;
    s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
    t = (b * s + f) / e;
    if (t < 0) {
      t = 0;
      s = std::clamp(-c / a, 0.0, 1.0);
    } else if (t > 1) {
      t = 1;
      s = std::clamp((b - c) / a, 0.0, 1.0);
    }
  } else if (a > 0) {
    s = std::clamp(-d1.dot(r) / a, 0.0, 1.0);
  } else if (e > 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  }
  return {p1 + s * d1, p2 + t * d2};
}

/// n·x rounded up (or down, for sign −1) past the rounding of the dot product and the sum:
/// |fl(n·x) − n·x| ≤ γ₃·Σ|nᵢxᵢ| with γ₃ < 3.01u, and 8u·fl(Σ|nᵢxᵢ|) covers it and the addition.
double dot_bound(const Vec3& n, const Vec3& x, double sign) {
  const double dot = n.dot(x);
  const double size = std::abs(n.x() * x.x()) + std::abs(n.y() * x.y()) + std::abs(n.z() * x.z());
  return dot + sign * 8 * u * size;
}

}  // namespace

bool boxes_overlap(const Box& a, const Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

double box_gap_squared_lower(const Box& a, const Box& b) {
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, b.lo[k] - a.hi[k], a.lo[k] - b.hi[k]});
    if (gap > kTinyGap) sum += gap * gap;
  }
  return lower_from_computed(sum);
}

ApproxClosest approximate_closest(const Triangle& a, const Triangle& b) {
  ApproxClosest best{a[0], b[0], std::numeric_limits<double>::infinity()};
  auto consider = [&](const Vec3& on_a, const Vec3& on_b) {
    const double d2 = (on_b - on_a).squaredNorm();
    if (d2 < best.distance_squared) best = {on_a, on_b, d2};
  };
  for (const Vec3& p : a)
    consider(p, closest_on_triangle(p, b));
  for (const Vec3& q : b)
    consider(closest_on_triangle(q, a), q);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const auto [on_a, on_b] = closest_of_segments(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]);
      consider(on_a, on_b);
    }
  return best;
}

double direction_gap_squared_lower(const Triangle& a, const Triangle& b, const Vec3& n) {
  const double nn = n.squaredNorm();
  if (!(nn > 1e-290) || !std::isfinite(nn)) return 0.0;
  double a_high = -std::numeric_limits<double>::infinity();
  double b_low = std::numeric_limits<double>::infinity();
  for (const Vec3& x : a)
    a_high = std::max(a_high, dot_bound(n, x, +1));
  for (const Vec3& y : b)
    b_low = std::min(b_low, dot_bound(n, y, -1));
  const double gap = b_low - a_high;  // true gap ≥ gap·(1 − u) when positive
  if (!(gap > kTinyGap)) return 0.0;
  // (gap(1 − u))² / (|n|²(1 + 3.01u)), with two more roundings: within (1 − 8u) of the quotient.
  return lower_from_computed(gap * gap / nn);
}

bool split_a(const TriangleTree::Node& a, const TriangleTree::Node& b) {
  if (a.leaf()) return false;
  if (b.leaf()) return true;
  return (a.box.hi - a.box.lo).sum() >= (b.box.hi - b.box.lo).sum();
}

TriangleTree::TriangleTree(const MeshView& mesh) : mesh_(mesh) {
  face_boxes_.reserve(mesh.faces.size());
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle t = triangle(f);
    face_boxes_.push_back({t[0].cwiseMin(t[1]).cwiseMin(t[2]), t[0].cwiseMax(t[1]).cwiseMax(t[2])});
    order_.push_back(f);
  }
  nodes_.reserve(2 * mesh.faces.size() / kLeafSize + 2);
  build(0, static_cast<std::uint32_t>(order_.size()));
}

Triangle TriangleTree::triangle(std::uint32_t face) const {
  const auto& f = mesh_.faces[face];
  return {mesh_.vertices[f[0]], mesh_.vertices[f[1]], mesh_.vertices[f[2]]};
}

std::uint32_t TriangleTree::build(std::uint32_t first, std::uint32_t count) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Box box = face_boxes_[order_[first]];
  for (std::uint32_t i = first; i < first + count; ++i) {
    box.lo = box.lo.cwiseMin(face_boxes_[order_[i]].lo);
    box.hi = box.hi.cwiseMax(face_boxes_[order_[i]].hi);
  }
  nodes_[index].box = box;
  if (count <= kLeafSize) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  int axis = 0;
  (box.hi - box.lo).maxCoeff(&axis);
  const auto middle = order_.begin() + first + count / 2;
  std::nth_element(order_.begin() + first, middle, order_.begin() + first + count,
                   [&](std::uint32_t x, std::uint32_t y) {
                     return face_boxes_[x].lo[axis] + face_boxes_[x].hi[axis] <
                            face_boxes_[y].lo[axis] + face_boxes_[y].hi[axis];
                   });
  const std::uint32_t left = build(first, count / 2);
  const std::uint32_t right = build(first + count / 2, count - count / 2);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

}  // namespace gjklab::exact::mesh
