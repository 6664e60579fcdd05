// results/README.md's schema tables, rendered from the schema's descriptors (archive_schema.hpp)
// so that the document cannot drift from what the writer writes: a unit test compares the
// document with its rendering, and `gjklab schema --update FILE` rewrites it.

#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "archive_schema.hpp"
#include "scene_schema.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "hdf5_util.hpp"

namespace gjklab::experiment {

namespace {

/// Groups of the scene archive are named "scene/GROUP" in the documents' markers.
constexpr std::string_view kScenePrefix = "scene/";

constexpr std::string_view kBeginMarker = "<!-- schema table: ";
constexpr std::string_view kMarkerClose = " -->";
constexpr std::string_view kEndMarker = "<!-- end schema table -->";

/// Characters as a Markdown viewer counts them: UTF-8 code points ("×" and "‖" are one each).
std::size_t display_width(std::string_view text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

std::string padded(std::string_view text, std::size_t width) {
  std::string out(text);
  out.append(width - std::min(width, display_width(text)), ' ');
  return out;
}

/// A table with the first two columns aligned; the third (prose) is left as it is.
std::string markdown_table(const std::array<std::string_view, 3>& headings,
                           const std::vector<std::array<std::string, 3>>& rows) {
  std::array<std::size_t, 2> width{display_width(headings[0]), display_width(headings[1])};
  for (const auto& row : rows)
    for (std::size_t k = 0; k < 2; ++k)
      width[k] = std::max(width[k], display_width(row[k]));
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "| " + string&&.
  const auto line = [&width](std::string_view a, std::string_view b, std::string_view c) {
    std::string text = "| ";
    text += padded(a, width[0]);
    text += " | ";
    text += padded(b, width[1]);
    text += " | ";
    text += c;
    text += " |\n";
    return text;
  };
  std::string out = line(headings[0], headings[1], headings[2]);
  for (const std::size_t w : {width[0], width[1], display_width(headings[2])}) {
    out += '|';
    out.append(w + 2, '-');
  }
  out += "|\n";
  for (const auto& row : rows)
    out += line(row[0], row[1], row[2]);
  return out;
}

std::vector<std::array<std::string, 3>> table_rows(const std::vector<ArchiveColumn>& columns) {
  std::vector<std::array<std::string, 3>> rows;
  for (const ArchiveColumn& c : columns)
    rows.push_back({"`" + c.name + "`", c.type, c.meaning});
  return rows;
}

/// The position of the next line at or after `from` that starts with `marker`, or npos.
std::size_t find_line(std::string_view document, std::string_view marker, std::size_t from) {
  for (std::size_t at = document.find(marker, from); at != std::string_view::npos;
       at = document.find(marker, at + 1))
    if (at == 0 || document[at - 1] == '\n') return at;
  return std::string_view::npos;
}

/// One line of the enum values' list: "- `Name`: `first` = 0, `second` = 1, ...".
template <class E>
std::string enum_values_line() {
  std::string out = "- `";
  out += schema::enum_type_name<E>();
  out += "`:";
  const char* separator = " ";
  for (const auto& [name, value] : h5::enum_members<E>()) {
    out += separator;
    out += '`';
    out += name;
    out += "` = ";
    out += std::to_string(value);
    separator = ", ";
  }
  return out + "\n";
}

template <class... E>
std::string enum_values(schema::EnumList<E...>) {
  return (enum_values_line<E>() + ...);
}

}  // namespace

std::string archive_schema_table(std::string_view group) {
  if (group.starts_with(kScenePrefix)) {
    const auto rows = scene_schema::rows(group.substr(kScenePrefix.size()));
    if (!rows)
      throw std::invalid_argument("no scene archive schema table '" + std::string(group) + "'");
    return markdown_table({group == "scene/root" ? "attribute" : "dataset", "type", "meaning"},
                          *rows);
  }
  if (group == "enums") return enum_values(schema::ArchiveEnums{});
  if (group == "root")
    return markdown_table({"attribute", "type", "meaning"}, table_rows(archive_root_attributes()));
  const std::vector<ArchiveColumn> columns = archive_columns(group);
  if (columns.empty())
    throw std::invalid_argument("no archive schema table '" + std::string(group) + "'");
  // The per-case groups give units; the others' columns are indices and points.
  const bool per_case = group == "cases" || group == "exact" || group == "algorithms";
  return markdown_table({"dataset", "type", per_case ? "unit / meaning" : "meaning"},
                        table_rows(columns));
}

std::string with_schema_tables(std::string_view document) {
  std::string out;
  std::size_t at = 0;
  for (std::size_t begin;
       (begin = find_line(document, kBeginMarker, at)) != std::string_view::npos;) {
    const std::size_t name_at = begin + kBeginMarker.size();
    const std::size_t close = document.find(kMarkerClose, name_at);
    const std::size_t line_end = document.find('\n', name_at);
    if (close == std::string_view::npos || line_end == std::string_view::npos || close > line_end)
      throw std::invalid_argument("a schema table's opening line does not end in \" -->\"");
    const std::string_view group = document.substr(name_at, close - name_at);
    const std::size_t end = find_line(document, kEndMarker, line_end);
    if (end == std::string_view::npos)
      throw std::invalid_argument("schema table '" + std::string(group) + "' has no line \"" +
                                  std::string(kEndMarker) + "\"");
    out += document.substr(at, line_end + 1 - at);
    out += archive_schema_table(group);
    at = end;
  }
  out += document.substr(at);
  return out;
}

}  // namespace gjklab::experiment
