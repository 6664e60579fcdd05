#include "gjklab/experiment/run/table.hpp"

#include <algorithm>
#include <iterator>
#include <ostream>
#include <utility>

namespace gjklab::experiment {

namespace {

// What LaTeX would read as a command, and the characters whose glyph its default font encoding
// (OT1) replaces, with the text that prints them.
constexpr std::pair<char, std::string_view> kLatexSpecial[] = {
    {'\\', "\\textbackslash{}"},
    {'~', "\\textasciitilde{}"},
    {'^', "\\textasciicircum{}"},
    {'<', "\\textless{}"},
    {'>', "\\textgreater{}"},
    {'|', "\\textbar{}"},
    {'_', "\\_"},
    {'%', "\\%"},
    {'&', "\\&"},
    {'#', "\\#"},
    {'$', "\\$"},
    {'{', "\\{"},
    {'}', "\\}"},
};

/// Each column's width in the text form: its least width, or its widest cell or header.
std::vector<std::size_t> text_widths(const Table& table) {
  std::vector<std::size_t> widths;
  for (const TableColumn& c : table.columns)
    widths.push_back(std::max(static_cast<std::size_t>(c.text_width), c.header.size()));
  for (const TableRow& row : table.rows)
    for (std::size_t i = 0; i < row.cells.size() && i < widths.size(); ++i)
      widths[i] = std::max(widths[i], row.cells[i].size());
  return widths;
}

/// One line of the text form. A left-aligned last column is not padded, so that no line ends
/// in spaces.
void text_line(std::ostream& out, const Table& table, const std::vector<std::size_t>& widths,
               const std::vector<std::string>& cells) {
  for (std::size_t i = 0; i < table.columns.size(); ++i) {
    const TableColumn& column = table.columns[i];
    const std::string& cell = i < cells.size() ? cells[i] : std::string();
    const std::string pad(widths[i] - std::min(widths[i], cell.size()), ' ');
    if (i > 0) out << std::string(static_cast<std::size_t>(column.text_gap), ' ');
    const bool last = i + 1 == table.columns.size();
    out << (column.right ? pad + cell : last ? cell : cell + pad);
  }
  out << "\n";
}

std::vector<std::string> headers(const Table& table) {
  std::vector<std::string> out;
  for (const TableColumn& c : table.columns)
    out.push_back(c.header);
  return out;
}

/// A Markdown cell: a '|' would end it.
std::string markdown_cell(const std::string& text) {
  std::string out;
  for (const char c : text)
    out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

void markdown_line(std::ostream& out, const std::vector<std::string>& cells) {
  out << "|";
  for (const std::string& cell : cells)
    out << " " << markdown_cell(cell) << " |";
  out << "\n";
}

void latex_line(std::ostream& out, const std::vector<std::string>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i)
    out << (i > 0 ? " & " : "") << latex_escape(cells[i]);
  out << " \\\\\n";
}

/// A caption as one LaTeX comment line (a line break would end the comment).
std::string latex_comment(const std::string& caption) {
  std::string line = caption;
  std::replace(line.begin(), line.end(), '\n', ' ');
  return "% " + line + "\n";
}

}  // namespace

void render_text(std::ostream& out, const Table& table) {
  const std::vector<std::size_t> widths = text_widths(table);
  text_line(out, table, widths, headers(table));
  for (const TableRow& row : table.rows)
    text_line(out, table, widths, row.cells);
}

void render_markdown(std::ostream& out, const Table& table) {
  if (!table.caption.empty()) out << table.caption << "\n\n";
  markdown_line(out, headers(table));
  out << "|";
  for (const TableColumn& c : table.columns)
    out << (c.right ? "---:|" : "---|");
  out << "\n";
  for (const TableRow& row : table.rows)
    markdown_line(out, row.cells);
}

void render_latex(std::ostream& out, const Table& table) {
  if (!table.caption.empty()) out << latex_comment(table.caption);
  out << "\\begin{tabular}{";
  for (const TableColumn& c : table.columns)
    out << (c.right ? 'r' : 'l');
  out << "}\n\\toprule\n";
  latex_line(out, headers(table));
  out << "\\midrule\n";
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    if (i > 0 && table.rows[i].group_start) out << "\\midrule\n";
    latex_line(out, table.rows[i].cells);
  }
  out << "\\bottomrule\n\\end{tabular}\n";
}

void render(std::ostream& out, const Table& table, TableFormat format) {
  switch (format) {
    case TableFormat::text:
      return render_text(out, table);
    case TableFormat::markdown:
      return render_markdown(out, table);
    case TableFormat::latex:
      return render_latex(out, table);
  }
}

std::string latex_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    const auto* special = std::find_if(std::begin(kLatexSpecial), std::end(kLatexSpecial),
                                       [&](const auto& s) { return s.first == c; });
    if (special == std::end(kLatexSpecial))
      out += c;
    else
      out += special->second;
  }
  return out;
}

}  // namespace gjklab::experiment
