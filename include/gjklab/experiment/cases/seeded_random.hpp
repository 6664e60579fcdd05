// Seeded random inputs outside the experiment families: the benchmark suites' clouds and poses
// and the property tests' pairs draw from one stream type, and every generator that places one
// cloud beside another (the families too) measures the clouds' extents the same way.
//
// The stream is std::mt19937_64, whose output sequence the standard fixes, with our own
// conversions to uniform and Gaussian variates, so a seed gives the same inputs with every
// standard library. (The families draw from GSL's mt19937 instead, per case; see families.hpp.)
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <span>

#include "gjklab/geometry/types.hpp"

namespace gjklab::experiment {

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Log-uniform in [lo, hi] (lo, hi > 0).
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, uniform()); }
  /// Uniform in lo … hi (inclusive).
  int integer(int lo, int hi) { return lo + static_cast<int>(uniform() * (hi - lo + 1)); }
  /// Standard normal variate (Box–Muller).
  double normal() {
    const double u = 1.0 - uniform();  // (0, 1]: the logarithm stays finite
    return std::sqrt(-2 * std::log(u)) * std::cos(2 * std::numbers::pi * uniform());
  }
  /// Uniform on the unit sphere: a normalised Gaussian vector.
  Vec3 unit_vector() {
    for (;;) {
      const Vec3 g(normal(), normal(), normal());
      if (const double n = g.norm(); n > 1e-9) return g / n;
    }
  }
  /// A uniformly distributed rotation (normalised Gaussian quaternion).
  Mat3 rotation() {
    for (;;) {
      const Quat q(normal(), normal(), normal(), normal());
      if (q.norm() > 1e-9) return q.normalized().toRotationMatrix();
    }
  }

 private:
  std::mt19937_64 engine_;
};

/// Where the cloud's extent along u ends: the largest u·p (−∞ for no points).
inline double max_projection(std::span<const Vec3> cloud, const Vec3& u) {
  double m = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : cloud)
    m = std::max(m, p.dot(u));
  return m;
}

/// Where the cloud's extent along u starts: the smallest u·p (+∞ for no points).
inline double min_projection(std::span<const Vec3> cloud, const Vec3& u) {
  double m = std::numeric_limits<double>::infinity();
  for (const Vec3& p : cloud)
    m = std::min(m, p.dot(u));
  return m;
}

/// How far B must move along the unit axis u for its extent along u to start `gap` (length
/// units) after A's ends; a negative gap makes them overlap by −gap.
inline double separating_shift(std::span<const Vec3> a, std::span<const Vec3> b, const Vec3& u,
                               double gap) {
  return max_projection(a, u) - min_projection(b, u) + gap;
}

}  // namespace gjklab::experiment
