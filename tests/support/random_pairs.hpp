// Seeded random point-cloud pairs for property tests.
//
// Uses std::mt19937_64 (whose output sequence the standard fixes) and our own conversions
// to uniform and Gaussian variates, so a seed gives the same pairs with every standard library.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "gjklab/geometry/polytope.hpp"

namespace gjklab::testing {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Log-uniform in [lo, hi] (lo, hi > 0).
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, uniform()); }
  int integer(int lo, int hi) { return lo + static_cast<int>(uniform() * (hi - lo + 1)); }
  /// Standard normal variate (Box–Muller).
  double normal() {
    const double u = 1.0 - uniform();  // (0, 1]
    return std::sqrt(-2 * std::log(u)) * std::cos(2 * M_PI * uniform());
  }
  Vec3 unit_vector() {
    for (;;) {
      const Vec3 g(normal(), normal(), normal());
      if (const double n = g.norm(); n > 1e-9) return g / n;
    }
  }

 private:
  std::mt19937_64 engine_;
};

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
  double a_max = -INFINITY, b_min = INFINITY;
  for (const Vec3& v : p.a)
    a_max = std::max(a_max, v.dot(u));
  for (const Vec3& v : p.b)
    b_min = std::min(b_min, v.dot(u));
  const double size = pair_size(p.a, p.b);
  const Vec3 shift = (a_max - b_min + gap * size) * u;
  for (Vec3& v : p.b)
    v += shift;
  return p;
}

}  // namespace gjklab::testing
