// Johnson's distance sub-algorithm (Gilbert, Johnson and Keerthi 1988, section 3).
//
// Given a simplex Y = {y_0 … y_{m−1}} (m ≤ 4 points, possibly degenerate), find the point of
// conv(Y) closest to the origin. For every non-empty subset X ⊆ Y the cofactors Δ_i(X) are
// built by the recursion
//   Δ_i({y_i}) = 1,
//   Δ_j(X ∪ {y_j}) = Σ_{i∈X} Δ_i(X) · (y_k − y_j)·y_i      (k: the first index in X),
//   Δ(X) = Σ_{i∈X} Δ_i(X),
// and the answer is the subset X with Δ(X) > 0, Δ_i(X) > 0 for i ∈ X (the closest point of
// aff(X) lies inside conv(X)) and Δ_j(X ∪ {y_j}) ≤ 0 for j ∉ X (no point outside X can
// decrease the distance). In exact arithmetic exactly one subset passes; in double none may,
// which the caller must report (Termination::degenerate_simplex).
#pragma once

#include <array>
#include <cstdint>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// All cofactors of a simplex of up to four points, indexed by subset bitmask (bit i ↔ y_i).
template <class T>
struct JohnsonCofactorsT {
  std::array<std::array<T, 4>, 16> delta{};  ///< delta[X][i] = Δ_i(X) for i ∈ X
  std::array<T, 16> total{};                 ///< total[X] = Δ(X)
};
using JohnsonCofactors = JohnsonCofactorsT<double>;

template <class T>
struct JohnsonSolutionT {
  bool found = false;                   ///< false when no subset passed both tests
  std::uint8_t subset = 0;              ///< bitmask of the chosen sub-simplex X
  std::array<T, 4> weights{};           ///< barycentric weights λ_i = Δ_i(X)/Δ(X); 0 outside X
  Vec3T<T> closest = Vec3T<T>::Zero();  ///< v = Σ λ_i y_i (three: refine_triangle_point)
};
using JohnsonSolution = JohnsonSolutionT<double>;

// Each function is defined for T = float, double and long double (johnson.cpp).

/// Computes every cofactor Δ_i(X) of the simplex y[0 … count−1] (count in 1…4).
template <class T>
JohnsonCofactorsT<T> johnson_cofactors(const std::array<Vec3T<T>, 4>& y, int count);

/// True if subset X passes Johnson's two tests for the simplex of `count` points.
template <class T>
bool johnson_subset_is_valid(const JohnsonCofactorsT<T>& c, std::uint8_t subset, int count);

/// True if every cofactor of subset X is positive: Δ(X) > 0 and Δ_i(X) > 0 for i ∈ X, i.e.
/// the point of aff(X) closest to the origin lies in the relative interior of conv(X).
template <class T>
bool johnson_subset_has_positive_cofactors(const JohnsonCofactorsT<T>& c, std::uint8_t subset,
                                           int count);

/// Johnson's sub-algorithm: tests the subsets in order of increasing size (then increasing
/// mask) and returns the first that passes, with its weights and closest point.
template <class T>
JohnsonSolutionT<T> johnson_closest_point(const std::array<Vec3T<T>, 4>& y, int count);

/// Johnson's sub-algorithm with the backup procedure of van den Bergen ("A fast and robust
/// GJK implementation for collision detection of convex objects", J. Graphics Tools 4(2),
/// 1999, after Gilbert, Johnson and Keerthi 1988): when no subset passes Johnson's two tests,
/// search all subsets X with positive cofactors (johnson_subset_has_positive_cofactors; the
/// singletons always qualify, Δ({y_i}) = 1) and return the one whose affine closest point
/// v(X) = Σ_{i∈X} (Δ_i(X)/Δ(X)) y_i has the smallest ‖v(X)‖², the first in Johnson's order
/// (size, then mask) on ties. Always found for finite points. `used_backup` (optional) tells
/// whether the backup decided.
template <class T>
JohnsonSolutionT<T> johnson_closest_point_with_backup(const std::array<Vec3T<T>, 4>& y, int count,
                                                      bool* used_backup = nullptr);

}  // namespace gjklab
