// `gjklab query --format table`: the JSON answer lines as an aligned table for a terminal.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace gjklab::cli {

/// The answers as an aligned table, one row per answer line, for people at a terminal: the
/// columns every answer has, then the distance, depth and exact fields that some have (a column
/// no line has is left out).
void write_answer_table(std::ostream& out, const std::vector<std::string>& lines);

}  // namespace gjklab::cli
