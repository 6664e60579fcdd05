// Options of the GJK queries, with their defaults in one place.
//
// Every tolerance says what it is relative to and whether it is squared. All defaults are
// scale-free: multiplying both shapes by 2^k leaves every decision unchanged, so distances
// scale by exactly 2^k where no overflow or underflow occurs.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "gjklab/geometry/enum_names.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// The floating-point type a GJK query (gjk-bool, the distance variants, EPA) runs in. The
/// queries are templates on the scalar type of their shapes; a study in float or long double
/// runs them on the clouds rounded to that type (geometry/scalar_cloud.hpp).
enum class ScalarPrecision : std::uint8_t {
  single_float,  ///< "float": IEEE binary32, what game and robotics engines run GJK in
  double_float,  ///< "double": IEEE binary64, the default
  long_double,   ///< "long double": x87 80-bit extended precision on x86-64
};

inline constexpr auto kScalarPrecisionNames = std::to_array<EnumName<ScalarPrecision>>({
    {ScalarPrecision::single_float, "float"},
    {ScalarPrecision::double_float, "double"},
    {ScalarPrecision::long_double, "long double"},
});
static_assert(in_value_order(kScalarPrecisionNames) &&
              ends_at(kScalarPrecisionNames, ScalarPrecision::long_double));

constexpr std::string_view to_string(ScalarPrecision v) {
  return name_of(kScalarPrecisionNames, v);
}

inline std::optional<ScalarPrecision> precision_from_string(std::string_view name) {
  return value_named(kScalarPrecisionNames, name);
}

/// How `gjk-bool` chooses its first search direction and first simplex point.
///
/// The centre starts use c = c_A − c_B, the difference of the shapes' interior points (for a
/// Polytope its vertex mean, computed at construction). c is a point of the hull of A − B but in
/// general not a support point. When a shape has no interior point, or c is zero or not finite
/// (coincident means, overflow), the centre starts fall back to `fixed_direction`.
enum class GjkBooleanStart : std::uint8_t {
  /// The first support point is taken in initial_direction and becomes the first simplex point;
  /// the search then heads from it towards the origin. Costs one support evaluation before the
  /// main loop, and cannot prove separation with it.
  fixed_direction,
  /// The first support point w is taken in d = −c; w·d < 0 proves separation after that one
  /// evaluation. Otherwise w is the first simplex point, as with fixed_direction (c is used
  /// only to choose a direction, never kept in the simplex).
  centre_direction,
  /// c is the first simplex point (no support evaluation) and d = −c the first direction, as
  /// in MPR's portal discovery. Separation is proved as above after one evaluation; an enclosing
  /// simplex may have c as a vertex, which is sound because c lies in the hull of A − B (up to
  /// the rounding of the two means), and saves one support evaluation on overlapping pairs.
  centre_point,
};

inline constexpr auto kGjkBooleanStartNames = std::to_array<EnumName<GjkBooleanStart>>({
    {GjkBooleanStart::fixed_direction, "fixed_direction"},
    {GjkBooleanStart::centre_direction, "centre_direction"},
    {GjkBooleanStart::centre_point, "centre_point"},
});
static_assert(in_value_order(kGjkBooleanStartNames) &&
              ends_at(kGjkBooleanStartNames, GjkBooleanStart::centre_point));

constexpr std::string_view to_string(GjkBooleanStart v) {
  return name_of(kGjkBooleanStartNames, v);
}

inline std::optional<GjkBooleanStart> boolean_start_from_string(std::string_view name) {
  return value_named(kGjkBooleanStartNames, name);
}

struct GjkBooleanDefaults {
  static constexpr int max_iterations = 64;
  static constexpr GjkBooleanStart start = GjkBooleanStart::centre_point;
  static constexpr bool recenter = true;
};

