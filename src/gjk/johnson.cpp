#include "gjklab/gjk/johnson.hpp"

#include <bit>

namespace gjklab {

namespace {

/// The 15 non-empty subsets of {0,1,2,3}, ordered by size and then by mask value: the order
/// in which Johnson's sub-algorithm tries them.
constexpr std::array<std::uint8_t, 15> kSubsetsBySize = {1, 2, 4, 8, 3, 5, 6, 9, 10, 12,
                                                         7, 11, 13, 14, 15};

int first_index(std::uint8_t mask) { return std::countr_zero(static_cast<unsigned>(mask)); }

}  // namespace

JohnsonCofactors johnson_cofactors(const std::array<Vec3, 4>& y, int count) {
  JohnsonCofactors c;
  const std::uint8_t all = static_cast<std::uint8_t>((1u << count) - 1);
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x) continue;
    if (std::popcount(static_cast<unsigned>(x)) == 1) {
      c.delta[x][first_index(x)] = 1.0;
      c.total[x] = 1.0;
      continue;
    }
    // Build Δ_j(X) from the subset X' = X \ {j} for each j ∈ X. X' has one point fewer and
    // was filled earlier because the order is by size.
    double total = 0;
    for (int j = 0; j < count; ++j) {
      if (!(x & (1u << j))) continue;
      const std::uint8_t rest = static_cast<std::uint8_t>(x & ~(1u << j));
      const int k = first_index(rest);
      const Vec3 edge = y[k] - y[j];  // differences first: better than subtracting dot products
      double dj = 0;
      for (int i = 0; i < count; ++i)
        if (rest & (1u << i)) dj += c.delta[rest][i] * edge.dot(y[i]);
      c.delta[x][j] = dj;
      total += dj;
    }
    c.total[x] = total;
  }
  return c;
}

bool johnson_subset_is_valid(const JohnsonCofactors& c, std::uint8_t subset, int count) {
  if (!(c.total[subset] > 0)) return false;  // also rejects NaN
  for (int i = 0; i < count; ++i) {
    const bool inside = subset & (1u << i);
    if (inside && !(c.delta[subset][i] > 0)) return false;
    if (!inside && !(c.delta[subset | (1u << i)][i] <= 0)) return false;
  }
  return true;
}

namespace {

/// The solution for subset X: λ_i = Δ_i(X)/Δ(X) and v = Σ λ_i y_i.
JohnsonSolution solution_of(const JohnsonCofactors& c, const std::array<Vec3, 4>& y, int count,
                            std::uint8_t x) {
  JohnsonSolution s;
  s.found = true;
  s.subset = x;
  for (int i = 0; i < count; ++i) {
    if (!(x & (1u << i))) continue;
    s.weights[i] = c.delta[x][i] / c.total[x];
    s.closest += s.weights[i] * y[i];
  }
  return s;
}

}  // namespace

bool johnson_subset_has_positive_cofactors(const JohnsonCofactors& c, std::uint8_t subset,
                                           int count) {
  if (!(c.total[subset] > 0)) return false;
  for (int i = 0; i < count; ++i)
    if ((subset & (1u << i)) && !(c.delta[subset][i] > 0)) return false;
  return true;
}

JohnsonSolution johnson_closest_point(const std::array<Vec3, 4>& y, int count) {
  const JohnsonCofactors c = johnson_cofactors(y, count);
  const std::uint8_t all = static_cast<std::uint8_t>((1u << count) - 1);
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x || !johnson_subset_is_valid(c, x, count)) continue;
    return solution_of(c, y, count, x);
  }
  return {};
}

JohnsonSolution johnson_closest_point_with_backup(const std::array<Vec3, 4>& y, int count,
                                                  bool* used_backup) {
  const JohnsonCofactors c = johnson_cofactors(y, count);
  const std::uint8_t all = static_cast<std::uint8_t>((1u << count) - 1);
  if (used_backup) *used_backup = false;
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x || !johnson_subset_is_valid(c, x, count)) continue;
    return solution_of(c, y, count, x);
  }
  // Backup procedure: every subset whose affine closest point lies inside its hull by the
  // cofactors' signs is a candidate; the one whose point is nearest the origin wins.
  if (used_backup) *used_backup = true;
  JohnsonSolution best;
  double best_norm = 0;
  for (std::uint8_t x : kSubsetsBySize) {
    if ((x & all) != x || !johnson_subset_has_positive_cofactors(c, x, count)) continue;
    const JohnsonSolution candidate = solution_of(c, y, count, x);
    const double norm = candidate.closest.squaredNorm();
    if (!best.found || norm < best_norm) best = candidate, best_norm = norm;
  }
  return best;
}

}  // namespace gjklab
