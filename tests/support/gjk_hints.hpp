// The certificates' distance hint from gjk-johnson's final simplex, as the oracle's own
// caller (experiment::solve_certified) builds it.
#pragma once

#include <vector>

#include "gjklab/exact/hint.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

namespace gjklab::testing {

inline exact::DistanceHint gjk_hint(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  const DistanceResult r = gjk_distance(Polytope(a), Polytope(b));
  exact::DistanceHint h;
  for (const SimplexVertex& v : r.simplex.vertices())
    h.simplex.push_back({v.index_a, v.index_b});
  return h;
}

}  // namespace gjklab::testing