/// Options of `gjk-bool`, the simplex-walking boolean GJK.
struct GjkBooleanOptions {
  /// Upper bound on main-loop iterations. A main-loop iteration is a support evaluation after
  /// the first with fixed_direction and centre_direction (whose first evaluation counts as one
  /// iteration when it proves separation), and every support evaluation with centre_point.
  int max_iterations = GjkBooleanDefaults::max_iterations;
  /// First simplex point and search direction (see GjkBooleanStart).
  GjkBooleanStart start = GjkBooleanDefaults::start;
  /// First search direction (any length) of fixed_direction, and of the centre starts when
  /// they fall back to it; fixed so that runs are reproducible.
  Vec3 initial_direction = Vec3(1, 0, 0);
  /// Translate a pair of polytopes far from the origin exactly towards it before the query
  /// (geometry/recentring.hpp), so that support values are compared at the scale of the pair;
  /// false reproduces the naive query on the coordinates as given.
  bool recenter = GjkBooleanDefaults::recenter;
};

/// The stopping test of the distance queries, evaluated on the gap ‖v‖² − v·w between the
/// upper bound ‖v‖² and v·w, where v is the current closest point of the simplex and w the
/// support point of A − B in direction −v (the minimiser of v·x over A − B).
///
/// Every criterion bounds the error of v: with v* the exact closest point of A − B and d = ‖v*‖,
/// the Frank–Wolfe inequality ‖v − v*‖² ≤ ‖v‖² − d² ≤ 2(‖v‖² − v·w) holds, and the plane
/// v·x = v·w separates the origin from A − B, so d ≥ v·w/‖v‖.
enum class GjkConvergence : std::uint8_t {
  /// van den Bergen's test (the default): ‖v‖² − v·w ≤ relative_gap · ‖v‖², or
  /// ≤ absolute_gap_squared. Scale-free; bounds the relative distance error:
  /// (‖v‖ − d)/‖v‖ ≤ relative_gap.
  relative,
  /// ‖v‖² − v·w ≤ absolute_gap_squared (squared length units). Bounds the absolute error:
  /// ‖v − v*‖² ≤ 2 · absolute_gap_squared. Not scale-free.
  absolute,
  /// The Frank–Wolfe duality gap of min ‖x‖² over A − B at x = v, g = 2(‖v‖² − v·w) (the
  /// gradient 2v dotted with v − w), with g ≤ duality_gap_tolerance (squared length units).
  /// Bounds ‖v − v*‖² ≤ g and ‖v‖² − d² ≤ g (Montaut et al. 2022). Not scale-free.
  duality_gap,
};

inline constexpr auto kGjkConvergenceNames = std::to_array<EnumName<GjkConvergence>>({
    {GjkConvergence::relative, "relative"},
    {GjkConvergence::absolute, "absolute"},
    {GjkConvergence::duality_gap, "duality_gap"},
});
static_assert(in_value_order(kGjkConvergenceNames) &&
              ends_at(kGjkConvergenceNames, GjkConvergence::duality_gap));

constexpr std::string_view to_string(GjkConvergence v) {
  return name_of(kGjkConvergenceNames, v);
}

inline std::optional<GjkConvergence> convergence_from_string(std::string_view name) {
  return value_named(kGjkConvergenceNames, name);
}

/// How a GJK distance query picks its first support point when it starts cold.
enum class GjkDistanceStart : std::uint8_t {
  /// In initial_direction.
  fixed_direction,
  /// In −c, with c = c_A − c_B the difference of the shapes' interior points (a Polytope's
  /// vertex mean): the support point of A − B facing the origin from c, which is usually close
  /// to the closest point and saves iterations. Falls back to initial_direction when a shape
  /// has no interior point or c is zero or not finite.
  centre_direction,
};

inline constexpr auto kGjkDistanceStartNames = std::to_array<EnumName<GjkDistanceStart>>({
    {GjkDistanceStart::fixed_direction, "fixed_direction"},
    {GjkDistanceStart::centre_direction, "centre_direction"},
});
static_assert(in_value_order(kGjkDistanceStartNames) &&
              ends_at(kGjkDistanceStartNames, GjkDistanceStart::centre_direction));

constexpr std::string_view to_string(GjkDistanceStart v) {
  return name_of(kGjkDistanceStartNames, v);
}

inline std::optional<GjkDistanceStart> distance_start_from_string(std::string_view name) {
  return value_named(kGjkDistanceStartNames, name);
}

