// Hostile but plausible inputs that crashed gjklab, each with its input as data
// (tests/regression/data/hostile/): every one now ends in a clear error naming the file, line
// or case, and the good cases around it are still answered.
#include <catch2/catch.hpp>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../support/cli_run.hpp"
#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/experiment/bench/bench.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"

using namespace gjklab;

namespace {

std::string hostile(const char* name) {
  return std::string(GJKLAB_REGRESSION_DATA_DIR) + "/hostile/" + name;
}

}  // namespace

TEST_CASE("cases file with a Latin-1 id, a 10^5-deep id and a 30 000-character id",
          "[regression][hostile]") {
  // The Latin-1 bytes made the JSON serialisation of the error line throw and abort the run
  // (later cases never answered); the deep id overflowed the stack when printed; the long id
  // overflowed the stack of std::regex that looked for it in the malformed line.
  const auto r = testing::run_cli(
      {"query", "--cases", hostile("cases_hostile_lines.jsonl"), "--algorithms", "gjk-johnson"});
  CHECK(r.status == 1);  // some lines were bad: the exit status says so
  std::istringstream lines(r.out);
  std::vector<nlohmann::json> answers;
  for (std::string line; std::getline(lines, line);)
    answers.push_back(nlohmann::json::parse(line));  // every output line is valid UTF-8 JSON
  REQUIRE(answers.size() == 5);
  CHECK(answers[0]["id"] == "before");
  CHECK(answers[1].contains("error"));
  CHECK(answers[2]["error"].get<std::string>().find("nested deeper than") != std::string::npos);
  CHECK(answers[3]["id"].get<std::string>().size() == 30000);
  CHECK(answers[4]["id"] == "after");
  CHECK(answers[4]["distance"] == 2.0);
  CHECK(r.err.find("cases_hostile_lines.jsonl:3") != std::string::npos);
}

TEST_CASE("json_line replaces bytes that are not UTF-8 instead of throwing",
          "[regression][hostile]") {
  const nlohmann::json j = {{"id", std::string("caf\xe9")}};
  const std::string line = experiment::json_line(j);
  CHECK(line == "{\"id\":\"caf\xef\xbf\xbd\"}");
}

TEST_CASE("OBJ line of commas: no crash, the vertices are read", "[regression][hostile]") {
  // `fields` of ",,," is empty and the reader indexed its first element.
  CHECK(experiment::read_point_file(hostile("obj_line_of_commas.obj")).size() == 4);
}

TEST_CASE("OFF counts 1e20 and 2e9: a clear error with the line", "[regression][hostile]") {
  // 1e20 was cast to a size (undefined) and reported as an empty cloud; in the mesh family's
  // reader (CGAL) 2e9 vertices reserved 48 GB and ended in std::bad_alloc.
  CHECK_THROWS_WITH(experiment::read_point_file(hostile("off_count_1e20.off")),
                    Catch::Contains("off_count_1e20.off:2") && Catch::Contains("declares 1e20"));
  CHECK_THROWS_WITH(
      exact::read_mesh_vertices(hostile("off_two_billion_vertices.off")),
      Catch::Contains("off_two_billion_vertices.off:2") && Catch::Contains("more than the file's"));
}

TEST_CASE("PLY with x declared as a list: a clear error, not a crash in CGAL's reader",
          "[regression][hostile]") {
  CHECK_THROWS_WITH(exact::read_mesh_vertices(hostile("ply_x_as_list.ply")),
                    Catch::Contains("ply_x_as_list.ply:4") && Catch::Contains("is a list"));
}

TEST_CASE("bench config: a non-numeric [published] key and values of the wrong type or range",
          "[regression][hostile]") {
  // std::stoi threw out of the program on the key; wrong types were silently ignored and
  // samples = 4294967297 was narrowed to 1.
  testing::ScratchDir dir("bench-config");
  auto load = [&](const std::string& body) {
    const std::string path = dir.file("bench.toml");
    std::ofstream(path) << body;
    return experiment::bench::load_bench_config(path);
  };
  CHECK_THROWS_WITH(load("[published.scene_ms]\nmany = 3.5\n"),
                    Catch::Contains("bench.toml:2: key 'published.scene_ms.many': must be an object count"));
  CHECK_THROWS_WITH(load("samples = 4294967297\n"),
                    Catch::Contains("bench.toml:1: key 'samples': must be between 1 and 100000"));
  CHECK_THROWS_WITH(load("samples = \"31\"\n"),
                    Catch::Contains("bench.toml:1: key 'samples': expected an integer"));
  CHECK_THROWS_WITH(load("batch_seconds = 1e300\n"), Catch::Contains("batch_seconds"));
  CHECK_THROWS_WITH(load("reference = 3\n"), Catch::Contains("bench.toml:1: key 'reference': expected a string"));
  CHECK_THROWS_WITH(load("[published.pair_us]\n\"box-box\" = nan\n"),
                    Catch::Contains("bench.toml:2: key 'published.pair_us.box-box': must be finite"));
  CHECK_THROWS_WITH(load("[published.scene_ms]\n32 = -1.5\n"),
                    Catch::Contains("bench.toml:2: key 'published.scene_ms.32': must be a finite number >= 0"));
  CHECK(load("samples = 7\n[published.scene_ms]\n32 = 1.5\n").samples == 7);
}
