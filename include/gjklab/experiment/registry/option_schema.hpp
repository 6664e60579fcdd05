// An algorithm's options as data: one row per key, naming the member of AlgorithmOptions it
// sets and the values it accepts. Parsing and validation (experiment files, sweeps, the Python
// module), describing into the archive and replay all walk the rows of the registry entry
// (AlgorithmInfo::options), so a key is either taken and applied, or refused: never validated
// and then ignored.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string_view>
#include <variant>

#include "gjklab/geometry/types.hpp"
#include "gjklab/gjk/options.hpp"

namespace gjklab::experiment {

struct AlgorithmOptions;

/// Where a key's value lives: a function from the options to the member (a captureless
/// lambda), so that a row can reach a member of a nested options struct.
template <class T>
using OptionAccess = T& (*)(AlgorithmOptions&);

/// The member's type decides how its text reads and writes: an integer count, a real number,
/// a boolean, a direction "x y z", or one of an enum's names.
using OptionMember =
    std::variant<OptionAccess<int>, OptionAccess<double>, OptionAccess<bool>, OptionAccess<Vec3>,
                 OptionAccess<ScalarPrecision>, OptionAccess<GjkBooleanStart>,
                 OptionAccess<GjkDistanceStart>, OptionAccess<GjkConvergence>>;

/// The values a number accepts (every value must also be finite; a count is an integer >= 1).
struct OptionRange {
  double min = -std::numeric_limits<double>::infinity();
  bool min_exclusive = false;  ///< min itself is refused (a tolerance that must be > 0)
  double max = std::numeric_limits<double>::infinity();
  /// How an error states a bounded count's range, e.g. "[4, 2^26]".
  std::string_view text = {};
};

inline constexpr OptionRange kNonNegative{.min = 0};
inline constexpr OptionRange kPositive{.min = 0, .min_exclusive = true};

/// Who may set a key.
enum class OptionUse : std::uint8_t {
  setting,   ///< an experiment, a sweep or the Python module sets it; archived and replayed
  recorded,  ///< set elsewhere (e.g. the [oracle] table); archived and replayed only
};

struct OptionRow {
  std::string_view key;
  OptionMember member;
  /// What the value means, in one phrase with its unit (relative or absolute, squared or
  /// not), for `gjklab names` and the tools that list options.
  std::string_view meaning;
  OptionRange range = {};
  OptionUse use = OptionUse::setting;
};

using OptionSchema = std::span<const OptionRow>;

// The option schemas of the registered algorithms (src/experiment/registry/algorithm_options.cpp).
OptionSchema gjk_boolean_option_schema();
OptionSchema gjk_distance_option_schema();  ///< gjk_distance (gjk-polyak)
/// The GJK distance variants with a sub-algorithm: gjk_distance, precision and warm_start.
OptionSchema gjk_variant_option_schema();
OptionSchema gjk_nesterov_option_schema();
OptionSchema epa_option_schema();
OptionSchema libccd_option_schema();
OptionSchema libccd_depth_option_schema();
OptionSchema sat_option_schema();
OptionSchema fcl_option_schema();
OptionSchema exact_option_schema();

}  // namespace gjklab::experiment
