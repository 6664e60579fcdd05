// results/README.md documents every dataset and root attribute of the archive; the writer and
// the reader take them from the schema's descriptor tables. The document's tables are made
// from those tables (`gjklab schema --update results/README.md`), and this checks that they
// are the current rendering, so that neither can change without the other.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjklab/experiment/archive/archive.hpp"

using namespace gjklab::experiment;

namespace {

const std::vector<std::string> kGroups = {"cases",           "exact",        "algorithms",
                                          "traces",          "geometry",     "meshes/exact",
                                          "meshes/algorithms", "meshes/geometry"};

std::string document(const std::string& relative) {
  std::ifstream in(std::string(GJKLAB_TESTS_DIR) + "/../" + relative, std::ios::binary);
  REQUIRE(in);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void check_names_unique(const std::vector<ArchiveColumn>& columns) {
  for (std::size_t i = 0; i < columns.size(); ++i)
    for (std::size_t j = i + 1; j < columns.size(); ++j)
      CHECK(columns[i].name != columns[j].name);
}

}  // namespace

TEST_CASE("results/README.md's schema tables are the schema's rendering", "[unit][archive]") {
  const std::string readme = document("results/README.md");
  for (const std::string& group : kGroups)
    CHECK(readme.find("<!-- schema table: " + group + " -->\n") != std::string::npos);
  CHECK(readme.find("<!-- schema table: root -->\n") != std::string::npos);
  CHECK(readme.find("<!-- schema table: enums -->\n") != std::string::npos);
  INFO("regenerate with: gjklab schema --update results/README.md");
  CHECK(with_schema_tables(readme) == readme);
}

const std::vector<std::string> kSceneGroups = {"root",  "frames",  "bodies", "contacts",
                                               "audit", "queries", "shapes", "state"};

TEST_CASE("docs/scenes.md's scene archive tables are the scene schema's rendering",
          "[unit][archive][scene]") {
  const std::string page = document("docs/scenes.md");
  for (const std::string& group : kSceneGroups)
    CHECK(page.find("<!-- schema table: scene/" + group + " -->\n") != std::string::npos);
  INFO("regenerate with: gjklab schema --update docs/scenes.md");
  CHECK(with_schema_tables(page) == page);
  CHECK_THROWS_AS(archive_schema_table("scene/no such group"), std::invalid_argument);
}

TEST_CASE("a schema table lists every column with its type and meaning", "[unit][archive]") {
  for (const std::string& group : kGroups) {
    INFO("group /" << group);
    const std::vector<ArchiveColumn> columns = archive_columns(group);
    REQUIRE(!columns.empty());
    const std::string table = archive_schema_table(group);
    for (const ArchiveColumn& c : columns) {
      INFO("column " << c.name);
      CHECK(!c.meaning.empty());
      CHECK(table.find("| `" + c.name + "` ") != std::string::npos);
      CHECK(table.find(" | " + c.meaning + " |\n") != std::string::npos);
    }
  }
  CHECK(archive_columns("no such group").empty());
  CHECK_THROWS_AS(archive_schema_table("no such group"), std::invalid_argument);
}

TEST_CASE("schema tables: types as the document names them", "[unit][archive]") {
  const auto type_of = [](const std::string& group, const std::string& name) {
    for (const ArchiveColumn& c :
         group == "root" ? archive_root_attributes() : archive_columns(group))
      if (c.name == name) return c.type;
    return std::string("(absent)");
  };
  CHECK(type_of("cases", "case_id") == "uint64");
  CHECK(type_of("cases", "shape_a") == "enum `ShapeKind`");
  CHECK(type_of("algorithms", "witness_a") == "float64 (rows × 3)");
  CHECK(type_of("traces", "simplex_index_a") == "int32 (rows × 4)");
  CHECK(type_of("exact", "intersect") == "bool");
  CHECK(type_of("root", "schema_version") == "int32");
  CHECK(type_of("root", "oracle") == "uint8 (0/1)");
  CHECK(type_of("root", "family_names") == "string array");
  CHECK(type_of("root", "touching_band") == "float64");
  CHECK(type_of("root", "checkpoint_*") == "uint64 each");
}

TEST_CASE("the archive schema names each column and root attribute once", "[unit][archive]") {
  for (const std::string& group : kGroups)
    check_names_unique(archive_columns(group));
  const std::vector<ArchiveColumn> root = archive_root_attributes();
  check_names_unique(root);
  // Creation order: the version first, the completion flag last.
  REQUIRE(root.size() > 2);
  CHECK(root.front().name == "schema_version");
  CHECK(root.back().name == "complete");
}

TEST_CASE("with_schema_tables replaces only the marked tables", "[unit][archive]") {
  const std::string stale =
      "# Title\n\n<!-- schema table: geometry -->\n| old | table |\n"
      "<!-- end schema table -->\n\nProse after.\n";
  const std::string made = with_schema_tables(stale);
  CHECK(made == "# Title\n\n<!-- schema table: geometry -->\n" + archive_schema_table("geometry") +
                    "<!-- end schema table -->\n\nProse after.\n");
  CHECK(with_schema_tables(made) == made);
  CHECK(with_schema_tables("no tables here\n") == "no tables here\n");
  // A marker inside a line is prose about the markers, not a table.
  const std::string prose = "the lines `<!-- schema table: … -->` are made\n";
  CHECK(with_schema_tables(prose) == prose);
  CHECK_THROWS_AS(with_schema_tables("<!-- schema table: nothing -->\n<!-- end schema table -->\n"),
                  std::invalid_argument);
  CHECK_THROWS_AS(with_schema_tables("<!-- schema table: cases -->\n| a |\n"),
                  std::invalid_argument);
}

TEST_CASE("the list of enum values names every member the archive's enum types hold",
          "[unit][archive]") {
  const std::string list = archive_schema_table("enums");
  // The members added last to ShapeKind, and one value of each other archive enum.
  for (const char* item :
       {"- `ShapeKind`: `sphere_points` = 0,", "`sphere` = 17", "`capsule` = 18",
        "- `Placement`: `separated` = 0,", "- `ContactClass`: ", "- `Termination`: `converged` = 0",
        "- `FailureClass`: `none` = 0", "- `GjkStep`: `continued` = 0",
        "- `AnswerMethod`: `certified` = 0, `qp` = 1, `none` = 2, `mesh_truth` = 3\n"}) {
    INFO(item);
    CHECK(list.find(item) != std::string::npos);
  }
  CHECK(list.find("unknown") == std::string::npos);
}
