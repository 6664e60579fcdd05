// `gjklab bench --compare FILE` on hand-made records: each row's change is its ratio to its
// reference now over the same ratio in the baseline (never a quotient of times), unmatched
// records are listed, rows over the threshold are marked, and a baseline that is not a bench
// report is refused with the file's name. Timings are never asserted.
#include <catch2/catch.hpp>

#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/experiment/bench/bench.hpp"

using namespace gjklab::experiment::bench;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

BenchRecord record(const std::string& case_name, const std::string& algorithm, double ns,
                   std::optional<double> ratio, std::optional<double> floor = std::nullopt,
                   const std::string& reference = "gjk-johnson") {
  BenchRecord r;
  r.suite = "seed";
  r.case_name = case_name;
  r.algorithm = algorithm;
  r.ns_median = ns;
  r.reference = reference;
  r.ratio_to_reference = ratio;
  r.ratio_to_floor = floor;
  return r;
}

/// The row of `algorithm` in `case_name`, or nullptr.
const BenchComparisonRow* row_of(const BenchComparison& c, const std::string& case_name,
                                 const std::string& algorithm) {
  for (const BenchComparisonRow& r : c.rows)
    if (r.case_name == case_name && r.algorithm == algorithm) return &r;
  return nullptr;
}

/// The reason `algorithm` in `case_name` was not compared, or "" when it was.
std::string why_not(const BenchComparison& c, const std::string& case_name,
                    const std::string& algorithm) {
  for (const BenchUnmatched& u : c.unmatched)
    if (u.case_name == case_name && u.algorithm == algorithm) return u.why;
  return "";
}

/// The words of `text`, split at spaces.
std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;)
    out.push_back(w);
  return out;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

}  // namespace

TEST_CASE("bench compare: the change is the ratio to the reference over the baseline's",
          "[unit][bench]") {
  BenchReport now;
  // Times ten times the baseline's everywhere (another machine): only the ratios count.
  now.records = {record("box-cone overlap", "gjk-johnson", 1000, 1.0, 2.0),
                 record("box-cone overlap", "gjk-certified", 3250, 3.25, 4.0),
                 record("box-cone overlap", "epa", 2100, 2.1),
                 record("box-cone separated", "gjk-certified", 1500, 1.5)};
  BenchBaseline baseline;
  baseline.path = "base.json";
  baseline.records = {record("box-cone overlap", "gjk-johnson", 100, 1.0, 2.5),
                      record("box-cone overlap", "gjk-certified", 250, 2.5, 4.0),
                      record("box-cone overlap", "epa", 200, 2.0, 3.0),
                      record("box-cone separated", "gjk-certified", 150, 1.5)};
  const BenchComparison c = compare_to_baseline(now, baseline);
  REQUIRE(c.rows.size() == 4);
  CHECK(c.unmatched.empty());
  const BenchComparisonRow* certified = row_of(c, "box-cone overlap", "gjk-certified");
  REQUIRE(certified);
  CHECK(certified->ratio_now == 3.25);
  CHECK(certified->ratio_baseline == 2.5);
  CHECK(*certified->change == Approx(1.3));
  CHECK(*certified->floor_change == Approx(1.0));
  CHECK(certified->over_threshold);  // 1.3 > the default 1.20
  const BenchComparisonRow* epa = row_of(c, "box-cone overlap", "epa");
  CHECK(*epa->change == Approx(1.05));
  CHECK_FALSE(epa->over_threshold);
  CHECK_FALSE(epa->floor_change.has_value());  // no floor in this run
  // The reference's own row: ratio 1 in both, so no change, but its floor change is kept.
  const BenchComparisonRow* johnson = row_of(c, "box-cone overlap", "gjk-johnson");
  CHECK_FALSE(johnson->change.has_value());
  CHECK(*johnson->floor_change == Approx(0.8));
  // Slowdowns first, the reference's row last; the median over the three changes.
  CHECK(c.rows[0].algorithm == "gjk-certified");
  CHECK(c.rows[1].algorithm == "epa");
  CHECK(c.rows[2].case_name == "box-cone separated");
  CHECK(c.rows[3].algorithm == "gjk-johnson");
  CHECK(*c.median_change == Approx(1.05));
  CHECK(c.over_threshold == 1);

  // Per algorithm: the medians of its rows, the reference last.
  REQUIRE(c.by_algorithm.size() == 3);
  CHECK(c.by_algorithm[0].algorithm == "gjk-certified");
  CHECK(c.by_algorithm[0].rows == 2);
  CHECK(*c.by_algorithm[0].median_change == Approx(1.15));
  CHECK(c.by_algorithm[0].over_threshold == 1);
  CHECK(c.by_algorithm[1].algorithm == "epa");
  CHECK(c.by_algorithm[2].algorithm == "gjk-johnson");
  CHECK_FALSE(c.by_algorithm[2].median_change.has_value());
  CHECK(*c.by_algorithm[2].median_floor_change == Approx(0.8));

  // A higher threshold marks nothing.
  const BenchComparison lenient = compare_to_baseline(now, baseline, 1.35);
  CHECK(lenient.over_threshold == 0);
  CHECK_FALSE(row_of(lenient, "box-cone overlap", "gjk-certified")->over_threshold);

  std::ostringstream text;
  print_comparison(c, text);
  CHECK_THAT(text.str(), Contains("compared with base.json"));
  CHECK_THAT(text.str(), Contains("1.30 !"));
  CHECK_THAT(text.str(), Contains("median change 1.05"));
  CHECK_THAT(text.str(), Contains("worst 1.30 (seed box-cone overlap, gjk-certified)"));
  CHECK_THAT(text.str(), Contains("1 over 1.20"));
}

