// Every Voronoi region of the segment, triangle and tetrahedron sub-problems, for testing the
// distance sub-algorithms.
//
// The simplex is the corner tetrahedron 0, e1, e2, e3 (or its first 1–3 points) in every
// order of its points; for each feature F (a non-empty subset of the points) the simplex is
// moved by −(p + n), with p the centroid of F and n a small integer vector in F's normal cone.
// The origin then lies in F's Voronoi region, and the closest point of the moved simplex to
// the origin is −n, in the relative interior of F.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::testing {

/// The corner tetrahedron 0, e1, e2, e3: every region's normal cone is easy to enumerate.
inline const std::array<Vec3, 4> kCornerTetrahedron = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                                                       Vec3(0, 0, 1)};

inline Vec3 feature_centroid(const std::array<Vec3, 4>& y, int count, unsigned feature) {
  Vec3 p = Vec3::Zero();
  int n = 0;
  for (int i = 0; i < count; ++i)
    if (feature & (1u << i)) p += y[i], ++n;
  return p / n;
}

/// Directions n with n ⊥ aff(F) and n·(y_j − p) < 0 for every j ∉ F: offsetting the origin
/// by p + n puts it in the Voronoi region of feature F (p = centroid of F).
inline std::vector<Vec3> normal_cone_samples(const std::array<Vec3, 4>& y, int count,
                                             unsigned feature) {
  const Vec3 p = feature_centroid(y, count, feature);
  std::vector<Vec3> out;
  for (int x = -2; x <= 2; ++x)
    for (int yy = -2; yy <= 2; ++yy)
      for (int z = -2; z <= 2; ++z) {
        const Vec3 n(x, yy, z);
        bool ok = true;
        for (int i = 0; i < count && ok; ++i) {
          const double along = n.dot(y[i] - p);
          ok = (feature & (1u << i)) ? along == 0 : along < 0;
        }
        // Zero offset only for the full tetrahedron (origin strictly inside).
        if (ok && (n != Vec3::Zero() || (count == 4 && feature == 15u))) out.push_back(n);
      }
  return out;
}

/// One region case: the moved simplex y[0 … count−1], the feature whose region holds the
/// origin (bit i ↔ y_i) and the expected closest point.
struct RegionCase {
  std::array<Vec3, 4> y;
  int count = 0;
  unsigned feature = 0;
  Vec3 closest = Vec3::Zero();
};

/// Calls f(const RegionCase&) for every region of every point order of the 1-, 2-, 3- and
/// 4-point simplices (several offsets per region).
template <class F>
void for_each_region_case(F&& f) {
  for (int count = 1; count <= 4; ++count) {
    std::array<int, 4> order{0, 1, 2, 3};
    do {
      std::array<Vec3, 4> y;
      for (int i = 0; i < count; ++i)
        y[i] = kCornerTetrahedron[order[i]];
      for (unsigned feature = 1; feature < (1u << count); ++feature) {
        const Vec3 p = feature_centroid(y, count, feature);
        for (const Vec3& n : normal_cone_samples(y, count, feature)) {
          RegionCase c;
          c.count = count;
          c.feature = feature;
          c.closest = -n;
          for (int i = 0; i < count; ++i)
            c.y[i] = y[i] - (p + n);
          f(c);
        }
      }
    } while (std::next_permutation(order.begin(), order.begin() + count));
  }
}

}  // namespace gjklab::testing
