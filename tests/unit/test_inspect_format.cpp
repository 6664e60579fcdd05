// `gjklab inspect --format`: the summary tables as Markdown and as LaTeX (booktabs) hold the
// cells of the text form, the text form is what it always was, and LaTeX's special characters
// are escaped (sweep labels such as gjk-johnson@max_iterations=8).
#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/experiment/run/summary.hpp"
#include "gjklab/experiment/run/table.hpp"
#include "gjklab/inspect.hpp"

using namespace gjklab;
using namespace gjklab::experiment;
using gjklab::testing::run_cli;

namespace {

// A committed reference archive with a sweep (labels name@max_iterations=N) and 3 families.
const std::string kArchive = std::string(GJKLAB_TESTS_DIR) + "/../results/step_limit.h5";

using Rows = std::vector<std::vector<std::string>>;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& text, const std::string& separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t at; (at = text.find(separator, start)) != std::string::npos;
       start = at + separator.size())
    parts.push_back(text.substr(start, at - start));
  parts.push_back(text.substr(start));
  return parts;
}

/// The data rows of each Markdown pipe table (header and alignment rows dropped).
std::vector<Rows> markdown_tables(const std::string& text) {
  std::vector<Rows> tables;
  bool in_table = false;
  for (const std::string& line : lines_of(text)) {
    if (line.empty() || line[0] != '|') {
      in_table = false;
      continue;
    }
    if (!in_table) tables.emplace_back();
    in_table = true;
    if (line.starts_with("|---")) continue;  // the alignment row
    tables.back().push_back(split(line.substr(2, line.size() - 4), " | "));
  }
  for (Rows& t : tables)
    t.erase(t.begin());  // the header
  return tables;
}

/// The text of a LaTeX cell with the escapes latex_escape writes undone.
std::string unescape(std::string cell) {
  const std::vector<std::pair<std::string, std::string>> escapes = {{"\\textbackslash{}", "\\"},
                                                                    {"\\textasciitilde{}", "~"},
                                                                    {"\\textasciicircum{}", "^"},
                                                                    {"\\textless{}", "<"},
                                                                    {"\\textgreater{}", ">"},
                                                                    {"\\textbar{}", "|"},
                                                                    {"\\_", "_"},
                                                                    {"\\%", "%"},
                                                                    {"\\&", "&"},
                                                                    {"\\#", "#"},
                                                                    {"\\$", "$"},
                                                                    {"\\{", "{"},
                                                                    {"\\}", "}"}};
  std::string out;
  for (std::size_t i = 0; i < cell.size();) {
    bool matched = false;
    for (const auto& [escaped, plain] : escapes)
      if (cell.compare(i, escaped.size(), escaped) == 0) {
        out += plain;
        i += escaped.size();
        matched = true;
        break;
      }
    if (!matched) out += cell[i++];
  }
  return out;
}

/// A LaTeX tabular: its column specification, the lines between \begin and \end, and its data
/// rows (cells unescaped).
struct Tabular {
  std::string columns;
  std::vector<std::string> lines;
  Rows rows;
};

std::vector<Tabular> latex_tables(const std::string& text) {
  std::vector<Tabular> tables;
  bool inside = false;
  for (const std::string& line : lines_of(text)) {
    if (line.starts_with("\\begin{tabular}{")) {
      tables.push_back({line.substr(16, line.size() - 17), {}, {}});
      inside = true;
    } else if (line == "\\end{tabular}") {
      inside = false;
    } else if (inside) {
      tables.back().lines.push_back(line);
    }
  }
  for (Tabular& t : tables)
    for (std::size_t i = 3; i < t.lines.size(); ++i) {  // after \toprule, header, \midrule
      const std::string& line = t.lines[i];
      if (line.starts_with("\\") && !line.ends_with(" \\\\")) continue;  // a rule
      std::vector<std::string> cells = split(line.substr(0, line.size() - 3), " & ");
      for (std::string& c : cells)
        c = unescape(c);
      t.rows.push_back(std::move(cells));
    }
  return tables;
}

/// Whitespace-separated words: a row of the text form, or the cells of a row.
std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;)
    out.push_back(w);
  return out;
}

bool text_has_row(const std::string& text, const std::vector<std::string>& cells) {
  std::string joined;
  for (const std::string& c : cells)
    joined += c + " ";
  const std::vector<std::string> wanted = words(joined);
  for (const std::string& line : lines_of(text))
    if (words(line) == wanted) return true;
  return false;
}

std::string inspect(const std::string& format) {
  const testing::CliResult r = run_cli({"inspect", kArchive, "--format", format});
  REQUIRE(r.status == 0);
  REQUIRE(r.err.empty());
  return r.out;
}

}  // namespace