TEST_CASE("bench compare: records on one side only are listed, not errors", "[unit][bench]") {
  BenchReport now;
  now.config.configurations = 1;
  now.records = {record("box-cone overlap", "gjk-johnson", 100, 1.0),
                 record("box-cone overlap", "gjk-bool", 50, 0.5),  // new algorithm
                 record("box-cone overlap", "epa", 200, 2.0, std::nullopt, "libccd-mpr"),
                 record("box-cone separated", "gjk-certified", 150, std::nullopt)};
  BenchBaseline baseline;
  baseline.meta = {{"configurations", "8"}};
  baseline.records = {record("box-cone overlap", "gjk-johnson", 100, 1.0),
                      record("box-cone overlap", "gjk-certified", 300, 3.0),  // gone
                      record("box-cone overlap", "epa", 200, 2.0),
                      record("box-cone separated", "gjk-certified", 150, 1.5),
                      record("box-box overlap", "gjk-johnson", 80, 1.0),  // case not run
                      record("box-box overlap", "epa", 160, 2.0),
                      record("box-cone overlap", "libccd-mpr", 90, 0.9)};  // algorithm not run
  const BenchComparison c = compare_to_baseline(now, baseline);
  REQUIRE(c.rows.size() == 1);  // gjk-johnson, the reference's own row
  CHECK(why_not(c, "box-cone overlap", "gjk-bool") == "only in this run");
  CHECK(why_not(c, "box-cone overlap", "gjk-certified") == "only in the baseline");
  CHECK(why_not(c, "box-cone overlap", "epa") ==
        "reference libccd-mpr here, gjk-johnson in the baseline");
  CHECK(why_not(c, "box-cone separated", "gjk-certified") == "no ratio to gjk-johnson in this run");
  CHECK(c.unmatched.size() == 4);
  // The baseline's cases and algorithms this run did not measure are counted, not listed; the
  // algorithms are named.
  CHECK(c.baseline_records_not_run == 3);
  CHECK(why_not(c, "box-box overlap", "epa").empty());
  CHECK(why_not(c, "box-cone overlap", "libccd-mpr").empty());
  CHECK(c.baseline_algorithms_not_run == std::vector<std::string>{"libccd-mpr"});
  CHECK_FALSE(c.median_change.has_value());
  // Other inputs than the baseline's are said.
  REQUIRE_FALSE(c.notes.empty());
  CHECK_THAT(c.notes[0], Contains("configurations is 8, this run's 1"));

  std::ostringstream text;
  print_comparison(c, text);
  CHECK_THAT(text.str(), Contains("not compared:"));
  CHECK_THAT(text.str(), Contains("1 only in this run, 1 only in the baseline, 2 other"));
  CHECK_THAT(text.str(), Contains("3 baseline rows of cases or algorithms this run did not"));
  CHECK_THAT(text.str(), Contains("baseline algorithms not run: libccd-mpr"));
}

