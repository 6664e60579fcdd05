// `gjklab bench`: arguments, the JSON records and the config file, on tiny runs (a few samples,
// no batching). Timings are never asserted: the machine may be shared and noisy.
#include <catch2/catch.hpp>

#include <set>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gjklab/cli.hpp"

namespace fs = std::filesystem;

namespace {

struct Run {
  int status;
  std::string out, err;
};

Run run_cli(const std::vector<std::string>& args) {
  std::vector<const char*> argv{"gjklab"};
  for (const auto& a : args)
    argv.push_back(a.c_str());
  std::istringstream in;
  std::ostringstream out, err;
  const int status = gjklab::cli::run(static_cast<int>(argv.size()), argv.data(), in, out, err);
  return {status, out.str(), err.str()};
}

/// A file path in a fresh temporary folder, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() /
            ("gjklab-bench-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

const std::vector<std::string> kTiny = {"--samples",  "2", "--configurations", "1",
                                        "--batch-us", "0", "--quiet"};

std::vector<std::string> with_tiny(std::vector<std::string> args) {
  args.insert(args.end(), kTiny.begin(), kTiny.end());
  return args;
}

}  // namespace

TEST_CASE("bench seed suite: JSON records with the documented fields and ratios", "[unit][bench]") {
  TempDir dir;
  const std::string json = dir.file("bench.json");
  const Run r =
      run_cli(with_tiny({"bench", "--suite", "seed", "--cases", "box-cone", "--json", json}));
  REQUIRE(r.status == 0);
  CHECK(r.out.find("box-cone overlap") != std::string::npos);
  CHECK(r.out.find("x ref") != std::string::npos);
  const nlohmann::json doc = read_json(json);
  REQUIRE(doc.contains("meta"));
  CHECK(doc["meta"]["boolean_reference"] == "libccd-mpr");
  CHECK(doc["meta"]["samples"] == 2);
  const auto& records = doc["records"];
  // Two cases (overlap, separated) × the four registered boolean and distance algorithms.
  REQUIRE(records.size() >= 8);
  int references = 0;
  std::set<std::pair<std::string, std::string>> case_references;
  for (const auto& rec : records) {
    case_references.insert({rec["case"].get<std::string>(), rec["reference"].get<std::string>()});
    for (const char* field : {"suite", "case", "algorithm", "ns_median", "ns_p10", "ns_p90",
                              "iterations_mean", "ratio_to_reference"})
      REQUIRE(rec.contains(field));
    CHECK(rec["suite"] == "seed");
    const std::string c = rec["case"];
    CHECK((c == "box-cone overlap" || c == "box-cone separated"));
    CHECK(rec["ns_p10"].get<double>() <= rec["ns_median"].get<double>());
    CHECK(rec["ns_median"].get<double>() <= rec["ns_p90"].get<double>());
    CHECK(rec["ns_median"].get<double>() > 0);
    CHECK(rec["iterations_mean"].get<double>() >= 0);
    if (rec["algorithm"] == rec["reference"]) {
      CHECK(rec["ratio_to_reference"].get<double>() == 1.0);
      ++references;
    }
    if (rec["algorithm"] == "gjk-bool") CHECK(rec["reference"] == "libccd-mpr");
  }
  // Each case's references (libccd-mpr for booleans; for distances the case's fastest peer
  // distance query, or libccd-gjk without one) have ratio 1 to themselves.
  CHECK(references == static_cast<int>(case_references.size()));
  CHECK(references >= 2);
}

TEST_CASE("bench: hill-climbing rows, an explicit reference and the scene suite", "[unit][bench]") {
  TempDir dir;
  const std::string json = dir.file("hc.json");
  Run r = run_cli(
      with_tiny({"bench", "--suite", "random", "--cases", "n=32 separated", "--algorithms",
                 "gjk-johnson,gjk-johnson+hc", "--reference", "gjk-johnson", "--json", json}));
  REQUIRE(r.status == 0);
  nlohmann::json doc = read_json(json);
  REQUIRE(doc["records"].size() == 2);
  for (const auto& rec : doc["records"]) {
    CHECK(rec["reference"] == "gjk-johnson");
    if (rec["algorithm"] == "gjk-johnson+hc") {
      CHECK(rec["ratio_to_full_scan"].is_number());
      CHECK(rec["ratio_to_floor"].is_null());
      CHECK(rec["floor_independent_ns"].is_null());
    } else {
      CHECK(rec["ratio_to_reference"].get<double>() == 1.0);
      CHECK(rec["ratio_to_floor"].is_number());
      // Both floors: dependent support calls (the table's) and independent ones.
      CHECK(rec["floor_ns"].get<double>() > 0);
      CHECK(rec["floor_independent_ns"].get<double>() > 0);
      CHECK(rec["ratio_to_floor_independent"].is_number());
    }
    // Hill climbing answers the same queries: same iteration counts on these generic clouds.
  }
  CHECK(doc["records"][0]["iterations_mean"] == doc["records"][1]["iterations_mean"]);

  const std::string scene = dir.file("scene.json");
  r = run_cli(with_tiny({"bench", "--suite", "scene", "--cases", "16 objects", "--algorithms",
                         "gjk-bool", "--json", scene}));
  REQUIRE(r.status == 0);
  doc = read_json(scene);
  REQUIRE(doc["records"].size() == 2);  // gjk-bool and its reference, libccd-mpr
  for (const auto& rec : doc["records"]) {
    CHECK(rec["queries_per_pass"] == 120);
    CHECK(rec["pass_ms_median"].get<double>() > 0);
  }
}

TEST_CASE("bench config file and seed-tables Markdown", "[unit][bench]") {
  TempDir dir;
  const std::string cfg = dir.file("tables.toml");
  std::ofstream(cfg) << "suites = [\"seed\"]\nalgorithms = [\"gjk-bool\"]\nsamples = 2\n"
                        "configurations = 1\nbatch_seconds = 0.0\ncases = \"box-box\"\n"
                        "[published]\nsource = \"a test\"\n"
                        "pair_us = { \"box-box\" = 17.3 }\nscene_ms = { \"8\" = 11.3 }\n";
  const std::string md = dir.file("tables.md");
  const Run r = run_cli({"bench", "--config", cfg, "--markdown", md, "--quiet"});
  REQUIRE(r.status == 0);
  std::ifstream in(md);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("| box-box | 17.3 |") != std::string::npos);
  CHECK(text.find("a test") != std::string::npos);

