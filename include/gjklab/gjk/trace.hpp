// Per-iteration traces of the GJK queries, delivered to an optional observer.
//
// A query builds a trace record only when its observer is enabled (a compile-time flag), and
// the record only reads values the query computes anyway: traced and untraced runs execute
// the same arithmetic and return bit-identical results.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "gjklab/geometry/enum_names.hpp"
#include "gjklab/gjk/simplex.hpp"

namespace gjklab {

/// Which branch of the GJK loop fired in an iteration (`continued`: none, the loop goes on).
enum class GjkStep : std::uint8_t {
  continued,         ///< the simplex was reduced and ‖v‖ decreased
  gap_converged,     ///< ‖v‖² − v·w within tolerance, or within rounding and ‖v‖ stuck
  repeated_support,  ///< w is already a vertex of the simplex
  contact,           ///< the simplex encloses the origin, or ‖v‖ is rounding noise
  separated,         ///< (boolean GJK) the support point did not pass the origin
  degenerate,        ///< the sub-algorithm accepted no subset, or a flat one after separation
  no_progress,       ///< ‖v‖ did not decrease
  non_finite,        ///< a NaN or infinity appeared
  step_limit,        ///< the iteration bound was reached
  momentum_restart,  ///< (Nesterov GJK) the momentum step failed; plain GJK directions from now on
  /// ‖v‖ did not decrease in floating point, but w passed v·w < ‖v‖² by more than the rounding
  /// of v·w, so exact GJK would have progressed: the simplex with w is kept (bounded count)
  stalled,
  /// (boolean GJK) the walk came back to an earlier state; the GJK distance walk decides
  cycled,
};

inline constexpr auto kGjkStepNames = std::to_array<EnumName<GjkStep>>({
    {GjkStep::continued, "continued"},
    {GjkStep::gap_converged, "gap_converged"},
    {GjkStep::repeated_support, "repeated_support"},
    {GjkStep::contact, "contact"},
    {GjkStep::separated, "separated"},
    {GjkStep::degenerate, "degenerate"},
    {GjkStep::no_progress, "no_progress"},
    {GjkStep::non_finite, "non_finite"},
    {GjkStep::step_limit, "step_limit"},
    {GjkStep::momentum_restart, "momentum_restart"},
    {GjkStep::stalled, "stalled"},
    {GjkStep::cycled, "cycled"},
});
static_assert(in_value_order(kGjkStepNames) && ends_at(kGjkStepNames, GjkStep::cycled));

constexpr std::string_view to_string(GjkStep v) {
  return name_of(kGjkStepNames, v);
}

/// One iteration of a GJK query.
struct GjkIterationTrace {
  int iteration = 0;
  Vec3 direction =
      Vec3::Zero();       ///< search direction (−v for the distance query; −d_k for Nesterov)
  SimplexVertex support;  ///< the support point w = a − b taken in this iteration
  double v_norm_squared = 0;  ///< ‖v‖² before the step (distance query)
  double v_dot_w = 0;         ///< v·w (distance query)
  double lower_bound = 0;     ///< best lower bound of the distance so far, max(0, v·w/‖v‖)
  Simplex simplex;            ///< the simplex after the step
  std::array<double, 4> weights{};  ///< barycentric weights of the simplex points (distance)
  GjkStep step = GjkStep::continued;
};

/// The default observer: disabled, so no trace is built.
struct NoTrace {
  static constexpr bool enabled = false;
  void on_iteration(const GjkIterationTrace&) {}
};

/// An observer that keeps every iteration.
struct TraceRecorder {
  static constexpr bool enabled = true;
  std::vector<GjkIterationTrace> iterations;
  void on_iteration(const GjkIterationTrace& t) { iterations.push_back(t); }
};

}  // namespace gjklab
