// Runs that lost or overwrote data, or accepted nonsense, with a hostile but plausible
// command line: each now stops with a clear error and leaves every file it did not create
// as it was.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/experiment/archive/archive.hpp"

using gjklab::testing::run_cli;
using gjklab::testing::ScratchDir;
namespace fs = std::filesystem;

namespace {

constexpr const char* kSmall = R"(name = "hostile-run"
seed = 3
cases = 40
[oracle]
enabled = false
[[family]]
name = "fa"
shape = "sphere_points"
[[algorithm]]
name = "gjk-bool"
)";

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("a fresh run never replaces an interrupted run's FILE.tmp or a starting run's file",
          "[regression][hostile]") {
  // A fresh run without --force replaced a resumable FILE.tmp (3348 cases) with its own; a
  // second run on the same --out failed on the HDF5 lock and then deleted the first run's
  // FILE.tmp. Stand-ins for the other run's files must come out untouched.
  ScratchDir dir("hostile-run");
  const std::string experiment = dir.file("small.toml");
  std::ofstream(experiment) << kSmall;
  const fs::path out = dir.file("out.h5");
  for (const char* suffix : {".tmp", ".tmp.new"}) {
    INFO(suffix);
    const fs::path other = out.string() + suffix;
    std::ofstream(other) << "another run's data";
    const auto r = run_cli({"run", experiment, "--out", out.string()});
    CHECK(r.status != 0);
    CHECK(r.err.find(other.string() + " exists") != std::string::npos);
    CHECK(contents(other) == "another run's data");
    CHECK_FALSE(fs::exists(out));
    fs::remove(other);
  }
  // --resume is named in the message for the interrupted run; --force replaces on purpose.
  std::ofstream(out.string() + ".tmp") << "stale";
  CHECK(run_cli({"run", experiment, "--out", out.string()}).err.find("--resume") !=
        std::string::npos);
  CHECK(run_cli({"run", experiment, "--out", out.string(), "--force"}).status == 0);
  CHECK(gjklab::experiment::read_archive(out).complete);
}

TEST_CASE("--out naming the experiment file is refused", "[regression][hostile]") {
  ScratchDir dir("hostile-run");
  const std::string experiment = dir.file("small.toml");
  std::ofstream(experiment) << kSmall;
  const auto r = run_cli({"run", experiment, "--out", experiment, "--force"});
  CHECK(r.status == 2);
  CHECK(r.err.find("would overwrite the experiment file") != std::string::npos);
  CHECK(contents(experiment) == kSmall);
}

TEST_CASE("a sweep of 10^6 values is refused before the run, with its line",
          "[regression][hostile]") {
  // Each value is a result group: a million of them took 8 GB and then aborted in HDF5.
  ScratchDir dir("hostile-run");
  std::string text = std::string(kSmall) + "[sweep]\nparameter = \"max_iterations\"\nvalues = [";
  for (int i = 1; i <= 1000; ++i)
    text += std::to_string(i) + (i < 1000 ? ", " : "]\n");
  const std::string experiment = dir.file("sweep.toml");
  std::ofstream(experiment) << text;
  const auto r = run_cli({"run", experiment, "--out", dir.file("sweep.h5")});
  CHECK(r.status == 2);
  CHECK(r.err.find("sweep.toml:13") != std::string::npos);
  CHECK(r.err.find("at most 256 values") != std::string::npos);
}

TEST_CASE("two families of weight 1e308 share the cases", "[regression][hostile]") {
  // The weights' sum overflowed to infinity and every case went to the last family.
  ScratchDir dir("hostile-run");
  const std::string experiment = dir.file("weights.toml");
  std::ofstream(experiment) << R"(name = "weights"
seed = 5
cases = 200
[oracle]
enabled = false
[[family]]
name = "fa"
shape = "sphere_points"
weight = 1e308
[[family]]
name = "fb"
shape = "cube_points"
weight = 1e308
[[algorithm]]
name = "gjk-bool"
)";
  const fs::path out = dir.file("weights.h5");
  REQUIRE(run_cli({"run", experiment, "--out", out.string()}).status == 0);
  std::map<std::uint32_t, int> per_family;
  for (const auto& r : gjklab::experiment::read_archive(out).results)
    ++per_family[r.record.family];
  CHECK(per_family[0] > 60);
  CHECK(per_family[1] > 60);
}

TEST_CASE("query --radius-a nan, query --cases FOLDER, replay --case -1: clear errors",
          "[regression][hostile]") {
  const std::string tetra = std::string(GJKLAB_TEST_DATA_DIR) + "/tetra.xyz";
  auto r = run_cli({"query", "--radius-a", "nan", tetra, tetra});
  CHECK(r.status == 2);
  CHECK(r.err.find("finite") != std::string::npos);
  ScratchDir dir("hostile-run");
  r = run_cli({"query", "--cases", dir.path().string()});
  CHECK(r.status != 0);
  CHECK(r.err.find("is a folder") != std::string::npos);
  r = run_cli({"replay", dir.file("none.h5"), "--case", "-1"});
  CHECK(r.status != 0);
  CHECK(r.err.find("not a case id") != std::string::npos);
}

TEST_CASE("an archive with one flipped byte that crashes libhdf5: inspect and replay report it",
          "[regression][hostile]") {
  // A 50-case quickstart archive with the byte at offset 5221 changed from 0x00 to 0xe6: libhdf5
  // segfaults in its global-heap reader (H5HG_read) while reading a variable-length string.
  // The archive is now read first in a child process, and its crash becomes an error.
  const std::string archive = std::string(GJKLAB_REGRESSION_DATA_DIR) +
                              "/hostile/archive_one_byte_flipped_hdf5_segfault.h5";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"inspect", archive},
        std::vector<std::string>{"replay", archive, "--case", "3"}}) {
    INFO(args[0]);
    const auto r = run_cli(args);
    CHECK(r.status == 1);
    CHECK(r.err.find("corrupt: reading it made the HDF5 library crash") != std::string::npos);
  }
}

TEST_CASE("values that only failed at run time are refused with FILE:LINE before it",
          "[regression][hostile]") {
  // Each once started the run, left a FILE.tmp and then failed without naming the key.
  ScratchDir dir("hostile-run");
  const std::string head = "name = \"late\"\nseed = 1\ncases = 4\n";
  const std::string family = "[[family]]\nname = \"s\"\nshape = \"sphere_points\"\n";
  struct Bad {
    std::string body, message;
  };
  const Bad bad[] = {
      {head + family + "radius = 1e308\n[[algorithm]]\nname = \"gjk-johnson\"\n",
       "late.toml:7: key 'family[0].radius': must be at most 1e+100"},
      {head + family + "[[algorithm]]\nname = \"epa\"\nmax_faces = 1\n",
       "late.toml:9: key 'algorithm[0].max_faces': must be in [4, 2^26]"},
      {head + family +
           "[[algorithm]]\nname = \"gjk-johnson\"\n[sweep]\nparameter = \"max_iterations\"\n"
           "values = [4, 4]\n",
       "late.toml:11: key 'sweep.values': value 4 appears twice"},
  };
  for (const Bad& b : bad) {
    INFO(b.message);
    const std::string experiment = dir.file("late.toml");
    std::ofstream(experiment) << b.body;
    const fs::path out = dir.file("late.h5");
    const auto r = run_cli({"run", experiment, "--out", out.string()});
    CHECK(r.status == 2);
    CHECK(r.err.find(b.message) != std::string::npos);
    CHECK_FALSE(fs::exists(out.string() + ".tmp"));
  }
}
