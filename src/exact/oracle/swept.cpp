// The exact oracle for sphere-swept shapes: the cores' exact answer, shifted by the radii.
//
// With R = r_A + r_B (an exact rational: the sum of two doubles) and q the cores' exact squared
// distance, the swept shapes intersect iff q ≤ R², decided exactly in rationals. Their distance
// √q − R and depth R − √q (cores apart) or √p + R (cores intersecting, p their squared depth)
// are irrational in general. They are evaluated with MPFR and rounded to the nearest double:
//   √q − R = (q − R²) / (√q + R),
// with the numerator exact, so that no cancellation occurs however close √q is to R; both
// this quotient and √p + R have a relative error below 2^(4−P) at MPFR precision P (each of
// the at most four roundings contributes 2^−P). The precision doubles from 128 bits until
// mpfr_can_round proves that rounding the approximation to 53 bits gives the correctly
// rounded double (it stops at 2^16 bits, far beyond any double input's needs). Results in the
// subnormal range (below 2^-1022) may be off by one subnormal step.
// No CGAL here: the cores come from exact::solve.
#include <gmp.h>
#include <mpfr.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "gjklab/exact/oracle.hpp"
#include "exact/arithmetic/gmp_support.hpp"
#include "exact/arithmetic/mpfr_support.hpp"

namespace gjklab::exact {

namespace {

/// out := √q (rounded at out's precision).
void sqrt_of(mpfr_ptr out, mpq_srcptr q) {
  mpfr_set_q(out, q, MPFR_RNDN);
  mpfr_sqrt(out, out, MPFR_RNDN);
}

/// The double nearest to √q − r for rationals q, r ≥ 0 (negative when √q < r).
double nearest_sqrt_minus(mpq_srcptr q, mpq_srcptr r) {
  detail::Mpq numerator;  // q − r², exact
  mpq_mul(numerator.get(), r, r);
  mpq_sub(numerator.get(), q, numerator.get());
  if (mpq_sgn(numerator.get()) == 0) return 0.0;
  return detail::correctly_rounded([&](mpfr_ptr out, mpfr_prec_t p) {
    detail::Mpfr denominator(p), rr(p);
    sqrt_of(denominator.get(), q);
    mpfr_set_q(rr.get(), r, MPFR_RNDN);
    mpfr_add(denominator.get(), denominator.get(), rr.get(), MPFR_RNDN);  // √q + r > 0
    mpfr_set_q(out, numerator.get(), MPFR_RNDN);
    mpfr_div(out, out, denominator.get(), MPFR_RNDN);
  });
}

/// The double nearest to √q + r for rationals q, r ≥ 0.
double nearest_sqrt_plus(mpq_srcptr q, mpq_srcptr r) {
  if (mpq_sgn(q) == 0 && mpq_sgn(r) == 0) return 0.0;
  return detail::correctly_rounded([&](mpfr_ptr out, mpfr_prec_t p) {
    detail::Mpfr rr(p);
    sqrt_of(out, q);
    mpfr_set_q(rr.get(), r, MPFR_RNDN);
    mpfr_add(out, out, rr.get(), MPFR_RNDN);
  });
}

/// out := the exact rational value of `r`.
void set_rational(mpq_ptr out, const Rational& r) {
  if (mpq_set_str(out, (r.numerator() + "/" + r.denominator()).c_str(), 10) != 0)
    throw std::logic_error("exact oracle: malformed rational " + r.numerator() + "/" +
                           r.denominator());
  mpq_canonicalize(out);
}

void check_radius(double radius, const char* name) {
  if (!(radius >= 0) || !std::isfinite(radius))
    throw std::invalid_argument(std::string(name) + ": the radius must be finite and >= 0, not " +
                                std::to_string(radius));
}

}  // namespace

OracleAnswer solve_swept(std::span<const Vec3> a, std::span<const Vec3> b, double radius_a,
                         double radius_b, const OracleOptions& options, const OracleHints& hints) {
  check_radius(radius_a, "shape A");
  check_radius(radius_b, "shape B");
  OracleAnswer answer = solve(a, b, options, hints);
  if (radius_a == 0 && radius_b == 0) return answer;

  detail::Mpq r, rb, q;
  detail::set_double(r.get(), radius_a);
  detail::set_double(rb.get(), radius_b);
  mpq_add(r.get(), r.get(), rb.get());  // R = r_A + r_B, exact
  set_rational(q.get(), answer.distance_squared);
  answer.swept = true;

  if (answer.intersect) {  // the cores intersect (q = 0): depth √p + R
    answer.distance = 0;
    if (answer.depth_squared) {
      detail::Mpq p;
      set_rational(p.get(), *answer.depth_squared);
      answer.depth = nearest_sqrt_plus(p.get(), r.get());
    }
    return answer;
  }
  detail::Mpq r2;
  mpq_mul(r2.get(), r.get(), r.get());
  if (mpq_cmp(q.get(), r2.get()) > 0) {  // cores farther apart than R: separated
    answer.distance = nearest_sqrt_minus(q.get(), r.get());
    return answer;
  }
  answer.intersect = true;  // cores within R: the balls overlap (or touch, depth 0)
  answer.distance = 0;
  if (options.depth) {
    const double shortfall = nearest_sqrt_minus(q.get(), r.get());  // √q − R ≤ 0
    answer.depth = shortfall == 0 ? 0.0 : -shortfall;
  }
  return answer;
}

}  // namespace gjklab::exact
