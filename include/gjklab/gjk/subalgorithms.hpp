// The distance sub-algorithms as interchangeable policies of the one GJK distance driver
// (gjk_distance_with<Sub>), and the queries that use them:
//
//   gjk-johnson          JohnsonSubAlgorithm          (gjk_distance.hpp; johnson.hpp)
//   gjk-johnson-backup   JohnsonBackupSubAlgorithm    (johnson.hpp: van den Bergen's backup)
//   gjk-sv               SignedVolumesSubAlgorithm    (signed_volumes.hpp: Montanari et al.)
//   gjk-voronoi          VoronoiSubAlgorithm          (voronoi.hpp: Ericson's region tests)
//
// Each policy reduces the simplex to the sub-simplex holding its point closest to the origin,
// keeping the points in order, and fills v, the witnesses and the barycentric weights of the
// kept points in that order.
#pragma once

#include <array>

#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/johnson.hpp"
#include "gjklab/gjk/signed_volumes.hpp"
#include "gjklab/gjk/voronoi.hpp"

namespace gjklab {

/// Johnson's sub-algorithm with van den Bergen's backup procedure (see
/// johnson_closest_point_with_backup): never undecided for finite points.
struct JohnsonBackupSubAlgorithm {
  template <class T>
  auto solve(const std::array<Vec3T<T>, 4>& y, int count) const {
    return johnson_closest_point_with_backup(y, count);
  }
  template <class T>
  bool reduce(SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) const {
    return detail::keep_solution(solve(simplex.points(), simplex.size()), simplex, out);
  }
};

/// The signed-volumes sub-algorithm of Montanari, Petrinic and Barbieri (2017).
struct SignedVolumesSubAlgorithm {
  template <class T>
  auto solve(const std::array<Vec3T<T>, 4>& y, int count) const {
    return signed_volumes_closest_point(y, count);
  }
  template <class T>
  bool reduce(SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) const {
    return detail::keep_solution(solve(simplex.points(), simplex.size()), simplex, out);
  }
};

/// The Voronoi-region case analysis (Ericson, Real-Time Collision Detection, ch. 5).
struct VoronoiSubAlgorithm {
  template <class T>
  auto solve(const std::array<Vec3T<T>, 4>& y, int count) const {
    return voronoi_closest_point(y, count);
  }
  template <class T>
  bool reduce(SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) const {
    return detail::keep_solution(solve(simplex.points(), simplex.size()), simplex, out);
  }
};

static_assert(SubAlgorithm<JohnsonSubAlgorithm>);
static_assert(SubAlgorithm<JohnsonBackupSubAlgorithm>);
static_assert(SubAlgorithm<SignedVolumesSubAlgorithm>);
static_assert(SubAlgorithm<VoronoiSubAlgorithm>);

}  // namespace gjklab
