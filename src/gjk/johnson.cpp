#include "gjklab/gjk/johnson.hpp"

#include <bit>

#include "gjklab/gjk/subsimplex.hpp"

namespace gjklab {

namespace {

/// The 15 non-empty subsets of {0,1,2,3}, ordered by size and then by mask value: the order
/// in which Johnson's sub-algorithm tries them.
constexpr std::array<std::uint8_t, 15> kSubsetsBySize = {1,  2,  4, 8,  3,  5,  6, 9,
                                                         10, 12, 7, 11, 13, 14, 15};

constexpr int first_index(std::uint8_t mask) {
  return std::countr_zero(static_cast<unsigned>(mask));
}

// The functions below are written once for each simplex size N (a template parameter), so
// that every subset test and loop bound is a compile-time constant: the compiler unrolls the
// whole recursion into straight-line arithmetic. Each cofactor is still computed with the same
// operations in the same order as the recursion above states it (differences first, then the
// sum over i ∈ X' in increasing i), so the results are bit for bit those of the generic loop
// (up to the sign of a zero sum, see below).

/// Cofactor storage without zero-initialisation, for closest_point: it reads only entries that
/// fill_cofactors wrote (Δ_i(X) with i ∈ X ⊆ {0 … N−1}).
template <class T>
struct UninitialisedCofactors {
  T delta[16][4];
  T total[16];
};

// Each cofactor sum (and Δ(X)) starts from its first term instead of 0 + it. The two differ
// only in the sign of a zero sum (0 + (−0) is +0), and no answer depends on that sign: the
// tests compare cofactors with 0, the weights divide positive ones, and a zero of either sign
// times anything finite stays zero in every sum it enters. It saves one add per cofactor.

template <int N, class T, class Cofactors>
[[gnu::always_inline]] inline void fill_cofactors(const std::array<Vec3T<T>, 4>& y, Cofactors& c) {
  constexpr std::uint8_t all = static_cast<std::uint8_t>((1u << N) - 1);
#pragma GCC unroll 16
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x) continue;
    if (std::popcount(static_cast<unsigned>(x)) == 1) {
      c.delta[x][first_index(x)] = T(1);
      c.total[x] = T(1);
      continue;
    }
    // Build Δ_j(X) from the subset X' = X \ {j} for each j ∈ X. X' has one point fewer and
    // was filled earlier because the order is by size.
    T total = 0;
#pragma GCC unroll 4
    for (int j = 0; j < N; ++j) {
      if (!(x & (1u << j))) continue;
      const std::uint8_t rest = static_cast<std::uint8_t>(x & ~(1u << j));
      const int k = first_index(rest);
      const Vec3T<T> edge = y[k] - y[j];  // differences first: better than subtracting dot products
      // The sum starts from its first term, not from 0 + it (see the note above).
      T dj = c.delta[rest][k] * edge.dot(y[k]);
#pragma GCC unroll 4
      for (int i = k + 1; i < N; ++i)
        if (rest & (1u << i)) dj += c.delta[rest][i] * edge.dot(y[i]);
      c.delta[x][j] = dj;
      total = j == first_index(x) ? dj : total + dj;
    }
    c.total[x] = total;
  }
}

template <int N, class Cofactors>
[[gnu::always_inline]] inline bool subset_is_valid(const Cofactors& c, std::uint8_t subset) {
  if (!(c.total[subset] > 0)) return false;  // also rejects NaN
#pragma GCC unroll 4
  for (int i = 0; i < N; ++i) {
    const bool inside = subset & (1u << i);
    if (inside && !(c.delta[subset][i] > 0)) return false;
    if (!inside && !(c.delta[subset | (1u << i)][i] <= 0)) return false;
  }
  return true;
}

template <int N, class T>
JohnsonSolutionT<T> closest_point(const std::array<Vec3T<T>, 4>& y) {
  UninitialisedCofactors<T> c;
  fill_cofactors<N, T>(y, c);
  constexpr std::uint8_t all = static_cast<std::uint8_t>((1u << N) - 1);
  JohnsonSolutionT<T> s;
#pragma GCC unroll 16
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x || !subset_is_valid<N>(c, x)) continue;
    s.found = true;
    s.subset = x;
#pragma GCC unroll 4
    for (int i = 0; i < N; ++i) {
      if (!(x & (1u << i))) continue;
      s.weights[i] = c.delta[x][i] / c.total[x];
      s.closest += s.weights[i] * y[i];
    }
    refine_triangle_point(s, y);
    return s;
  }
  return s;
}

}  // namespace

