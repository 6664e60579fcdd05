// Double-word ("double-double") arithmetic with a running bound on the absolute error, for
// computations that need about 100 bits: the exact layer's floating-point filters, and the GJK
// sub-simplex solve on ill-conditioned simplices (gjk/precise_subsimplex.hpp).
//
// A value is hi + lo with |lo| ≤ ulp(hi)/2, and err bounds |exact − (hi + lo)|, where "exact" is
// the real number the same expression gives on the input doubles. The sums and products are
// the classical error-free transformations (TwoSum, and the exact product a·b = p + fma(a, b, −p))
// followed by one renormalisation. Every operation is always_inline so that a caller compiled
// for a processor with fused multiply-add gets the instruction (see the exact layer's
// filtered_tetrahedron.cpp); elsewhere fma is the C library's, which is exact too. With u = 2^-53
// the rounding they add is at most, derived for these exact sequences of operations:
//   x + y: 3.1·u²·(|x.hi| + |y.hi|)   (the low parts' sum and its addition to TwoSum's error)
//   x · y: 8·u²·(1 + 3u)·|x.hi·y.hi|  (three products of low parts and two sums, each ≤ u)
// and the bounds below use 4u² and 10u². Each also adds kUnderflowSlack, an absolute 2^-1000
// that covers every gradual-underflow loss (at most a few 2^-1074), so values that small are
// never decided. Overflow gives Inf or NaN, which no comparison below accepts. The bounds are
// themselves computed in double and scaled by 1 + 2^-40, which covers their own rounding.
#pragma once

#include <cmath>

namespace gjklab {

struct DoubleWord {
  double hi = 0, lo = 0;
  double err = 0;  ///< absolute bound on |exact − (hi + lo)|
};

namespace double_word {

constexpr double kU2 = 0x1p-106;  // u², u = 2^-53
constexpr double kUnderflowSlack = 0x1p-1000;
constexpr double kBoundSafety = 1 + 0x1p-40;

/// a + b = s + e exactly (Knuth's TwoSum; any order of magnitudes).
[[gnu::always_inline]] inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

/// a + b = s + e exactly, for |a| ≥ |b| or a = 0.
[[gnu::always_inline]] inline void fast_two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  e = b - (s - a);
}

/// a · b = p + e exactly, barring underflow.
[[gnu::always_inline]] inline void two_product(double a, double b, double& p, double& e) {
  p = a * b;
  e = __builtin_fma(a, b, -p);
}

}  // namespace double_word

/// x − y for doubles, exactly (err 0).
[[gnu::always_inline]] inline DoubleWord exact_difference(double x, double y) {
  DoubleWord out;
  double_word::two_sum(x, -y, out.hi, out.lo);
  return out;
}

[[gnu::always_inline]] inline DoubleWord operator-(const DoubleWord& x) {
  return {-x.hi, -x.lo, x.err};
}

[[gnu::always_inline]] inline DoubleWord operator+(const DoubleWord& x, const DoubleWord& y) {
  using namespace double_word;
  double s, e;
  two_sum(x.hi, y.hi, s, e);
  const double w = e + (x.lo + y.lo);
  DoubleWord out;
  two_sum(s, w, out.hi, out.lo);
  const double rounding = 4 * kU2 * (std::fabs(x.hi) + std::fabs(y.hi));
  out.err = (x.err + y.err + rounding) * kBoundSafety + kUnderflowSlack;
  return out;
}

[[gnu::always_inline]] inline DoubleWord operator-(const DoubleWord& x, const DoubleWord& y) {
  return x + (-y);
}

[[gnu::always_inline]] inline DoubleWord operator*(const DoubleWord& x, const DoubleWord& y) {
  using namespace double_word;
  double p, e;
  two_product(x.hi, y.hi, p, e);
  const double cross_terms = x.hi * y.lo + x.lo * y.hi;
  DoubleWord out;
  fast_two_sum(p, e + cross_terms, out.hi, out.lo);
  // |x̂·ŷ − x·y| ≤ |x̂|·y.err + |ŷ|·x.err + x.err·y.err, with |x̂| ≤ |x.hi|·(1 + u).
  const double ax = std::fabs(x.hi), ay = std::fabs(y.hi);
  const double propagated = (ax * y.err + ay * x.err + x.err * y.err) * (1 + 0x1p-52);
  out.err = (propagated + 10 * kU2 * ax * ay) * kBoundSafety + kUnderflowSlack;
  return out;
}

[[gnu::always_inline]] inline DoubleWord operator*(const DoubleWord& x, double y) {
  return x * DoubleWord{y, 0, 0};
}

/// The value is decided > 0 (or < 0): it lies further from zero than its error bound. As
/// |lo| ≤ u·|hi|, hi > err·(1 + 2^-50) gives hi + lo > err.
[[gnu::always_inline]] inline bool positive(const DoubleWord& x) {
  return x.hi > x.err * (1 + 0x1p-50);
}
[[gnu::always_inline]] inline bool negative(const DoubleWord& x) {
  return positive(-x);
}

}  // namespace gjklab