struct GjkDistanceDefaults {
  static constexpr GjkDistanceStart start = GjkDistanceStart::centre_direction;
  static constexpr int max_iterations = 128;
  static constexpr GjkConvergence convergence = GjkConvergence::relative;
  static constexpr double relative_gap = 1e-12;
  static constexpr double absolute_gap_squared = 0.0;
  static constexpr double duality_gap_tolerance = 0.0;
  static constexpr double relative_contact = 1e-13;
  static constexpr bool recenter = true;
};

/// Options of the GJK distance queries: `gjk-johnson`, `gjk-johnson-backup`, `gjk-sv`,
/// `gjk-voronoi` (and, through GjkNesterovOptions, `gjk-nesterov`).
struct GjkDistanceOptions {
  /// Upper bound on main-loop iterations (each costs one support call per shape).
  int max_iterations = GjkDistanceDefaults::max_iterations;
  /// Which stopping test applies (see GjkConvergence); only that criterion's tolerances are read.
  GjkConvergence convergence = GjkDistanceDefaults::convergence;
  /// `relative` criterion; relative, on squared lengths (dimensionless): converged when
  /// ‖v‖² − v·w ≤ relative_gap · ‖v‖², i.e. the lower bound v·w/‖v‖ is within a factor
  /// (1 − relative_gap) of the upper bound ‖v‖ (van den Bergen's test).
  double relative_gap = GjkDistanceDefaults::relative_gap;
  /// `relative` and `absolute` criteria; absolute, squared length units: converged when
  /// ‖v‖² − v·w ≤ absolute_gap_squared (for `relative`, a floor in addition to the relative
  /// test). The default 0 disables the floor, which keeps the query scale-invariant; with
  /// `absolute` and 0 the query stops only on a gap ≤ 0, a repeated support point or no progress.
  double absolute_gap_squared = GjkDistanceDefaults::absolute_gap_squared;
  /// `duality_gap` criterion; absolute, squared length units: converged when the Frank–Wolfe
  /// duality gap 2(‖v‖² − v·w) ≤ duality_gap_tolerance. With 0 (the default) the query stops
  /// only on a gap ≤ 0, a repeated support point or no progress.
  double duality_gap_tolerance = GjkDistanceDefaults::duality_gap_tolerance;
  /// Relative to the simplex size, not squared: the shapes are declared in contact when
  /// ‖v‖ ≤ relative_contact · max_i ‖y_i‖ over the simplex vertices y_i, i.e. when v is
  /// indistinguishable from the rounding noise of the points that produced it.
  double relative_contact = GjkDistanceDefaults::relative_contact;
  /// First search direction (any length). A fixed default keeps the query scale-invariant;
  /// pass the previous query's direction to warm-start a sequence of queries (or start from
  /// the previous query's final simplex with gjk_distance_warm_with).
  Vec3 initial_direction = Vec3(1, 0, 0);
  /// How a cold start picks its first support point (see GjkDistanceStart).
  GjkDistanceStart start = GjkDistanceDefaults::start;
  /// Translate a pair of polytopes far from the origin exactly towards it before the query
  /// (geometry/recentring.hpp), so that support values are compared at the scale of the pair;
  /// false reproduces the naive query on the coordinates as given. Answers are reported in the
  /// original frame.
  bool recenter = GjkDistanceDefaults::recenter;
};

struct GjkNesterovDefaults {
  static constexpr bool normalize_direction = false;
};

/// Options of `gjk-nesterov`: those of the distance queries (the stopping criterion, contact
/// test and iteration bound mean the same) and the momentum variant.
struct GjkNesterovOptions : GjkDistanceOptions {
  /// false (the default): the paper's schedule, δ_k = (k+1)/(k+3) and
  /// d_k = δ_k d_{k−1} + (1−δ_k) y_k. true: the normalised heuristic that coal applies to
  /// shapes that are not strictly convex, δ_k = (k+2)/(k+3) and
  /// d_k = δ_k d_{k−1}/‖d_{k−1}‖ + (1−δ_k) y_k/‖y_k‖ (on this testbed's point clouds it costs
  /// more iterations than the paper's schedule; see gjk_nesterov.hpp).
  bool normalize_direction = GjkNesterovDefaults::normalize_direction;
};

}  // namespace gjklab