template <class T>
JohnsonCofactorsT<T> johnson_cofactors(const std::array<Vec3T<T>, 4>& y, int count) {
  JohnsonCofactorsT<T> c;
  switch (count) {
    case 1:
      fill_cofactors<1, T>(y, c);
      break;
    case 2:
      fill_cofactors<2, T>(y, c);
      break;
    case 3:
      fill_cofactors<3, T>(y, c);
      break;
    case 4:
      fill_cofactors<4, T>(y, c);
      break;
    default:
      break;  // no points: no subsets
  }
  return c;
}

template <class T>
bool johnson_subset_is_valid(const JohnsonCofactorsT<T>& c, std::uint8_t subset, int count) {
  switch (count) {
    case 1:
      return subset_is_valid<1>(c, subset);
    case 2:
      return subset_is_valid<2>(c, subset);
    case 3:
      return subset_is_valid<3>(c, subset);
    case 4:
      return subset_is_valid<4>(c, subset);
    default:
      return subset_is_valid<0>(c, subset);
  }
}

template <class T>
JohnsonSolutionT<T> johnson_closest_point(const std::array<Vec3T<T>, 4>& y, int count) {
  switch (count) {
    case 1:
      return closest_point<1, T>(y);
    case 2:
      return closest_point<2, T>(y);
    case 3:
      return closest_point<3, T>(y);
    case 4:
      return closest_point<4, T>(y);
    default:
      return {};  // no points: nothing found
  }
}

namespace {

/// The solution for subset X: λ_i = Δ_i(X)/Δ(X) and v = Σ λ_i y_i.
template <class T>
JohnsonSolutionT<T> solution_of(const JohnsonCofactorsT<T>& c, const std::array<Vec3T<T>, 4>& y,
                                int count, std::uint8_t x) {
  JohnsonSolutionT<T> s;
  s.found = true;
  s.subset = x;
  for (int i = 0; i < count; ++i) {
    if (!(x & (1u << i))) continue;
    s.weights[i] = c.delta[x][i] / c.total[x];
    s.closest += s.weights[i] * y[i];
  }
  refine_triangle_point(s, y);
  return s;
}

}  // namespace

template <class T>
bool johnson_subset_has_positive_cofactors(const JohnsonCofactorsT<T>& c, std::uint8_t subset,
                                           int count) {
  if (!(c.total[subset] > 0)) return false;
  for (int i = 0; i < count; ++i)
    if ((subset & (1u << i)) && !(c.delta[subset][i] > 0)) return false;
  return true;
}

template <class T>
JohnsonSolutionT<T> johnson_closest_point_with_backup(const std::array<Vec3T<T>, 4>& y, int count,
                                                      bool* used_backup) {
  const JohnsonCofactorsT<T> c = johnson_cofactors(y, count);
  const std::uint8_t all = static_cast<std::uint8_t>((1u << count) - 1);
  if (used_backup) *used_backup = false;
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x || !johnson_subset_is_valid(c, x, count)) continue;
    return solution_of(c, y, count, x);
  }
  // Backup procedure: every subset whose affine closest point lies inside its hull by the
  // cofactors' signs is a candidate; the one whose point is nearest the origin wins.
  if (used_backup) *used_backup = true;
  JohnsonSolutionT<T> best;
  T best_norm = 0;
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x || !johnson_subset_has_positive_cofactors(c, x, count)) continue;
    const JohnsonSolutionT<T> candidate = solution_of(c, y, count, x);
    const T norm = candidate.closest.squaredNorm();
    if (!best.found || norm < best_norm) best = candidate, best_norm = norm;
  }
  return best;
}

#define GJKLAB_JOHNSON_FOR(T)                                                                    \
  template JohnsonCofactorsT<T> johnson_cofactors(const std::array<Vec3T<T>, 4>&, int);          \
  template bool johnson_subset_is_valid(const JohnsonCofactorsT<T>&, std::uint8_t, int);         \
  template bool johnson_subset_has_positive_cofactors(const JohnsonCofactorsT<T>&, std::uint8_t, \
                                                      int);                                      \
  template JohnsonSolutionT<T> johnson_closest_point(const std::array<Vec3T<T>, 4>&, int);       \
  template JohnsonSolutionT<T> johnson_closest_point_with_backup(const std::array<Vec3T<T>, 4>&, \
                                                                 int, bool*);
GJKLAB_JOHNSON_FOR(float)
GJKLAB_JOHNSON_FOR(double)
GJKLAB_JOHNSON_FOR(long double)
#undef GJKLAB_JOHNSON_FOR

}  // namespace gjklab
