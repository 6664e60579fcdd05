#include "gjklab/query_table.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>

namespace gjklab::cli {

namespace {

using Json = nlohmann::ordered_json;

/// A JSON value as a table cell: numbers with 12 significant digits (the JSON lines keep all
/// 17), booleans as yes/no, vectors in brackets, absent as "-".
std::string cell(const Json& j) {
  if (j.is_null()) return "-";
  if (j.is_boolean()) return j.get<bool>() ? "yes" : "no";
  if (j.is_number_float()) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.12g", j.get<double>());
    return buffer;
  }
  if (j.is_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < j.size(); ++k)
      out += (k ? " " : "") + cell(j[k]);
    return out + "]";
  }
  if (j.is_string()) return j.get<std::string>();
  return j.dump();
}

}  // namespace

void write_answer_table(std::ostream& out, const std::vector<std::string>& lines) {
  static const std::vector<std::string> kColumns = {"id",          "algorithm", "intersect",
                                                    "distance",    "depth",     "iterations",
                                                    "termination", "method",    "error"};
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> used(kColumns.size(), false);
  for (const std::string& line : lines) {
    const Json j = Json::parse(line);
    std::vector<std::string> row;
    for (std::size_t c = 0; c < kColumns.size(); ++c) {
      const auto found = j.find(kColumns[c]);
      row.push_back(found == j.end() ? "-" : cell(*found));
      used[c] = used[c] || found != j.end();
    }
    rows.push_back(std::move(row));
  }
  std::vector<std::size_t> width(kColumns.size(), 0);
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    width[c] = kColumns[c].size();
    for (const auto& row : rows)
      width[c] = std::max(width[c], row[c].size());
  }
  auto write_row = [&](const std::vector<std::string>& row) {
    std::string text;
    for (std::size_t c = 0; c < kColumns.size(); ++c)
      if (used[c]) text += row[c] + std::string(width[c] - row[c].size() + 2, ' ');
    while (!text.empty() && text.back() == ' ')
      text.pop_back();
    out << text << "\n";
  };
  write_row(kColumns);
  for (const auto& row : rows)
    write_row(row);
}

}  // namespace gjklab::cli
