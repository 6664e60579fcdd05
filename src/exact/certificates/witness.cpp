// Exact witness errors (see witness.hpp). No CGAL here: the QP fallback goes through solve().
#include "gjklab/exact/witness.hpp"

#include <gmp.h>
#include <mpfr.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "exact/arithmetic/gmp_support.hpp"
#include "exact/arithmetic/mpfr_support.hpp"
#include "gjklab/exact/certificate.hpp"

namespace gjklab::exact {

double distance_to_hull(std::span<const Vec3> cloud, const Vec3& p) {
  if (!p.allFinite()) throw std::invalid_argument("witness: non-finite coordinate");
  const std::array<Vec3, 1> point{p};
  // Exact GJK from the vertex nearest p (in doubles: only a start, every step is exact).
  std::int32_t nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (const double d2 = (cloud[i] - p).squaredNorm(); d2 < best) {
      best = d2;
      nearest = static_cast<std::int32_t>(i);
    }
  if (const auto c = certify_distance(cloud, point, DistanceHint{{{nearest, 0}}}))
    return c->distance;
  return solve(cloud, point, {.certificates = false, .hull_vertices = false}).distance;
}

double distance_difference(const Vec3& p, const Vec3& q, const Rational& distance_squared) {
  if (!p.allFinite() || !q.allFinite())
    throw std::invalid_argument("witness: non-finite coordinate");
  detail::Mpq s, t, x, y;  // s = ‖p − q‖², exactly
  for (int i = 0; i < 3; ++i) {
    detail::set_double(x.get(), p[i]);
    detail::set_double(y.get(), q[i]);
    mpq_sub(x.get(), x.get(), y.get());
    mpq_mul(x.get(), x.get(), x.get());
    mpq_add(s.get(), s.get(), x.get());
  }
  if (mpq_set_str(t.get(),
                  (distance_squared.numerator() + "/" + distance_squared.denominator()).c_str(),
                  10) != 0)
    throw std::invalid_argument("witness: malformed rational");
  mpq_canonicalize(t.get());
  detail::Mpq numerator;  // s − t, exact: √s − √t = (s − t)/(√s + √t) without cancellation
  mpq_sub(numerator.get(), s.get(), t.get());
  if (mpq_sgn(numerator.get()) == 0) return 0.0;
  const double signed_difference = detail::correctly_rounded([&](mpfr_ptr out, mpfr_prec_t prec) {
    detail::Mpfr root_s(prec), root_t(prec);
    mpfr_set_q(root_s.get(), s.get(), MPFR_RNDN);
    mpfr_sqrt(root_s.get(), root_s.get(), MPFR_RNDN);
    mpfr_set_q(root_t.get(), t.get(), MPFR_RNDN);
    mpfr_sqrt(root_t.get(), root_t.get(), MPFR_RNDN);
    mpfr_add(root_s.get(), root_s.get(), root_t.get(), MPFR_RNDN);  // √s + √t > 0
    mpfr_set_q(out, numerator.get(), MPFR_RNDN);
    mpfr_div(out, out, root_s.get(), MPFR_RNDN);
  });
  return std::abs(signed_difference);
}

}  // namespace gjklab::exact
