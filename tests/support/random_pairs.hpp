// Seeded random point-cloud pairs for property tests, drawn from the library's seeded stream
// (experiment/seeded_random.hpp: std::mt19937_64 with its own conversions, so a seed gives
// the same pairs with every standard library).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "gjklab/experiment/cases/seeded_random.hpp"
#include "gjklab/geometry/polytope.hpp"

namespace gjklab::testing {

using Rng = experiment::SeededRandom;

enum class CloudKind { sphere, cube };

inline std::vector<Vec3> random_cloud(Rng& rng, CloudKind kind, int n) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    if (kind == CloudKind::sphere) {
      pts.push_back(rng.unit_vector());
    } else {
      pts.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    }
  }
  return pts;
}

struct RandomPair {
  std::vector<Vec3> a, b;
  double intended_gap;  ///< along the placement axis, relative to size; < 0 means overlap
};

/// A and B with B moved along a random axis u so that their extents along u are separated by
/// gap · size (overlapping when gap < 0). The true distance is what the oracle says.
inline RandomPair random_pair(Rng& rng, CloudKind kind, int na, int nb, double gap) {
  RandomPair p{random_cloud(rng, kind, na), random_cloud(rng, kind, nb), gap};
  const Vec3 u = rng.unit_vector();
  const double size = pair_size(p.a, p.b);
  const Vec3 shift = experiment::separating_shift(p.a, p.b, u, gap * size) * u;
  for (Vec3& v : p.b)
    v += shift;
  return p;
}

}  // namespace gjklab::testing
