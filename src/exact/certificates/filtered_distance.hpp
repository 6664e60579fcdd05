// Internal to src/exact/: the distance certificate decided in floating point where that is
// provably right, before the exact certificate (distance_certificate.cpp). No CGAL here.
#pragma once

#include <optional>
#include <span>

#include "gjklab/exact/certificate.hpp"

namespace gjklab::exact::detail {

/// The hint's own simplex certified without exact arithmetic wherever a floating-point
/// evaluation with a proven error bound decides: that the origin's nearest point v of the
/// simplex's hull lies inside it (every barycentric weight > 0), that every point of A and B
/// lies on its side of the planes through the closest points orthogonal to v (points within
/// the error bound of a plane, and only those, are decided exactly in integers), and the
/// nearest doubles of the distance and of the witness points (in long double, with a bound).
/// The exact squared distance is a Rational made from the feature's points on first use.
/// nullopt when any step is too close to call, the hint does not hold, its pairs repeat, or an
/// index is out of range: the exact certificate then decides. Never certifies what the exact
/// certificate would not: both answers, when given, are the same.
std::optional<DistanceCertificate> certify_distance_filtered(std::span<const Vec3> a,
                                                             std::span<const Vec3> b,
                                                             const DistanceHint& hint);

/// The nearest doubles of Σ λ_k x_k (at most four points), per coordinate, for weights λ_k ≥ 0
/// each known to a relative error of at most 5·2^-64, when a long double evaluation with an error
/// bound shows them; nullopt otherwise (then the caller rounds exactly).
std::optional<Vec3> nearest_weighted_sum(std::span<const long double> weights,
                                         std::span<const Vec3> points);

/// The nearest doubles of the hulls' common point Σ λ_k a_k = Σ λ_k b_k, when the points
/// a_k − b_k enclose the origin strictly (every barycentric weight λ_k > 0) and a double-word
/// evaluation with a proven error bound decides that and each coordinate's rounding
/// (filtered_tetrahedron.cpp); nullopt otherwise (the origin on a face, a flat tetrahedron, a
/// rounding too close to call, a coordinate out of the normal range).
std::optional<Vec3> enclosed_origin_witness(std::span<const Vec3, 4> a, std::span<const Vec3, 4> b);

/// The exact certificate alone: exact GJK from the hint for at most max_steps steps
/// (distance_certificate.cpp). certify_distance tries the filtered one first.
std::optional<DistanceCertificate> certify_distance_exact(std::span<const Vec3> a,
                                                          std::span<const Vec3> b,
                                                          const DistanceHint& hint, int max_steps);

}  // namespace gjklab::exact::detail
