// The experiment driver: determinism across thread counts, a smoke run end to end, and the
// temporary-file-then-rename rule as seen from a run.
#include <catch2/catch.hpp>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gjklab/cli.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/run/driver.hpp"

using namespace gjklab::experiment;
namespace fs = std::filesystem;

namespace {

const char* kTinyExperiment = R"(
name = "tiny"
seed = 42
cases = 40
threads = 1
output = "unused.h5"

[placement]
mode = "mixed"
gap = [1e-6, 1.0]
depth = [1e-4, 0.3]

[[family]]
shape = "sphere_points"
vertices = [4, 24]

[[family]]
name = "boxes"
shape = "box"

[[algorithm]]
name = "gjk-bool"

[[algorithm]]
name = "gjk-johnson"

[[algorithm]]
name = "libccd-mpr"
max_iterations = 32
)";

/// A fresh folder under the system's temporary directory, removed at the end of the scope.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("gjklab-driver-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  static int& counter() {
    static int n = 0;
    return n;
  }
};

bool same_double(double x, double y) {
  return (std::isnan(x) && std::isnan(y)) || x == y;
}

void require_same_results(const std::vector<CaseResult>& x, const std::vector<CaseResult>& y) {
  REQUIRE(x.size() == y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    INFO("case " << i);
    CHECK(x[i].record.case_id == y[i].record.case_id);
    CHECK(x[i].record.size == y[i].record.size);
    REQUIRE(x[i].exact.has_value() == y[i].exact.has_value());
    if (x[i].exact) {
      CHECK(x[i].exact->distance2_num == y[i].exact->distance2_num);
      CHECK(x[i].exact->distance2_den == y[i].exact->distance2_den);
    }
    REQUIRE(x[i].algorithms.size() == y[i].algorithms.size());
    for (std::size_t k = 0; k < x[i].algorithms.size(); ++k) {
      const auto &p = x[i].algorithms[k], &q = y[i].algorithms[k];
      CHECK(p.intersect == q.intersect);
      CHECK(same_double(p.distance, q.distance));
      CHECK(same_double(p.rel_error, q.rel_error));
      CHECK(p.iterations == q.iterations);
      CHECK(p.termination == q.termination);
    }
    CHECK(x[i].geometry.has_value() == y[i].geometry.has_value());
  }
}

}  // namespace

TEST_CASE("driver: the archive is identical with 1 and 2 threads", "[unit][driver]") {
  const ExperimentConfig config = parse_experiment(kTinyExperiment, "tiny.toml");
  TempDir dir;
  RunOptions one, two;
  one.output = (dir.path / "one.h5").string();
  one.threads = 1;
  two.output = (dir.path / "two.h5").string();
  two.threads = 2;
  const RunReport r1 = run_experiment(config, one);
  const RunReport r2 = run_experiment(config, two);
  CHECK(r1.cases == 40);
  const Archive a1 = read_archive(*one.output), a2 = read_archive(*two.output);
  CHECK(a1.complete);
  CHECK(a2.complete);
  require_same_results(a1.results, a2.results);
  // The sample exercises both exact answers.
  int intersecting = 0;
  for (const auto& r : a1.results)
    intersecting += r.exact->intersect;
  CHECK(intersecting > 0);
  CHECK(intersecting < 40);
}

TEST_CASE("driver: evaluate_case is a function of (seed, case id)", "[unit][driver]") {
  const ExperimentConfig config = parse_experiment(kTinyExperiment, "tiny.toml");
  const CaseResult first = evaluate_case(config, 7);
  evaluate_case(config, 3);
  const CaseResult again = evaluate_case(config, 7);
  CHECK(again.record.case_id == 7);
  require_same_results({first}, {again});
}