TEST_CASE("bench compare: a baseline that is not a bench report is refused, naming the file",
          "[unit][bench]") {
  gjklab::testing::ScratchDir dir("bench-compare");
  const std::string path = dir.file("baseline.json");
  write_file(path, R"({"meta": {"cpu": "x", "configurations": 8}, "records": [
    {"suite": "seed", "case": "box-cone overlap", "algorithm": "epa", "reference": "gjk-johnson",
     "ns_median": 200, "ratio_to_reference": 2.0, "ratio_to_floor": null},
    {"suite": "seed", "case": "box-cone overlap", "algorithm": "gjk-johnson",
     "reference": "gjk-johnson", "ratio_to_reference": 1.0, "ratio_to_floor": 3.5}]})");
  const BenchBaseline b = read_baseline(path);
  REQUIRE(b.records.size() == 2);
  CHECK(*b.records[0].ratio_to_reference == 2.0);
  CHECK_FALSE(b.records[0].ratio_to_floor.has_value());
  CHECK(*b.records[1].ratio_to_floor == 3.5);
  CHECK(b.meta.at("configurations") == "8");

  CHECK_THROWS_WITH(read_baseline(dir.file("missing.json")),
                    StartsWith(dir.file("missing.json") + ": cannot be read"));
  CHECK_THROWS_WITH(read_baseline(dir.path().string()), Contains("is a directory"));
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"not json at all", "is not JSON"},
      {"", "is not JSON"},
      {"[1, 2]", "is not a bench report"},
      {R"({"meta": {}})", "has no \"records\" array"},
      {R"({"records": [7]})", "records[0] is not an object"},
      {R"({"records": [{"suite": "seed", "case": "c", "algorithm": "epa",
           "ratio_to_reference": 1.0}]})",
       "records[0] has no \"reference\" (a string)"},
      {R"({"records": [{"suite": "seed", "case": "c", "algorithm": "epa", "reference": "r"}]})",
       "records[0] has no \"ratio_to_reference\" (a number or null)"},
      {R"({"records": [{"suite": "seed", "case": "c", "algorithm": "epa", "reference": "r",
           "ratio_to_reference": "fast"}]})",
       "\"ratio_to_reference\" is not a number or null"},
      {R"({"records": [{"suite": "seed", "case": "c", "algorithm": "epa", "reference": "r",
           "ratio_to_reference": 0}]})",
       "\"ratio_to_reference\" is 0, not a positive number"},
      {R"({"records": [
           {"suite": "s", "case": "c", "algorithm": "a", "reference": "r", "ratio_to_reference": 1},
           {"suite": "s", "case": "c", "algorithm": "a", "reference": "r", "ratio_to_reference": 2}
         ]})",
       "records[1] repeats records[0] (s, c, a)"}};
  for (const auto& [text, problem] : bad) {
    INFO(text);
    write_file(path, text);
    CHECK_THROWS_AS(read_baseline(path), BenchError);
    CHECK_THROWS_WITH(read_baseline(path), StartsWith(path + ": ") && Contains(problem));
  }
}

TEST_CASE("bench --compare: a tiny run against its own JSON, and a bad baseline's exit",
          "[unit][bench]") {
  using gjklab::testing::run_cli;
  gjklab::testing::ScratchDir dir("bench-compare-cli");
  const std::string base = dir.file("base.json"), now = dir.file("now.json");
  // Two cases (overlap, separated) of two algorithms, against gjk-johnson.
  const std::vector<std::string> tiny = words(
      "bench --suite seed --cases box-cone --algorithms gjk-johnson,epa --reference "
      "gjk-johnson --samples 2 --configurations 1 --batch-us 0 --quiet");
  std::vector<std::string> args = tiny;
  args.insert(args.end(), {"--json", base});
  REQUIRE(run_cli(args).status == 0);
  args = tiny;
  args.insert(args.end(), {"--compare", base, "--compare-threshold", "1.5", "--json", now});
  const gjklab::testing::CliResult r = run_cli(args);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Contains("compared with " + base));
  CHECK_THAT(r.out, Contains("summary: 4 rows compared"));
  std::ifstream in(now);
  const nlohmann::json doc = nlohmann::json::parse(in);
  REQUIRE(doc.contains("compare"));
  CHECK(doc["compare"]["baseline"] == base);
  CHECK(doc["compare"]["threshold"] == 1.5);
  CHECK(doc["compare"]["rows"].size() == 4);
  CHECK(doc["compare"]["not_compared"].empty());
  CHECK(doc["meta"]["precision"] == "double");
  for (const auto& row : doc["compare"]["rows"])
    if (row["algorithm"] == "epa")
      CHECK(row["change"].get<double>() ==
            Approx(row["ratio_to_reference"].get<double>() /
                   row["baseline_ratio_to_reference"].get<double>()));

  // A bad baseline stops the command before the run, with the file and the problem.
  write_file(base, "{\"records\": 3}");
  args = tiny;
  args.insert(args.end(), {"--compare", base});
  const gjklab::testing::CliResult bad = run_cli(args);
  CHECK(bad.status == 2);
  CHECK_THAT(bad.err, Contains(base + ": has no \"records\" array"));
  CHECK(bad.out.empty());
  // --compare-threshold needs --compare.
  args = tiny;
  args.insert(args.end(), {"--compare-threshold", "1.2"});
  CHECK(run_cli(args).status == 2);
}
