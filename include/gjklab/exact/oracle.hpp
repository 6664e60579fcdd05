// The exact oracle: ground truth for two point clouds, computed with exact rational arithmetic.
//
// Every double is an exact rational, so the oracle's answers are exact for the clouds as given
// (no tolerance anywhere). Lower-dimensional clouds (single points, duplicates, collinear and
// coplanar sets) are legal. The implementation uses CGAL and lives in src/exact/ only: this
// header exposes plain doubles and decimal strings so that no other translation unit pays for
// CGAL's headers.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "gjklab/exact/hint.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::exact {

/// An exact rational num/den in lowest terms, as decimal strings (den ≥ 1).
///
/// A certificate finds its value as an unreduced fraction of integers of a few hundred bits.
/// Reducing it (a gcd) and printing it in decimal cost more than the certificate itself, and
/// most answers are never printed (benchmarks, booleans, distances as doubles), so the digits
/// are made on first use, once, by the value's source, which copies share.
class Rational {
 public:
  /// Makes the digits on first use; defined inside the exact layer.
  class Source;

  Rational();  ///< 0/1
  /// The value num/den, given in lowest terms.
  Rational(std::string numerator, std::string denominator);
  explicit Rational(std::shared_ptr<const Source> source);

  const std::string& numerator() const;
  const std::string& denominator() const;
  /// The nearest double to num/den (round to nearest, ties to even).
  double to_double() const;
  bool is_zero() const;
  /// The same value (both sides are in lowest terms, so equal digits).
  friend bool operator==(const Rational& x, const Rational& y);

 private:
  std::shared_ptr<const Source> source_;
};

/// Returns the double nearest to √(num/den) (correctly rounded).
double sqrt_to_double(const Rational& r);

/// Steps of exact GJK a distance certificate may take beyond its hint before the QP takes over.
inline constexpr int kCertificateMaxSteps = 64;

struct OracleOptions {
  /// Also compute the exact squared penetration depth of intersecting pairs: certified from a
  /// depth hint when one is given and holds, otherwise from the exact hull of the Minkowski
  /// difference (|A|·|B| points, much slower).
  bool depth = false;
  /// Try the certificates (certificate.hpp) before the QP. Off: the QP answers every pair.
  bool certificates = true;
  /// Exact GJK (distance) and EPA (depth) steps a certificate may take beyond its hint (0: the
  /// hint itself must prove the answer).
  int certificate_steps = kCertificateMaxSteps;
  /// Audit mode: also solve every certified pair by the QP (and the Minkowski hull) and throw
  /// CertificateMismatch if the two rationals differ.
  bool verify = false;
  /// Count each cloud's hull vertices (an exact hull of each cloud: costlier than a
  /// certificate). Off: the counts are −1.
  bool hull_vertices = true;
};

/// Floating-point answers that the certificates verify (see hint.hpp); both optional.
struct OracleHints {
  std::optional<DistanceHint> distance;
  std::optional<DepthHint> depth;
};

/// Thrown by the audit mode (OracleOptions::verify) when a certified rational differs from the
/// QP's: a bug in a certificate, never an answer.
struct CertificateMismatch : std::logic_error {
  using std::logic_error::logic_error;
};

struct OracleAnswer {
  /// The closed convex hulls share at least one point (touching counts as intersecting).
  bool intersect = false;
  /// Exact squared Euclidean distance between the hulls (0 when intersecting).
  Rational distance_squared;
  /// √distance_squared rounded to the nearest double.
  double distance = 0;
  /// Number of vertices of each cloud's convex hull (1 for a point, 2 for a segment, the
  /// polygon's corner count for a flat cloud); duplicates and interior points do not count.
  /// −1 when not computed (OracleOptions::hull_vertices off).
  int hull_vertices_a = 0;
  int hull_vertices_b = 0;
  /// With OracleOptions::depth and intersect: the exact squared penetration depth, i.e. the
  /// squared distance from the origin to the boundary of A − B (0 when the pair only touches
  /// or when A − B has no interior). Empty when not requested or not intersecting.
  std::optional<Rational> depth_squared;
  /// √depth_squared rounded to the nearest double, when depth_squared is present.
  std::optional<double> depth;
  /// Answered by solve_swept for non-zero radii: intersect, distance and depth are the swept
  /// shapes', while distance_squared, depth_squared and the hull counts stay the cores'.
  bool swept = false;
  /// Certified path only (else empty): the exact closest points of the hulls, p ∈ conv(A) and
  /// q ∈ conv(B) with ‖p − q‖² = distance_squared (a common point when intersecting), each
  /// coordinate rounded to the nearest double. The cores' points for swept shapes.
  std::optional<Vec3> witness_a, witness_b;
  /// Certified depth only (else empty): the outward unit normal of the face of A − B nearest
  /// the origin, i.e. the direction in which B must move by the depth (rounded).
  std::optional<Vec3> depth_normal;
  /// How distance_squared (and intersect) was obtained.
  AnswerMethod method = AnswerMethod::qp;
  /// How depth_squared was obtained (`none` when it is absent).
  AnswerMethod depth_method = AnswerMethod::none;
};

/// Solves the pair exactly. Throws std::invalid_argument (gjklab::InvalidGeometry) for an
/// empty cloud or a non-finite coordinate; the message names which cloud, e.g.
/// "cloud B: non-finite coordinate in point 3".
/// With certificates on, the distance is first certified from `hints.distance` (exact GJK
/// from the pair (0, 0) without one), the depth from `hints.depth`; the QP answers whatever no
/// certificate proves. Either way the rationals are the same.
OracleAnswer solve(std::span<const Vec3> a, std::span<const Vec3> b,
                   const OracleOptions& options = {}, const OracleHints& hints = {});

/// Solves a pair of sphere-swept shapes: the hull of cloud a swept by a ball of radius_a, and
/// likewise b (length units, each finite and >= 0; a single point and a radius make a sphere,
/// two points a capsule, any cloud a rounded polytope). With R = radius_a + radius_b and q the
/// cores' exact squared distance:
///   intersect   q ≤ R², decided exactly;
///   distance    √q − R when positive, else 0, correctly rounded (evaluated with MPFR);
///   depth       with OracleOptions::depth and intersect: R − √q when the cores are apart, else
///               √p + R with p the cores' exact squared depth, correctly rounded.
/// distance_squared, depth_squared and the hull counts are the cores' (exact rationals; the
/// swept answers are irrational in general). With both radii 0 this is solve(a, b, options).
/// Throws std::invalid_argument as solve does, and for a negative or non-finite radius.
OracleAnswer solve_swept(std::span<const Vec3> a, std::span<const Vec3> b, double radius_a,
                         double radius_b, const OracleOptions& options = {},
                         const OracleHints& hints = {});

/// Number of vertices of the convex hull of one cloud (see OracleAnswer::hull_vertices_a),
/// decided with exact predicates. Throws std::invalid_argument for an empty cloud or a
/// non-finite coordinate.
int hull_vertex_count(std::span<const Vec3> cloud);

/// Version string of the CGAL library the oracle was built with (for provenance).
std::string cgal_version();

}  // namespace gjklab::exact
