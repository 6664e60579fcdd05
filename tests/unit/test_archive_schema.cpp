// results/README.md documents every dataset of the archive; the writer and the reader take
// their columns from the schema tables. This checks that the document's tables list exactly
// those columns, in order, with their types, so neither can change without the other.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gjklab/experiment/archive.hpp"

using namespace gjklab::experiment;

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(' ') - first + 1);
}

/// The names in backquotes in a table cell ("`index_a`, `index_b`": two).
std::vector<std::string> quoted_names(const std::string& cell) {
  std::vector<std::string> names;
  for (std::size_t open = cell.find('`'); open != std::string::npos;
       open = cell.find('`', open + 1)) {
    const std::size_t close = cell.find('`', open + 1);
    if (close == std::string::npos) break;
    names.push_back(cell.substr(open + 1, close - open - 1));
    open = close;
  }
  return names;
}

/// The first table after the heading "### `/GROUP…", one entry per dataset it names.
std::vector<ArchiveColumn> documented_columns(const std::string& group) {
  std::ifstream in(std::string(GJKLAB_TESTS_DIR) + "/../results/README.md");
  REQUIRE(in);
  const std::string heading = "### `/" + group;
  std::vector<ArchiveColumn> columns;
  bool in_section = false, in_table = false;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("### ")) in_section = line.starts_with(heading);
    if (!in_section) continue;
    if (!line.starts_with("|")) {
      if (in_table) break;
      continue;
    }
    in_table = true;
    std::vector<std::string> cells;
    std::stringstream row(line.substr(1));
    for (std::string cell; std::getline(row, cell, '|') && cells.size() < 2;)
      cells.push_back(trim(cell));
    if (cells.size() < 2 || cells[0] == "dataset" || cells[0].starts_with("-")) continue;
    for (const std::string& name : quoted_names(cells[0]))
      columns.push_back({name, cells[1]});
  }
  return columns;
}

}  // namespace

TEST_CASE("results/README.md documents every archive column with its type", "[unit][archive]") {
  for (const std::string group : {"cases", "exact", "algorithms", "traces", "geometry"}) {
    INFO("group /" << group);
    const std::vector<ArchiveColumn> written = archive_columns(group);
    const std::vector<ArchiveColumn> documented = documented_columns(group);
    REQUIRE(!written.empty());
    REQUIRE(documented.size() == written.size());
    for (std::size_t i = 0; i < written.size(); ++i) {
      INFO("column " << i);
      CHECK(documented[i].name == written[i].name);
      CHECK(documented[i].type == written[i].type);
    }
  }
  CHECK(archive_columns("no such group").empty());
}

TEST_CASE("the archive schema names each column once per group", "[unit][archive]") {
  for (const std::string group : {"cases", "exact", "algorithms", "traces", "geometry"}) {
    const std::vector<ArchiveColumn> columns = archive_columns(group);
    for (std::size_t i = 0; i < columns.size(); ++i)
      for (std::size_t j = i + 1; j < columns.size(); ++j)
        CHECK(columns[i].name != columns[j].name);
  }
}
