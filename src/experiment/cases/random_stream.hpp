// RandomStream, which families.hpp declares (private to src/experiment/cases, with unit tests
// that open it): the GSL generator the case generators draw from.
#pragma once

#include <gsl/gsl_rng.h>

#include <cstdint>
#include <new>

#include "gjklab/experiment/cases/families.hpp"

namespace gjklab::experiment {

/// Owns one gsl_rng_mt19937. The public headers name this type, not gsl_rng (a typedef of an
/// anonymous struct, which no header can declare without including GSL's).
struct RandomStream {
  /// gsl_rng_mt19937 seeded with `seed` by gsl_rng_set (mt19937 keeps 32 bits of its seed).
  /// Throws std::bad_alloc.
  explicit RandomStream(std::uint32_t seed) : gsl(gsl_rng_alloc(gsl_rng_mt19937)) {
    if (!gsl) throw std::bad_alloc();
    gsl_rng_set(gsl, seed);
  }
  ~RandomStream() { gsl_rng_free(gsl); }
  RandomStream(const RandomStream&) = delete;
  RandomStream& operator=(const RandomStream&) = delete;

  gsl_rng* const gsl;
};

}  // namespace gjklab::experiment
