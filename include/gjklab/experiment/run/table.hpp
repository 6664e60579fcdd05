// A table's content, computed once, and the forms it is printed in: the aligned text that
// `gjklab run` and `gjklab inspect` print, a Markdown pipe table (for a README) and a LaTeX
// booktabs tabular (for a paper). The cells are text already formatted, numbers with their
// precision, so every form shows the same numbers; a renderer only lays them out.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/geometry/enum_names.hpp"

namespace gjklab::experiment {

struct TableColumn {
  std::string header;
  bool right = false;  ///< right-aligned (numbers), else left-aligned
  /// The text form: the column's least width, and the spaces before it (none before the first).
  int text_width = 0;
  int text_gap = 1;
};

struct TableRow {
  std::vector<std::string> cells;  ///< one per column
  /// The first row of a group (a family's rows): LaTeX puts a rule above it, between groups.
  bool group_start = false;
};

struct Table {
  /// What the table shows, e.g. "results/step_limit.h5: per algorithm"; the Markdown and
  /// LaTeX forms print it above the table (LaTeX as a comment), the text form does not.
  std::string caption;
  std::vector<TableColumn> columns;
  std::vector<TableRow> rows;
};

enum class TableFormat : std::uint8_t {
  text,      ///< columns aligned with spaces, as the commands have always printed them
  markdown,  ///< a pipe table, numbers right-aligned
  latex,     ///< \begin{tabular} with \toprule, \midrule, \bottomrule (the booktabs package)
};
inline constexpr auto kTableFormatNames = std::to_array<EnumName<TableFormat>>({
    {TableFormat::text, "text"},
    {TableFormat::markdown, "markdown"},
    {TableFormat::latex, "latex"},
});
static_assert(in_value_order(kTableFormatNames) && ends_at(kTableFormatNames, TableFormat::latex));
constexpr std::string_view to_string(TableFormat f) {
  return name_of(kTableFormatNames, f);
}
inline std::optional<TableFormat> table_format_from_string(std::string_view name) {
  return value_named(kTableFormatNames, name);
}

/// Prints the table in the format.
void render(std::ostream& out, const Table& table, TableFormat format);

void render_text(std::ostream& out, const Table& table);
void render_markdown(std::ostream& out, const Table& table);
void render_latex(std::ostream& out, const Table& table);

/// The text with LaTeX's special characters escaped (_ % & # $ { } ~ ^ \ and < > |, which
/// the default font encoding would print as other glyphs), for a cell of a tabular.
std::string latex_escape(std::string_view text);

}  // namespace gjklab::experiment