  std::ofstream(cfg) << "suites = [\"seed\"]\nsampels = 2\n";
  const Run bad = run_cli({"bench", "--config", cfg, "--quiet"});
  CHECK(bad.status == 2);
  CHECK(bad.err.find("sampels") != std::string::npos);
  // The one TOML reader's errors: the file, the line and the key.
  CHECK(bad.err.find(cfg + ":2: key 'sampels'") != std::string::npos);
  std::ofstream(cfg) << "suites = [\"seed\"]\n[published.scene_ms]\n4 = -1\n";
  const Run negative = run_cli({"bench", "--config", cfg, "--quiet"});
  CHECK(negative.status == 2);
  CHECK(negative.err.find(cfg + ":3: key 'published.scene_ms.4'") != std::string::npos);
}

TEST_CASE("bench usage errors exit with 2 and say what is wrong", "[unit][bench]") {
  Run r = run_cli(with_tiny({"bench", "--suite", "seed", "--algorithms", "no-such-algorithm"}));
  CHECK(r.status == 2);
  CHECK(r.err.find("no-such-algorithm") != std::string::npos);
  r = run_cli(with_tiny({"bench", "--suite", "nonsense"}));
  CHECK(r.status == 2);
  r = run_cli(with_tiny({"bench", "--suite", "seed", "--reference", "nope"}));
  CHECK(r.status == 2);
  CHECK(r.err.find("nope") != std::string::npos);
  r = run_cli({"bench", "--config", "/nonexistent/bench.toml", "--quiet"});
  CHECK(r.status == 2);
}