TEST_CASE("inspect --format latex: booktabs tabulars with the cells of the markdown tables",
          "[unit][inspect]") {
  const std::string latex = inspect("latex");
  const std::string markdown = inspect("markdown");
  const std::string text = run_cli({"inspect", kArchive}).out;
  const std::vector<Tabular> tabulars = latex_tables(latex);
  const std::vector<Rows> pipes = markdown_tables(markdown);
  REQUIRE(tabulars.size() == 2);  // per algorithm, per family and algorithm
  REQUIRE(pipes.size() == 2);
  CHECK(tabulars[0].columns == "lrrrrrrrr");
  CHECK(tabulars[1].columns == "llrrrl");
  for (const Tabular& t : tabulars) {
    REQUIRE(t.lines.size() >= 4);
    CHECK(t.lines.front() == "\\toprule");
    CHECK(t.lines[2] == "\\midrule");
    CHECK(t.lines.back() == "\\bottomrule");
  }
  CHECK(tabulars[0].lines[1] ==
        "algorithm & cases & wrong & err\\_med & err\\_p99 & err\\_max & it\\_mean & it\\_max & "
        "ns/query \\\\");
  // 36 labels (3 algorithms × 12 bounds); 3 families, a rule between each two.
  CHECK(tabulars[0].rows.size() == 36);
  CHECK(tabulars[1].rows.size() == 3 * 36);
  CHECK(std::count(tabulars[1].lines.begin(), tabulars[1].lines.end(), "\\midrule") == 1 + 2);
  for (std::size_t t = 0; t < 2; ++t) {
    REQUIRE(tabulars[t].rows == pipes[t]);
    for (const std::vector<std::string>& row : pipes[t])
      CHECK(text_has_row(text, row));
  }
  CHECK(latex.find("\ngjk-johnson@max\\_iterations=8 & ") != std::string::npos);
  CHECK(latex.find("max_iterations") == std::string::npos);  // every underscore escaped
  CHECK(latex.starts_with("% " + kArchive + ": per algorithm, 800 cases\n"));
}

TEST_CASE("inspect: a bad --format is a usage error naming the valid ones", "[unit][inspect]") {
  const testing::CliResult r = run_cli({"inspect", kArchive, "--format", "html"});
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(r.err.find("--format") != std::string::npos);
  CHECK(r.err.find("latex") != std::string::npos);
  // The same from a caller that fills the arguments itself.
  std::ostringstream out, err;
  CHECK(cli::run_inspect_command({kArchive, "tex"}, out, err) == 2);
  CHECK(err.str() == "gjklab inspect: unknown format 'tex'; valid: text markdown latex\n");
}

TEST_CASE("latex_escape escapes every special character", "[unit][inspect]") {
  CHECK(latex_escape("gjk-johnson@max_iterations=8") == "gjk-johnson@max\\_iterations=8");
  CHECK(latex_escape("a_b%c&d#e$f{g}h") == "a\\_b\\%c\\&d\\#e\\$f\\{g\\}h");
  CHECK(latex_escape("~^\\") == "\\textasciitilde{}\\textasciicircum{}\\textbackslash{}");
  CHECK(latex_escape("<|>") == "\\textless{}\\textbar{}\\textgreater{}");
  CHECK(unescape(latex_escape("x_%&#${}~^\\<|>y")) == "x_%&#${}~^\\<|>y");
}

TEST_CASE("the text form of the summary tables is the one the commands always printed",
          "[unit][inspect]") {
  RunSummary s;
  s.cases = 10;
  AlgorithmSummary johnson;
  johnson.name = "gjk-johnson";
  johnson.cases = 10;
  johnson.wrong_booleans = 1;
  johnson.distances = 10;
  johnson.rel_error_median = 1.5e-16;
  johnson.rel_error_p99 = 2.25e-15;
  johnson.rel_error_max = 3e-15;
  johnson.iterations_mean = 4.25;
  johnson.iterations_max = 9;
  johnson.timed = 10;
  johnson.time_ns_median = 812.4;
  johnson.terminations[static_cast<std::size_t>(Termination::step_limit)] = 2;
  AlgorithmSummary ccd;
  ccd.name = "libccd-gjk";
  ccd.cases = 10;
  ccd.iterations_mean = 3;
  ccd.iterations_max = 5;
  s.algorithms = {johnson, ccd};
  std::ostringstream summary, families;
  render_text(summary, summary_table(s));
  print_family_table(families, {{"spheres", s}});
  CHECK(
      summary.str() ==
      "algorithm         cases    wrong    err_med    err_p99    err_max  it_mean it_max   "
      "ns/query\n"
      "gjk-johnson          10        1   1.50e-16   2.25e-15   3.00e-15     4.25      9        "
      "812\n"
      "libccd-gjk           10        0          -          -          -     3.00      5          "
      "-\n");
  CHECK(families.str() ==
        "family                   algorithm        cases   wrong    err_max  not converged\n"
        "spheres                  gjk-johnson         10       1   3.00e-15  step_limit=2\n"
        "spheres                  libccd-gjk          10       0          -  -\n");
}
