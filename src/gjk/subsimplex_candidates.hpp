// Candidate answers shared by the sub-algorithms that build a SubsimplexSolutionT region by
// region (signed volumes, Voronoi regions): a single kept point, and the choice between two
// candidates. Private to src/gjk/.
#pragma once

#include <array>
#include <cstdint>

#include "gjklab/gjk/subsimplex.hpp"

namespace gjklab::detail {

/// The answer "y_i alone": weight 1, closest point y_i.
template <class T>
SubsimplexSolutionT<T> single_point(const std::array<Vec3T<T>, 4>& y, int i) {
  SubsimplexSolutionT<T> s;
  s.found = true;
  s.subset = static_cast<std::uint8_t>(1u << i);
  s.weights[i] = 1;
  s.closest = y[i];
  return s;
}

/// The candidate nearer to the origin; the first one on ties (and when the second is NaN).
template <class T>
const SubsimplexSolutionT<T>& nearer(const SubsimplexSolutionT<T>& best,
                                     const SubsimplexSolutionT<T>& c) {
  if (!best.found) return c;
  return c.closest.squaredNorm() < best.closest.squaredNorm() ? c : best;
}

}  // namespace gjklab::detail
