// Correctly rounded conversions of exact rationals to doubles, with GMP integers only.
//
// Both conversions scale the value by a power of two 2^-e so that its integer part q has 53
// significant bits (fewer only in the subnormal range, where e is clamped to -1074), round q
// to nearest with ties to even by comparing the exact remainder with one half, and return
// q·2^e, which ldexp computes exactly (or overflows to infinity, which is then the correctly
// rounded result). No floating-point operation other than that final ldexp is involved.
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "exact/arithmetic/gmp_support.hpp"

namespace gjklab::exact {

namespace {

constexpr long kMinExponent = -1074;  // exponent of the least subnormal double, 2^-1074
constexpr std::size_t kPrecision = 53;

long bit_length(mpz_srcptr x) {
  return static_cast<long>(mpz_sizeinbase(x, 2));
}

/// Sets n, d (d > 0, lowest terms not required) from r; returns the sign of the value.
int parse(const Rational& r, mpz_ptr n, mpz_ptr d) {
  const std::string &num = r.numerator(), &den = r.denominator();
  if (num.empty() || mpz_set_str(n, num.c_str(), 10) != 0)
    throw std::invalid_argument("Rational: malformed numerator '" + num + "'");
  if (den.empty() || mpz_set_str(d, den.c_str(), 10) != 0)
    throw std::invalid_argument("Rational: malformed denominator '" + den + "'");
  if (mpz_sgn(d) == 0) throw std::invalid_argument("Rational: zero denominator");
  const int sign = mpz_sgn(n) * mpz_sgn(d);
  mpz_abs(n, n);
  mpz_abs(d, d);
  return sign;
}

/// num/den := n·2^-e / d as an integer fraction (shifting whichever side keeps it integral).
void scaled(mpz_srcptr n, mpz_srcptr d, long e, mpz_ptr num, mpz_ptr den) {
  if (e <= 0) {
    mpz_mul_2exp(num, n, static_cast<mp_bitcnt_t>(-e));
    mpz_set(den, d);
  } else {
    mpz_set(num, n);
    mpz_mul_2exp(den, d, static_cast<mp_bitcnt_t>(e));
  }
}

/// The double nearest to n/d for n, d > 0 (ties to even).
double nearest_quotient(mpz_srcptr n, mpz_srcptr d) {
  // n/d lies in (2^(bn-bd-1), 2^(bn-bd+1)), so n/d·2^-e lies in (2^52, 2^54) for this e.
  long e = bit_length(n) - bit_length(d) - static_cast<long>(kPrecision);
  if (e < kMinExponent) e = kMinExponent;
  detail::Mpz num, den, q, r;
  scaled(n, d, e, num.get(), den.get());
  mpz_fdiv_qr(q.get(), r.get(), num.get(), den.get());
  if (mpz_sizeinbase(q.get(), 2) > kPrecision) {  // q ≥ 2^53: one more bit of scaling
    ++e;
    scaled(n, d, e, num.get(), den.get());
    mpz_fdiv_qr(q.get(), r.get(), num.get(), den.get());
  }
  // Round q + r/den to nearest, ties to even: compare 2r with den.
  mpz_mul_2exp(r.get(), r.get(), 1);
  const int c = mpz_cmp(r.get(), den.get());
  if (c > 0 || (c == 0 && mpz_odd_p(q.get()))) mpz_add_ui(q.get(), q.get(), 1);
  // q ≤ 2^53 converts exactly; ldexp is exact except for overflow to infinity.
  return std::ldexp(mpz_get_d(q.get()), static_cast<int>(e));
}

/// The double nearest to √(n/d) for n, d > 0 (ties to even).
double nearest_sqrt(mpz_srcptr n, mpz_srcptr d) {
  // √(n/d)·2^-e = √(n·2^-2e / d); its floor is the integer square root of floor(n·2^-2e / d).
  const long diff = bit_length(n) - bit_length(d);
  long e = (diff >= 0 ? diff / 2 : -((-diff + 1) / 2)) - static_cast<long>(kPrecision);
  detail::Mpz num, den, s;
  for (;;) {
    if (e < kMinExponent) e = kMinExponent;
    scaled(n, d, 2 * e, num.get(), den.get());
    mpz_fdiv_q(s.get(), num.get(), den.get());
    mpz_sqrt(s.get(), s.get());
    const std::size_t bits = mpz_sizeinbase(s.get(), 2);
    if (bits > kPrecision) {
      ++e;  // s ≥ 2^53
    } else if (bits < kPrecision && e > kMinExponent) {
      --e;  // s < 2^52 and not yet at the subnormal exponent
    } else {
      break;
    }
  }
  // y = √(num/den) with s = floor(y): y ⋚ s + 1/2  ⇔  4·num ⋚ (2s+1)²·den.
  detail::Mpz lhs, rhs;
  mpz_mul_2exp(lhs.get(), num.get(), 2);
  mpz_mul_2exp(rhs.get(), s.get(), 1);
  mpz_add_ui(rhs.get(), rhs.get(), 1);
  mpz_mul(rhs.get(), rhs.get(), rhs.get());
  mpz_mul(rhs.get(), rhs.get(), den.get());
  const int c = mpz_cmp(lhs.get(), rhs.get());
  if (c > 0 || (c == 0 && mpz_odd_p(s.get()))) mpz_add_ui(s.get(), s.get(), 1);
  return std::ldexp(mpz_get_d(s.get()), static_cast<int>(e));
}

std::string decimal(mpz_srcptr z) {
  std::string out(mpz_sizeinbase(z, 10) + 2, '\0');
  mpz_get_str(out.data(), 10, z);
  out.resize(std::char_traits<char>::length(out.c_str()));
  return out;
}

}  // namespace

namespace {

/// A value given by its digits.
class DigitsSource final : public Rational::Source {
 public:
  explicit DigitsSource(Digits digits) : digits_(std::move(digits)) {}
  bool is_zero() const override { return digits_.numerator == "0"; }

