// Random draws shared by the case generators (private to src/experiment/cases): uniform,
// log-uniform values and counts, directions and rotations from one GSL stream.
#pragma once

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <algorithm>
#include <cmath>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::experiment {

/// Uniform in [0, 1).
inline double uniform(gsl_rng* r) {
  return gsl_rng_uniform(r);
}

/// Log-uniform in [lo, hi] (0 < lo <= hi).
inline double log_uniform(gsl_rng* r, const Interval& range) {
  const double u = uniform(r);
  if (range.lo == range.hi) return range.lo;
  return std::clamp(range.lo * std::pow(range.hi / range.lo, u), range.lo, range.hi);
}

/// Integer with P(n) ∝ log((n + 1) / n) on [lo, hi]: the floor of a log-uniform variate on
/// [lo, hi + 1), so every scale of vertex counts gets an equal share.
inline int log_uniform_count(gsl_rng* r, const Interval& range) {
  const double u = uniform(r);
  const double lo = range.lo;
  const double hi = range.hi;
  if (lo == hi) return static_cast<int>(lo);
  const double x = std::floor(lo * std::pow((hi + 1) / lo, u));
  return static_cast<int>(std::clamp(x, lo, hi));
}

inline Vec3 unit_vector(gsl_rng* r) {
  double x = 0, y = 0, z = 0;
  gsl_ran_dir_3d(r, &x, &y, &z);
  return {x, y, z};
}

/// A rotation uniform on SO(3): a normalised quaternion of four independent Gaussians.
inline Mat3 random_rotation(gsl_rng* r) {
  for (;;) {
    const double w = gsl_ran_gaussian(r, 1.0);
    const double x = gsl_ran_gaussian(r, 1.0);
    const double y = gsl_ran_gaussian(r, 1.0);
    const double z = gsl_ran_gaussian(r, 1.0);
    const Quat q(w, x, y, z);
    if (q.norm() > 1e-6) return q.normalized().toRotationMatrix();
  }
}

}  // namespace gjklab::experiment
