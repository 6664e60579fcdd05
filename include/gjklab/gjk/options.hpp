// Options of the GJK queries, with their defaults in one place.
//
// Every tolerance says what it is relative to and whether it is squared. All defaults are
// scale-free: multiplying both shapes by 2^k leaves every decision unchanged, so distances
// scale by exactly 2^k where no overflow or underflow occurs.
#pragma once

#include "gjklab/geometry/types.hpp"

namespace gjklab {

struct GjkBooleanDefaults {
  static constexpr int max_iterations = 64;
};

/// Options of `gjk-bool`, the simplex-walking boolean GJK.
struct GjkBooleanOptions {
  /// Upper bound on main-loop iterations (support evaluations after the first).
  int max_iterations = GjkBooleanDefaults::max_iterations;
  /// First search direction (any length); fixed by default so runs are reproducible.
  Vec3 initial_direction = Vec3(1, 0, 0);
};

struct GjkDistanceDefaults {
  static constexpr int max_iterations = 128;
  static constexpr double relative_gap = 1e-12;
  static constexpr double absolute_gap_squared = 0.0;
  static constexpr double relative_contact = 1e-13;
};

/// Options of `gjk-johnson` (and later distance variants).
struct GjkDistanceOptions {
  /// Upper bound on main-loop iterations (each costs one support call per shape).
  int max_iterations = GjkDistanceDefaults::max_iterations;
  /// Relative, on squared lengths (dimensionless): converged when
  /// ‖v‖² − v·w ≤ relative_gap · ‖v‖², i.e. the lower bound v·w/‖v‖ is within a factor
  /// (1 − relative_gap) of the upper bound ‖v‖ (van den Bergen's test).
  double relative_gap = GjkDistanceDefaults::relative_gap;
  /// Absolute, squared length units: also converged when ‖v‖² − v·w ≤ absolute_gap_squared.
  /// The default 0 disables this floor, which keeps the query scale-invariant.
  double absolute_gap_squared = GjkDistanceDefaults::absolute_gap_squared;
  /// Relative to the simplex size, not squared: the shapes are declared in contact when
  /// ‖v‖ ≤ relative_contact · max_i ‖y_i‖ over the simplex vertices y_i, i.e. when v is
  /// indistinguishable from the rounding noise of the points that produced it.
  double relative_contact = GjkDistanceDefaults::relative_contact;
  /// First search direction (any length). A fixed default keeps the query scale-invariant;
  /// pass the previous query's direction to warm-start a sequence of queries.
  Vec3 initial_direction = Vec3(1, 0, 0);
};

}  // namespace gjklab
