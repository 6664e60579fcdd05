// `gjklab query` on closed meshes: mesh sides in a cases file, two mesh files with
// --decomposition; `exact` answers the solids, the convex algorithms the pieces.
#include <catch2/catch.hpp>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"

namespace {

using Json = nlohmann::json;
using gjklab::testing::run_cli;

/// An L prism (bar [0, 2] × [0, 1], arm [0, 1] × [1, 2], z in [0, 1]) as a cases-line side.
Json l_prism() {
  Json v = Json::array(), f = Json::array();
  const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (const double z : {0.0, 1.0})
    for (const auto& p : xy)
      v.push_back({p[0], p[1], z});
  for (int k = 1; k < 5; ++k) {
    f.push_back({0, k + 1, k});
    f.push_back({6, 6 + k, 6 + k + 1});
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    f.push_back({i, j, 6 + j});
    f.push_back({i, 6 + j, 6 + i});
  }
  return {{"vertices", v}, {"faces", f}};
}

/// A small box in the L's notch, a quarter unit from both arms, as a point list.
Json notch_box() {
  Json pts = Json::array();
  for (const double x : {1.25, 1.75})
    for (const double y : {1.25, 1.75})
      for (const double z : {0.0, 1.0})
        pts.push_back({x, y, z});
  return pts;
}

std::vector<Json> lines_of(const std::string& out) {
  std::vector<Json> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    lines.push_back(Json::parse(line));
  return lines;
}

std::string write_off(const gjklab::testing::ScratchDir& dir, const std::string& name,
                      const Json& mesh) {
  std::ofstream out(dir.file(name));
  out << "OFF\n" << mesh["vertices"].size() << " " << mesh["faces"].size() << " 0\n";
  for (const auto& v : mesh["vertices"])
    out << v[0].get<double>() << " " << v[1].get<double>() << " " << v[2].get<double>() << "\n";
  for (const auto& f : mesh["faces"])
    out << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  return dir.file(name);
}

}  // namespace

TEST_CASE("query --cases: a mesh side; exact answers the solid, GJK the hull or the pieces",
          "[unit][query][decomposition]") {
  const Json line = {{"id", "notch"}, {"a", l_prism()}, {"b", notch_box()}};
  for (const std::string decomposition : {"hull", "exact"}) {
    const auto r = run_cli({"query", "--cases", "-", "--algorithms", "exact,gjk-johnson",
                            "--decomposition", decomposition},
                           line.dump() + "\n");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto lines = lines_of(r.out);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0]["algorithm"] == "exact");
    CHECK(lines[0]["intersect"] == false);
    CHECK(lines[0]["distance"] == 0.25);
    CHECK(lines[0]["method"] == "mesh-truth");
    CHECK(lines[0]["contact"] == "separated");
    CHECK(lines[1]["algorithm"] == "gjk-johnson");
    CHECK(lines[1]["decomposition"] == decomposition);
    CHECK(lines[1]["pieces_b"] == 1);
    // The hull of the L fills its notch: the classic false positive.
    CHECK(lines[1]["intersect"] == (decomposition == "hull"));
    if (decomposition == "exact") {
      CHECK(lines[1]["pieces_a"].get<int>() >= 2);
      CHECK(lines[1]["distance"].get<double>() == Approx(0.25).margin(1e-12));
    }
  }
}

TEST_CASE("query --cases: a bad mesh side is an error naming the line, side and face",
          "[unit][query][decomposition]") {
  Json open = l_prism();
  open["faces"].erase(open["faces"].begin() + 3);
  Json bad_index = l_prism();
  bad_index["faces"][2][1] = -1;
  const std::string input =
      Json{{"id", "open"}, {"a", open}, {"b", notch_box()}}.dump() + "\n" +
      Json{{"id", "index"}, {"a", notch_box()}, {"b", bad_index}}.dump() + "\n" +
      Json{{"id", "swept"}, {"a", l_prism()}, {"b", notch_box()}, {"radius_a", 0.1}}.dump() + "\n";
  const auto r = run_cli({"query", "--cases", "-", "--algorithms", "exact"}, input);
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("<stdin>:1: case 'open': mesh a: face") &&
                        Catch::Contains("<stdin>:2: case 'index': mesh b face 2: a vertex index "
                                        "is not an integer") &&
                        Catch::Contains("<stdin>:3: case 'swept': radius_a and radius_b sweep "
                                        "point clouds, not meshes"));
}

