// Internal to src/exact/: small RAII wrappers around GMP values and the conversions between
// GMP rationals, the public Rational (decimal strings) and doubles. No CGAL here.
#pragma once

#include <gmp.h>

#include "gjklab/exact/oracle.hpp"

namespace gjklab::exact::detail {

/// An owned mpz_t.
class Mpz {
 public:
  Mpz() { mpz_init(v_); }
  ~Mpz() { mpz_clear(v_); }
  Mpz(const Mpz&) = delete;
  Mpz& operator=(const Mpz&) = delete;
  mpz_ptr get() { return v_; }
  mpz_srcptr get() const { return v_; }

 private:
  mpz_t v_;
};

/// An owned mpq_t (initialised to 0/1).
class Mpq {
 public:
  Mpq() { mpq_init(v_); }
  ~Mpq() { mpq_clear(v_); }
  Mpq(const Mpq&) = delete;
  Mpq& operator=(const Mpq&) = delete;
  mpq_ptr get() { return v_; }
  mpq_srcptr get() const { return v_; }

 private:
  mpq_t v_;
};

/// The exact value of a finite double.
void set_double(mpq_ptr out, double x);

/// The double nearest to q (ties to even).
double nearest_double(mpq_srcptr q);
/// The double nearest to num/den · 2^exponent (den ≠ 0; lowest terms not required, so no gcd).
double nearest_double(mpz_srcptr num, mpz_srcptr den, long exponent);
/// The double nearest to √q for q ≥ 0 (NaN for q < 0).
double nearest_sqrt(mpq_srcptr q);

/// The public decimal form of q (q must be canonical: lowest terms, positive denominator).
Rational to_rational(mpq_srcptr q);

}  // namespace gjklab::exact::detail