 private:
  Digits make_digits() const override { return digits_; }
  Digits digits_;
};

const std::shared_ptr<const Rational::Source>& zero_source() {
  static const std::shared_ptr<const Rational::Source> zero =
      std::make_shared<const DigitsSource>(Rational::Source::Digits{"0", "1"});
  return zero;
}

}  // namespace

Rational::Rational() : source_(zero_source()) {}

Rational::Rational(std::string numerator, std::string denominator)
    : source_(std::make_shared<const DigitsSource>(
          Source::Digits{std::move(numerator), std::move(denominator)})) {}

Rational::Rational(std::shared_ptr<const Source> source) : source_(std::move(source)) {}

const std::string& Rational::numerator() const {
  return source_->digits().numerator;
}

const std::string& Rational::denominator() const {
  return source_->digits().denominator;
}

bool Rational::is_zero() const {
  return source_->is_zero();
}

bool operator==(const Rational& x, const Rational& y) {
  return x.source_ == y.source_ ||
         (x.numerator() == y.numerator() && x.denominator() == y.denominator());
}

double Rational::to_double() const {
  detail::Mpz n, d;
  const int sign = parse(*this, n.get(), d.get());
  if (sign == 0) return 0.0;
  const double magnitude = nearest_quotient(n.get(), d.get());
  return sign < 0 ? -magnitude : magnitude;
}

double sqrt_to_double(const Rational& r) {
  detail::Mpz n, d;
  const int sign = parse(r, n.get(), d.get());
  if (sign == 0) return 0.0;
  if (sign < 0) return std::numeric_limits<double>::quiet_NaN();
  return nearest_sqrt(n.get(), d.get());
}

namespace detail {

void set_double(mpq_ptr out, double x) {
  mpq_set_d(out, x);
}  // exact for finite x

double nearest_double(mpz_srcptr num, mpz_srcptr den, long exponent) {
  const int sign = mpz_sgn(num) * mpz_sgn(den);
  if (sign == 0) return 0.0;
  detail::Mpz n, d;
  mpz_abs(n.get(), num);
  mpz_abs(d.get(), den);
  if (exponent > 0) mpz_mul_2exp(n.get(), n.get(), static_cast<mp_bitcnt_t>(exponent));
  if (exponent < 0) mpz_mul_2exp(d.get(), d.get(), static_cast<mp_bitcnt_t>(-exponent));
  const double magnitude = nearest_quotient(n.get(), d.get());
  return sign < 0 ? -magnitude : magnitude;
}

double nearest_sqrt(mpq_srcptr q) {
  if (mpq_sgn(q) <= 0) return mpq_sgn(q) == 0 ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  return exact::nearest_sqrt(mpq_numref(q), mpq_denref(q));  // the mpz overload above
}

double nearest_double(mpq_srcptr q) {
  const int sign = mpq_sgn(q);
  if (sign == 0) return 0.0;
  detail::Mpz n;
  mpz_abs(n.get(), mpq_numref(q));
  const double magnitude = nearest_quotient(n.get(), mpq_denref(q));
  return sign < 0 ? -magnitude : magnitude;
}

Rational to_rational(mpq_srcptr q) {
  return Rational(decimal(mpq_numref(q)), decimal(mpq_denref(q)));
}

}  // namespace detail

}  // namespace gjklab::exact
