// The sub-algorithm of a GJK distance query: the contract (SubAlgorithm), the closest point
// of a simplex it reduces to, and the two sub-algorithms every query can use: Johnson's as
// published and the double-word solve a query continues with (see gjk_distance.hpp).
#pragma once

#include <array>
#include <concepts>

#include "gjklab/gjk/johnson.hpp"
#include "gjklab/gjk/precise_subsimplex.hpp"
#include "gjklab/gjk/simplex.hpp"

namespace gjklab {

/// The point of a simplex closest to the origin, with the matching points of A and B and the
/// barycentric weights of the (reduced) simplex points.
template <class T>
struct ClosestOnSimplexT {
  Vec3T<T> v = Vec3T<T>::Zero();
  Vec3T<T> witness_a = Vec3T<T>::Zero();
  Vec3T<T> witness_b = Vec3T<T>::Zero();
  std::array<T, 4> weights{};
};
using ClosestOnSimplex = ClosestOnSimplexT<double>;

/// A distance sub-algorithm: reduces the simplex to the sub-simplex whose convex hull holds
/// the point closest to the origin, and computes that point. Returns false, leaving the
/// simplex untouched, when it cannot decide (a degenerate simplex).
///
/// `solve` is the same computation without applying it: for the points y[0 … count−1] it
/// returns {found, subset (bitmask), weights (by point index), closest}, so that the driver
/// can test the answer before it changes its simplex.
template <class S>
concept SubAlgorithm = requires(const S& s, Simplex& simplex, ClosestOnSimplex& out,
                                const std::array<Vec3, 4>& y, int count) {
  { s.reduce(simplex, out) } -> std::same_as<bool>;
  { s.solve(y, count).found } -> std::convertible_to<bool>;
  { s.solve(y, count).subset } -> std::convertible_to<std::uint8_t>;
  { s.solve(y, count).weights } -> std::convertible_to<std::array<double, 4>>;
  { s.solve(y, count).closest } -> std::convertible_to<Vec3>;
};

namespace detail {

/// The witness points of the simplex's closest point: Σ λ_k a_k and Σ λ_k b_k over the kept
/// points, in order. The loops keep only v and the weights and form the witnesses once, at the
/// end.
template <class T>
void combine_witnesses(const SimplexT<T>& simplex, const std::array<T, 4>& weights,
                       Vec3T<T>& witness_a, Vec3T<T>& witness_b) {
  Vec3T<T> wa = Vec3T<T>::Zero(), wb = Vec3T<T>::Zero();
  for (int k = 0; k < simplex.size(); ++k) {
    wa += weights[k] * simplex[k].a;
    wb += weights[k] * simplex[k].b;
  }
  witness_a = wa;
  witness_b = wb;
}

/// Keeps the subset a sub-algorithm's solution chose and records v and the kept points'
/// weights, in order, in `out` (its witnesses are left alone).
template <class Solution, class T>
void keep_subset(const Solution& s, SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) {
  std::array<T, 4> weights{};
  int kept = 0;
  for (int i = 0; i < simplex.size(); ++i)
    if (s.subset & (1u << i)) weights[kept++] = s.weights[i];
  simplex.keep(s.subset);
  out.v = s.closest;
  out.weights = weights;
}

/// Applies a sub-algorithm's answer (subset, weights by original index, closest point) to the
/// simplex and the closest-point record, witnesses included. False, leaving both untouched, if
/// nothing was found.
template <class Solution, class T>
bool keep_solution(const Solution& s, SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) {
  if (!s.found) return false;
  keep_subset(s, simplex, out);
  combine_witnesses(simplex, out.weights, out.witness_a, out.witness_b);
  return true;
}

}  // namespace detail

/// Johnson's distance sub-algorithm (see johnson.hpp), as published: no backup procedure.
struct JohnsonSubAlgorithm {
  template <class T>
  JohnsonSolutionT<T> solve(const std::array<Vec3T<T>, 4>& y, int count) const {
    return johnson_closest_point(y, count);
  }
  template <class T>
  bool reduce(SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) const {
    return detail::keep_solution(solve(simplex.points(), simplex.size()), simplex, out);
  }
};

/// The sub-simplex solve in double-word arithmetic (precise_subsimplex.hpp): what a query
/// continues with when its own sub-algorithm's answer could not be proven (see
/// gjk_distance_run_as_given). Not a registered algorithm of its own.
struct PreciseSubAlgorithm {
  template <class T>
  SubsimplexSolutionT<T> solve(const std::array<Vec3T<T>, 4>& y, int count) const {
    return precise_closest_point(y, count);
  }
  template <class T>
  bool reduce(SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) const {
    return detail::keep_solution(solve(simplex.points(), simplex.size()), simplex, out);
  }
};

}  // namespace gjklab
