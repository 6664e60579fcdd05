// Internal to src/exact/: correctly rounded evaluation of irrational exact quantities with
// MPFR (the sphere-swept answers, the witness errors). No CGAL here.
#pragma once

#include <gmp.h>
#include <mpfr.h>

namespace gjklab::exact::detail {

/// An owned mpfr_t of the given precision.
class Mpfr {
 public:
  explicit Mpfr(mpfr_prec_t precision) { mpfr_init2(v_, precision); }
  ~Mpfr() { mpfr_clear(v_); }
  Mpfr(const Mpfr&) = delete;
  Mpfr& operator=(const Mpfr&) = delete;
  mpfr_ptr get() { return v_; }

 private:
  mpfr_t v_;
};

inline constexpr mpfr_prec_t kFirstPrecision = 128;
inline constexpr mpfr_prec_t kLastPrecision = 1 << 16;

/// The double nearest to the value that `approximate(out, P)` approximates with relative error
/// below 2^(4−P) at precision P (out has precision P). The value must not be 0.
template <class Approximate>
double correctly_rounded(Approximate&& approximate) {
  for (mpfr_prec_t p = kFirstPrecision;; p *= 2) {
    Mpfr x(p);
    approximate(x.get(), p);
    // |error| < 2^(4−p)·|value| ≤ 2^(5−p)·2^EXP(x) (|value| < 2·2^EXP(x) up to that error).
    if (p >= kLastPrecision || mpfr_can_round(x.get(), p - 5, MPFR_RNDN, MPFR_RNDN, 53))
      return mpfr_get_d(x.get(), MPFR_RNDN);
  }
}

}  // namespace gjklab::exact::detail
