// Internal to src/exact/: small RAII wrappers around GMP values and the conversions between
// GMP rationals, the public Rational (decimal strings) and doubles. No CGAL here.
#pragma once

#include <gmp.h>

#include <memory>
#include <mutex>
#include <string>
#include <utility>

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

namespace gjklab::exact {

/// A Rational's value, whose decimal digits are made once, on first use, by make_digits.
class Rational::Source {
 public:
  struct Digits {
    std::string numerator, denominator;  ///< lowest terms, denominator ≥ 1
  };
  virtual ~Source() = default;
  virtual bool is_zero() const = 0;
  /// Thread-safe: copies of a Rational may be read from several threads.
  const Digits& digits() const {
    std::call_once(once_, [this] { digits_ = make_digits(); });
    return digits_;
  }

 private:
  virtual Digits make_digits() const = 0;
  mutable std::once_flag once_;
  mutable Digits digits_;
};

}  // namespace gjklab::exact

namespace gjklab::exact::detail {

/// The digits of the value that compute(mpq_ptr out) sets (any fraction with a non-zero
/// denominator: it is canonicalised here).
template <class Compute>
class ComputedSource final : public Rational::Source {
 public:
  ComputedSource(bool is_zero, Compute compute) : zero_(is_zero), compute_(std::move(compute)) {}
  bool is_zero() const override { return zero_; }

 private:
  Digits make_digits() const override {
    Mpq q;
    compute_(q.get());
    mpq_canonicalize(q.get());
    const Rational r = to_rational(q.get());
    return {r.numerator(), r.denominator()};
  }
  bool zero_;
  Compute compute_;
};

/// A Rational computed on first use by compute (see ComputedSource); is_zero must be known.
template <class Compute>
Rational lazy_rational(bool is_zero, Compute compute) {
  return Rational(std::make_shared<const ComputedSource<Compute>>(is_zero, std::move(compute)));
}

}  // namespace gjklab::exact::detail
