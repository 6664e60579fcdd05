// The fields of one algorithm's answer, named once: `gjklab query` prints them as a JSON line,
// the Python module returns them as a dict (QueryResult.as_dict), in the same order.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "gjklab/experiment/registry/algorithms.hpp"

namespace gjklab::experiment {

/// A field's value: a flag, a count, a number (length units), a name or decimal integer
/// (exact rationals' numerators and denominators), or a point or direction (world frame).
using AnswerValue = std::variant<bool, std::int64_t, double, std::string, Vec3>;
using AnswerFields = std::vector<std::pair<std::string, AnswerValue>>;

/// algorithm, precision (when not double), radii (when swept), intersect, distance, depth,
/// normal, witnesses, the proven bracket, iterations, support calls, termination, and the
/// exact answer's rationals and methods when the algorithm is exact (`core_` keys for swept
/// shapes: the rationals are the cores').
AnswerFields answer_fields(std::string_view algorithm, const Outcome& o, ScalarPrecision precision,
                           double radius_a, double radius_b);

}  // namespace gjklab::experiment
