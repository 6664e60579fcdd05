// Seeded random inputs shared by the micro-benchmarks.
#pragma once

#include <random>

#include "gjklab/geometry/types.hpp"

namespace gjklab::bench {

/// A uniformly distributed unit vector (normalised Gaussian).
inline Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  for (;;) {
    const Vec3 g(normal(rng), normal(rng), normal(rng));
    if (g.norm() > 1e-9) return g.normalized();
  }
}

}  // namespace gjklab::bench
