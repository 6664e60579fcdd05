// Why a query stopped. Every algorithm in gjklab reports one of these; none returns a sentinel.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace gjklab {

enum class Termination : std::uint8_t {
  converged,           ///< the algorithm's own stopping test was met: the answer is final
  step_limit,          ///< max_iterations reached: the answer is the best one at that point
  no_progress,         ///< an iteration failed to improve the bound (rounding noise dominates)
  degenerate_simplex,  ///< the sub-algorithm found no valid sub-simplex (e.g. flat tetrahedron)
  cycling,             ///< a support point seen before came back after being dropped
  numerical_failure,   ///< a NaN or infinity appeared in the computation
  invalid_input,       ///< the input was rejected before any iteration (empty, non-finite)
};

inline constexpr std::array<Termination, 7> kAllTerminations = {
    Termination::converged,          Termination::step_limit, Termination::no_progress,
    Termination::degenerate_simplex, Termination::cycling,    Termination::numerical_failure,
    Termination::invalid_input};

constexpr std::string_view to_string(Termination t) {
  switch (t) {
    case Termination::converged:
      return "converged";
    case Termination::step_limit:
      return "step_limit";
    case Termination::no_progress:
      return "no_progress";
    case Termination::degenerate_simplex:
      return "degenerate_simplex";
    case Termination::cycling:
      return "cycling";
    case Termination::numerical_failure:
      return "numerical_failure";
    case Termination::invalid_input:
      return "invalid_input";
  }
  return "unknown";
}

inline std::optional<Termination> termination_from_string(std::string_view name) {
  for (Termination t : kAllTerminations)
    if (to_string(t) == name) return t;
  return std::nullopt;
}

}  // namespace gjklab
