// Exact re-centring of a pair of shapes far from the origin.
//
// GJK compares support values d·x. For shapes of size s placed at distance M ≫ s from the
// origin, each d·x is rounded at the magnitude of M (|error| ≤ 3u‖d‖M, u = 2^-53): vertices
// whose support values differ by less than that are confused, and the answer's error grows to
// the order of u·M instead of u·s. Translating both shapes by the same vector leaves every
// distance, depth and intersection unchanged; done exactly, it leaves the clouds themselves
// unchanged too, only nearer the origin, where support values are compared at the scale of
// the pair.
//
// The rule, per axis i, on the bounding box [lo, hi] of both clouds: t_i = lo when
// 0 < lo and hi ≤ 2·lo; t_i = hi when hi < 0 and lo ≥ 2·hi; else t_i = 0. Every coordinate x
// of that axis then satisfies t_i/2 ≤ x ≤ 2·t_i (mirrored for t_i < 0), so x − t_i is exact
// (Sterbenz's lemma) and the translated cloud is the same set of points, moved by −t. The
// translation is used only where it brings the largest |coordinate| of the pair down by a
// factor of 8 or more (three bits): pairs near the origin are left alone, so their queries
// run on the very same doubles as without it.
#pragma once

#include <algorithm>
#include <optional>
#include <type_traits>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

namespace detail {

/// The exact translation of one axis whose coordinates all lie in [lo, hi] (see the file
/// comment): lo or hi when Sterbenz's lemma applies to every coordinate, else 0.
template <class T>
T exact_axis_shift(T lo, T hi) {
  if (lo > 0 && hi <= 2 * lo) return lo;
  if (hi < 0 && lo >= 2 * hi) return hi;
  return 0;
}

/// Largest |coordinate| of a box, after moving it by −t.
template <class T>
T largest_magnitude(const Vec3T<T>& lo, const Vec3T<T>& hi, const Vec3T<T>& t) {
  return std::max((lo - t).cwiseAbs().maxCoeff(), (hi - t).cwiseAbs().maxCoeff());
}

}  // namespace detail

/// The translation t to subtract from both clouds (exactly, see the file comment), or nullopt
/// when the pair is near the origin already (t would gain less than three bits). Cloud: a
/// Polytope, or a ScalarCloud<T> (the rule holds in any binary floating-point type).
template <class Cloud>
auto exact_recentring(const Cloud& a, const Cloud& b)
    -> std::optional<std::remove_cvref_t<decltype(a.box_lower())>> {
  using Point = std::remove_cvref_t<decltype(a.box_lower())>;
  const Point lo = a.box_lower().cwiseMin(b.box_lower());
  const Point hi = a.box_upper().cwiseMax(b.box_upper());
  Point t;
  for (int i = 0; i < 3; ++i)
    t[i] = detail::exact_axis_shift(lo[i], hi[i]);
  // Three bits or more: the translated box is at most 1/8 of the original's magnitude.
  if (!(detail::largest_magnitude(lo, hi, t) * 8 <=
        detail::largest_magnitude<typename Point::Scalar>(lo, hi, Point::Zero())))
    return std::nullopt;
  return t;
}

}  // namespace gjklab