TEST_CASE("gjklab run: smoke run, existing output, inspect", "[smoke][driver]") {
  TempDir dir;
  const fs::path experiment = dir.path / "tiny.toml";
  {
    std::ofstream f(experiment);
    f << kTinyExperiment;
  }
  const fs::path out = dir.path / "tiny.h5";
  auto run = [&](std::vector<std::string> args, std::string* output = nullptr) {
    std::vector<const char*> argv{"gjklab"};
    for (const auto& a : args)
      argv.push_back(a.c_str());
    std::istringstream in;
    std::ostringstream o, e;
    const int status = gjklab::cli::run(static_cast<int>(argv.size()), argv.data(), in, o, e);
    if (output) *output = o.str() + e.str();
    return status;
  };
  std::string text;
  REQUIRE(run({"run", experiment.string(), "--out", out.string(), "--cases", "12"}, &text) == 0);
  CHECK(fs::exists(out));
  CHECK_FALSE(fs::exists(out.string() + ".tmp"));
  CHECK_THAT(text, Catch::Contains("gjk-johnson"));
  CHECK_THAT(text, Catch::Contains("12 cases"));

  // An existing output is not overwritten without --force, and nothing is started.
  REQUIRE(run({"run", experiment.string(), "--out", out.string()}, &text) == 1);
  CHECK_THAT(text, Catch::Contains("exists"));
  CHECK(read_archive(out).results.size() == 12);
  REQUIRE(run({"run", experiment.string(), "--out", out.string(), "--cases", "5", "--force"}) == 0);
  CHECK(read_archive(out).results.size() == 5);

  // Replay reruns an archived case (geometry regenerated from the archived experiment when
  // it was not kept) with the archived options, and finds the same answers.
  REQUIRE(run({"replay", out.string(), "--case", "3", "--trace"}, &text) == 0);
  CHECK_THAT(text, Catch::Contains("gjk-johnson: intersect"));
  CHECK_THAT(text, Catch::Contains("equals the archived result"));
  CHECK_THAT(text, Catch::Contains("it 1 "));
  CHECK_THAT(text, Catch::Contains("libccd-mpr is not traceable"));
  REQUIRE(run({"replay", out.string(), "--case", "99"}, &text) == 1);
  CHECK_THAT(text, Catch::Contains("no case 99"));
  REQUIRE(run({"replay", out.string(), "--case", "1", "--algorithm", "nope"}, &text) == 1);
  CHECK_THAT(text, Catch::Contains("no algorithm 'nope'"));

  REQUIRE(run({"inspect", out.string()}, &text) == 0);
  CHECK_THAT(text, Catch::Contains("complete"));
  CHECK_THAT(text, Catch::Contains("cgal_version"));
  CHECK_THAT(text, Catch::Contains("libccd-mpr"));

  // Unwritable output folder: reported before any work.
  REQUIRE(run({"run", experiment.string(), "--out", (dir.path / "no/such/dir/x.h5").string()},
              &text) == 1);
  CHECK_THAT(text, Catch::Contains("no/such/dir"));
  // A config error names the file.
  {
    std::ofstream f(experiment);
    f << "name = \"x\"\nseed = 1\ncases = 3\nbogus = 2\n";
  }
  REQUIRE(run({"run", experiment.string()}, &text) == 2);
  CHECK_THAT(text, Catch::Contains("tiny.toml:4"));
}

TEST_CASE("driver: a stop request leaves an incomplete archive under the temporary name",
          "[unit][driver]") {
  const ExperimentConfig config = parse_experiment(kTinyExperiment, "tiny.toml");
  TempDir dir;
  RunOptions options;
  options.output = (dir.path / "stopped.h5").string();
  const std::atomic<bool> stop{true};
  options.stop = &stop;
  const RunReport report = run_experiment(config, options);
  CHECK_FALSE(report.complete);
  CHECK(report.cases == 0);
  CHECK_FALSE(fs::exists(*options.output));
  REQUIRE(fs::exists(*options.output + ".tmp"));
  const Archive archive = read_archive(*options.output + ".tmp");
  CHECK_FALSE(archive.complete);
  CHECK(archive.results.empty());
}

