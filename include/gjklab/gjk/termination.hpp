// Why a query stopped. Every algorithm in gjklab reports one of these; none returns a sentinel.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "gjklab/geometry/enum_names.hpp"

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

inline constexpr auto kTerminationNames = std::to_array<EnumName<Termination>>({
    {Termination::converged, "converged"},
    {Termination::step_limit, "step_limit"},
    {Termination::no_progress, "no_progress"},
    {Termination::degenerate_simplex, "degenerate_simplex"},
    {Termination::cycling, "cycling"},
    {Termination::numerical_failure, "numerical_failure"},
    {Termination::invalid_input, "invalid_input"},
});
static_assert(in_value_order(kTerminationNames) &&
              ends_at(kTerminationNames, Termination::invalid_input));

inline constexpr auto kAllTerminations = values_of(kTerminationNames);

constexpr std::string_view to_string(Termination t) {
  return name_of(kTerminationNames, t);
}

inline std::optional<Termination> termination_from_string(std::string_view name) {
  return value_named(kTerminationNames, name);
}

}  // namespace gjklab
