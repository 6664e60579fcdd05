// Options of the registered algorithms by key: which keys each algorithm takes, setting them
// from text (experiment files, sweeps and archives all go through it) and describing them as
// text (archives). All of them walk the rows of the algorithm's option schema, given by its
// registry entry (AlgorithmInfo::options, option_schema.hpp).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gjklab/experiment/config/config.hpp"

namespace gjklab::experiment {

/// The option keys an algorithm takes (beyond `name`), e.g. max_iterations, relative_gap.
std::vector<std::string_view> option_keys(std::string_view algorithm);

/// Sets one option of spec from its text: a number ("1e-12", "64"), a direction ("1 0 0"),
/// a boolean ("true"/"false") or a criterion name ("relative"). Throws std::invalid_argument
/// with the problem (key not taken by the algorithm, malformed, out of range).
void set_option(AlgorithmSpec& spec, std::string_view key, std::string_view text);

/// (key, text) of every option the algorithm takes; numbers round-trip exactly.
std::vector<std::pair<std::string, std::string>> describe_options(const AlgorithmSpec& spec);

/// Rebuilds a spec from describe_options' text (as archived). Throws std::invalid_argument.
AlgorithmSpec spec_from_description(const std::string& name,
                                    const std::vector<std::pair<std::string, std::string>>& text);

/// What an option's value may be, in the terms of the parser that reads it: its type
/// ("integer", "number", "boolean", "direction" or "choice"), a choice's names in order, and
/// the accepted values in words ("a number >= 0", "one of relative, absolute, duality_gap").
struct OptionValues {
  std::string_view type;
  std::vector<std::string_view> choices;
  std::string accepts;
};
OptionValues option_values(const OptionRow& row);

/// Shortest decimal text that reads back as the same double.
std::string round_trip(double x);

}  // namespace gjklab::experiment
