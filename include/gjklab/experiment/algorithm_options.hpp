// Options of the registered algorithms by key: which keys each algorithm takes, setting them
// from numbers (experiment files, sweeps, archives) and describing them as text (archives).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gjklab/experiment/config.hpp"

namespace gjklab::experiment {

/// The option keys an algorithm takes (beyond `name`), e.g. max_iterations, relative_gap.
std::vector<std::string_view> option_keys(std::string_view algorithm);

/// Number of values an option takes: 3 for initial_direction, else 1.
int option_arity(std::string_view key);

/// Sets one option of spec from its value(s). Throws std::invalid_argument with the problem
/// (key not taken by the algorithm, wrong number of values, out of range).
void set_option(AlgorithmSpec& spec, std::string_view key, std::span<const double> values);

/// (key, value) text of every option the algorithm takes; numbers round-trip exactly, a
/// direction is "x y z".
std::vector<std::pair<std::string, std::string>> describe_options(const AlgorithmSpec& spec);

/// Rebuilds a spec from describe_options' text (as archived). Throws std::invalid_argument.
AlgorithmSpec spec_from_description(const std::string& name,
                                    const std::vector<std::pair<std::string, std::string>>& text);

}  // namespace gjklab::experiment
