// Certificates: exact answers verified from a floating-point hint in O(|A| + |B|) work.
//
// Distance and intersection. Starting from the hint's simplex (index pairs into A and B), the
// certificate computes, exactly in integers, the point v of the simplex's hull closest to the
// origin. v = 0 proves intersection (the origin is a convex combination of points of A − B).
// Otherwise v is the exact squared distance's witness when the plane through v orthogonal to v
// supports A − B: min over a of v·a − max over b of v·b ≥ v·v (then every point of A − B is at
// least ‖v‖ from the origin, and v itself is a point of A − B). When that test fails, the
// violating support point is added to the simplex and the step repeats: exact GJK, warm-started
// from the hint, for at most `max_steps` steps (exact arithmetic cannot cycle; the bound only
// caps the work before the QP takes over).
//
// Depth. From a closed convex polytope P ⊂ A − B (the hint's vertices are points of A − B) that
// holds the origin, the distance from the origin to the boundary of P is a lower bound of the
// depth, attained at P's nearest face plane n·x = c. If that plane supports A − B as well
// (max over A − B of n·w = c), it is also an upper bound, and the depth squared is c²/‖n‖².
// P is checked exactly: every directed edge paired with its reverse, each vertex's faces one
// fan, Euler characteristic 2, every vertex on or behind every face plane with some vertex
// strictly behind, and the origin on or behind every face plane. When the hint's faces fail
// these checks, they are replaced once by the exact hull of its points (still points of
// A − B). When P passes but its nearest face does not support A − B, exact EPA steps add the
// violating support point (at most `max_steps`), and each grown polytope is checked again.
//
// All arithmetic is exact on the input doubles (integers scaled by a common power of two);
// floating-point filters with proven error bounds decide nearly every comparison, and only the
// near ties are redone exactly.
#pragma once

#include <optional>
#include <span>

#include "gjklab/exact/hint.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::exact {

struct DistanceCertificate {
  bool intersect = false;
  Rational distance_squared;  ///< exact, in lowest terms (0 when intersecting)
  double distance = 0;        ///< √distance_squared, correctly rounded
  /// The exact closest points p ∈ conv(A) and q ∈ conv(B) (p = q when intersecting is not
  /// tracked: both are then the common point found), each rounded to the nearest double.
  Vec3 witness_a = Vec3::Zero();
  Vec3 witness_b = Vec3::Zero();
  /// The final simplex as index pairs (the feature pair that realises the distance).
  DistanceHint feature;
  /// Exact GJK steps taken beyond the hint (0: the hint itself was certified).
  int repair_steps = 0;
};

/// Certifies the distance (or intersection) of the hulls of two non-empty clouds of finite
/// points from a hint; nullopt when no certificate was found within max_steps (then the caller
/// falls back to the QP). Indices out of range in the hint are ignored; an empty or unusable
/// hint starts exact GJK from the pair (0, 0).
std::optional<DistanceCertificate> certify_distance(std::span<const Vec3> a,
                                                    std::span<const Vec3> b,
                                                    const DistanceHint& hint,
                                                    int max_steps = kCertificateMaxSteps);

struct DepthCertificate {
  Rational depth_squared;  ///< exact, in lowest terms
  /// The outward unit normal of the supporting face plane that realises the depth (the
  /// direction in which B must move by the depth), rounded: each coordinate within a few ulps.
  Vec3 normal = Vec3::UnitX();
  /// Exact EPA steps taken beyond the hint (0: the hint's own nearest face was certified).
  int repair_steps = 0;
};

/// Certifies the squared penetration depth of an intersecting pair from an EPA polytope;
/// nullopt when any check fails (the caller then falls back to the Minkowski hull). When the
/// polytope passes every check but its nearest face does not support A − B, up to max_steps
/// exact EPA steps add the violating support point (and the result is checked again).
std::optional<DepthCertificate> certify_depth(std::span<const Vec3> a, std::span<const Vec3> b,
                                              const DepthHint& hint,
                                              int max_steps = kCertificateMaxSteps);

}  // namespace gjklab::exact