TEST_CASE("driver: a run stopped after a checkpoint resumes to the uninterrupted archive",
          "[unit][driver]") {
  const ExperimentConfig config = parse_experiment(kTinyExperiment, "tiny.toml");
  TempDir dir;
  RunOptions whole;
  whole.output = (dir.path / "whole.h5").string();
  run_experiment(config, whole);

  RunOptions part;
  part.output = (dir.path / "part.h5").string();
  part.checkpoint_cases = 7;
  part.stop_after = 15;
  const RunReport stopped = run_experiment(config, part);
  CHECK_FALSE(stopped.complete);
  CHECK(stopped.cases == 21);  // three checkpoints of 7
  CHECK(read_archive(*part.output + ".tmp").results.size() == 21);

  RunOptions more;
  more.threads = 2;
  const RunReport resumed = resume_experiment(*part.output + ".tmp", more);
  CHECK(resumed.complete);
  CHECK(resumed.resumed_cases == 21);
  CHECK_FALSE(fs::exists(*part.output + ".tmp"));
  CHECK_FALSE(fs::exists(*part.output + ".tmp.partial"));
  const Archive a = read_archive(*whole.output), b = read_archive(*part.output);
  CHECK(b.complete);
  CHECK(a.header.start_time <= b.header.start_time);
  require_same_results(a.results, b.results);
  CHECK_THROWS_WITH(resume_experiment(*part.output, more), Catch::Contains("no interrupted run"));
}

TEST_CASE("driver: traces of every query are archived and read back", "[unit][driver]") {
  const ExperimentConfig config =
      parse_experiment(std::string(kTinyExperiment) + "\n[trace]\nmode = \"all\"\n", "tiny.toml");
  TempDir dir;
  RunOptions options;
  options.output = (dir.path / "traced.h5").string();
  options.cases = 10;
  run_experiment(config, options);
  const Archive archive = read_archive(*options.output);
  CHECK(archive.header.trace_mode == TraceMode::all);
  REQUIRE(archive.results.size() == 10);
  for (const CaseResult& r : archive.results) {
    REQUIRE(r.traces.size() == 3);
    // gjk-bool and gjk-johnson: one trace row per iteration; libccd cannot be traced.
    for (int k : {0, 1}) {
      CHECK(r.traces[k].size() == static_cast<std::size_t>(r.algorithms[k].iterations));
      for (std::size_t i = 0; i < r.traces[k].size(); ++i)
        CHECK(r.traces[k][i].iteration == static_cast<int>(i) + 1);
    }
    CHECK(r.traces[2].empty());
    // The last row of a converged query names the branch that ended it.
    if (r.algorithms[1].termination == gjklab::Termination::converged)
      CHECK(r.traces[1].back().step != gjklab::GjkStep::continued);
  }
}

TEST_CASE("driver: SAT's axis counts are identical with 1 and 2 threads", "[unit][driver]") {
  // CGAL's hull listed the faces of a cloud in an order that varied with the thread that hulled
  // it, and SAT's early exit counts axes in face order: its iteration counts differed between
  // runs. Hull features now come in a canonical order.
  const ExperimentConfig config = parse_experiment(R"(
name = "sat-threads"
seed = 23
cases = 120
output = "unused.h5"
[placement]
mode = "mixed"
[[family]]
shape = "sphere_points"
vertices = [8, 48]
[[algorithm]]
name = "sat"
)",
                                                   "sat-threads.toml");
  TempDir dir;
  RunOptions one, two;
  one.output = (dir.path / "one.h5").string();
  one.threads = 1;
  two.output = (dir.path / "two.h5").string();
  two.threads = 2;
  run_experiment(config, one);
  run_experiment(config, two);
  const Archive a1 = read_archive(*one.output), a2 = read_archive(*two.output);
  REQUIRE(a1.results.size() == 120);
  require_same_results(a1.results, a2.results);
  int separated = 0;
  for (const auto& r : a1.results)
    separated += !r.exact->intersect;
  CHECK(separated > 20);  // early exits happen
}