TEST_CASE("query two mesh files with --decomposition: pieces for GJK, the solids for exact",
          "[unit][query][decomposition]") {
  gjklab::testing::ScratchDir dir("query-meshes");
  const std::string l = write_off(dir, "l.off", l_prism());
  Json notch = l_prism();
  for (auto& v : notch["vertices"])  // a second L, turned a half turn about z into the notch
    v = {3.25 - v[0].get<double>(), 3.25 - v[1].get<double>(), v[2].get<double>()};
  const std::string other = write_off(dir, "other.off", notch);
  const auto r = run_cli({"query", l, other, "--decomposition", "exact", "--algorithms",
                          "exact,gjk-johnson,gjk-bool,libccd-gjk"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  const auto lines = lines_of(r.out);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0]["contact"] == "separated");
  const double truth = lines[0]["distance"];
  CHECK(truth == Approx(0.25 * std::sqrt(2.0)).margin(1e-15));
  for (std::size_t k = 1; k < 4; ++k) {
    CHECK(lines[k]["intersect"] == false);
    CHECK(lines[k]["decomposition"] == "exact");
  }
  CHECK(lines[1]["distance"].get<double>() == Approx(truth).margin(1e-12));
  const auto usage = run_cli({"query", l, other, "--decomposition", "vhacd"});
  CHECK(usage.status == 2);
  const auto swept = run_cli({"query", l, other, "--decomposition", "hull", "--radius-a", "1"});
  CHECK(swept.status == 2);
}

#ifdef GJKLAB_HAVE_FCL
TEST_CASE("query: fcl-bvh answers a mesh case, and says why not for two point clouds",
          "[unit][query][decomposition]") {
  const std::string input =
      Json{{"id", "notch"}, {"a", l_prism()}, {"b", notch_box()}}.dump() + "\n" +
      Json{{"id", "clouds"}, {"a", notch_box()}, {"b", notch_box()}}.dump() + "\n";
  const auto r = run_cli({"query", "--cases", "-", "--algorithms", "fcl-bvh"}, input);
  INFO(r.err);
  REQUIRE(r.status == 0);
  const auto lines = lines_of(r.out);
  REQUIRE(lines.size() == 2);
  CHECK(lines[0]["algorithm"] == "fcl-bvh");
  CHECK(lines[0]["intersect"] == false);
  CHECK(lines[0]["distance"].get<double>() == Approx(0.25).margin(1e-12));
  CHECK(lines[1]["algorithm"] == "fcl-bvh");
  CHECK(lines[1]["error"] == "answers for two meshes only");
  const auto unknown = run_cli({"query", "--cases", "-", "--algorithms", "fcl-nope"}, input);
  CHECK(unknown.status == 2);
  CHECK_THAT(unknown.err, Catch::Contains("\ngjklab query: mesh cases also take: fcl-bvh\n"));
}
#endif

TEST_CASE("query --cases: a flat point cloud beside a mesh is refused, naming the side",
          "[unit][query][decomposition]") {
  const Json flat = {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}};
  const auto r = run_cli({"query", "--cases", "-", "--algorithms", "exact"},
                         Json{{"id", "flat"}, {"a", l_prism()}, {"b", flat}}.dump() + "\n");
  const auto lines = lines_of(r.out);
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0]["error"].get<std::string>(),
             Catch::Contains("side b: the point cloud spans 2 dimensions; a solid needs 3"));
}

TEST_CASE("query --decomposition-option: KEY=VALUE checked before any case runs",
          "[unit][query][decomposition]") {
  const std::string line =
      Json{{"id", "notch"}, {"a", l_prism()}, {"b", notch_box()}}.dump() + "\n";
  auto r = run_cli({"query", "--cases", "-", "--decomposition", "exact", "--decomposition-option",
                    "concavity=5"},
                   line);
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains("decomposition 'exact' takes no option 'concavity'"));
  r = run_cli({"query", "--cases", "-", "--decomposition-option", "concavity"}, line);
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains("expected KEY=VALUE"));
}
