#include "gjklab/geometry/recentring.hpp"

#include <algorithm>
#include <cmath>

namespace gjklab {

namespace {

/// The exact translation of one axis whose coordinates all lie in [lo, hi] (see the file
/// comment of recentring.hpp): lo or hi when Sterbenz's lemma applies to every coordinate,
/// else 0.
double exact_axis_shift(double lo, double hi) {
  if (lo > 0 && hi <= 2 * lo) return lo;
  if (hi < 0 && lo >= 2 * hi) return hi;
  return 0;
}

/// Largest |coordinate| of a box, after moving it by −t.
double largest_magnitude(const Vec3& lo, const Vec3& hi, const Vec3& t) {
  return std::max((lo - t).cwiseAbs().maxCoeff(), (hi - t).cwiseAbs().maxCoeff());
}

}  // namespace

std::optional<Vec3> exact_recentring(const Polytope& a, const Polytope& b) {
  const Vec3 lo = a.box_lower().cwiseMin(b.box_lower());
  const Vec3 hi = a.box_upper().cwiseMax(b.box_upper());
  Vec3 t;
  for (int i = 0; i < 3; ++i)
    t[i] = exact_axis_shift(lo[i], hi[i]);
  // Three bits or more: the translated box is at most 1/8 of the original's magnitude.
  if (!(largest_magnitude(lo, hi, t) * 8 <= largest_magnitude(lo, hi, Vec3::Zero())))
    return std::nullopt;
  return t;
}

}  // namespace gjklab
