// `gjklab run` killed for real (SIGKILL, SIGINT) at several points, then `--resume`d: the
// finished archive equals an uninterrupted run's, dataset by dataset and timing aside,
// including the traces and the kept geometry that straddle checkpoints.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;

// Near-contact and parallel-edge pairs, so that failing queries keep traces and geometry in
// most checkpoints; timed repetitions make the run long enough to be interrupted.
constexpr const char* kExperiment = R"(name = "resume-cli"
seed = 31
cases = 1500
threads = 2
[trace]
mode = "failing"
[timing]
enabled = true
repetitions = 15
[placement]
mode = "mixed"
gap = [1e-15, 1e-3]
depth = [1e-15, 1e-3]
[[family]]
name = "parallel-edges"
shape = "contact"
contact = "parallel-edges"
angle = [1e-9, 1e-2]
[[family]]
name = "grazing"
shape = "sphere_points"
vertices = [8, 64]
[[algorithm]]
name = "gjk-johnson"
[[algorithm]]
name = "gjk-sv"
[[algorithm]]
name = "gjk-bool"
)";

std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

/// Starts `gjklab run` with the arguments, its standard output discarded and its standard error
/// written to `error_log` (discarded by default); returns its pid.
pid_t start(const std::vector<std::string>& args, const std::string& error_log = "/dev/null") {
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::vector<char*> argv;
    static const std::string binary = GJKLAB_BINARY;
    argv.push_back(const_cast<char*>(binary.c_str()));
    for (const std::string& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    std::freopen("/dev/null", "w", stdout);
    std::freopen(error_log.c_str(), "w", stderr);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

/// The text of a file (empty if it cannot be read).
std::string file_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Waits for the process; its exit status, or 128 + the signal that ended it.
int finish(pid_t pid) {
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// True if the two archives hold the same datasets with the same values, timing aside.
bool same_archives(const fs::path& a, const fs::path& b) {
  const std::string script = std::string(GJKLAB_TESTS_DIR) + "/../tools/compare-archives";
  const std::string command = quoted(GJKLAB_PYTHON3) + " " + quoted(script) + " --strict " +
                              quoted(a.string()) + " " + quoted(b.string()) + " > /dev/null";
  return std::system(command.c_str()) == 0;
}

}  // namespace

TEST_CASE("run killed by SIGKILL or SIGINT, then resumed, equals an uninterrupted run",
          "[smoke][resume]") {
  const fs::path dir = fs::temp_directory_path() / "gjklab-resume-cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path experiment = dir / "resume.toml";
  std::ofstream(experiment) << kExperiment;
  const fs::path reference = dir / "reference.h5";
  REQUIRE(finish(start({"run", experiment.string(), "--out", reference.string()})) == 0);
  REQUIRE(fs::exists(reference));

  int resumed = 0;
  for (const int signal : {SIGKILL, SIGINT}) {
    for (const int delay_ms : {150, 400, 900}) {
      INFO("signal " << signal << " after " << delay_ms << " ms");
      const fs::path out =
          dir / ("run-" + std::to_string(signal) + "-" + std::to_string(delay_ms) + ".h5");
      fs::path temporary = out;
      temporary += ".tmp";
      const pid_t pid =
          start({"run", experiment.string(), "--out", out.string(), "--checkpoint", "64"});
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      kill(pid, signal);
      const int status = finish(pid);
      if (fs::exists(out)) {  // finished before the signal arrived
        CHECK(status == 0);
        CHECK(same_archives(reference, out));
        continue;
      }
      if (!fs::exists(temporary)) continue;  // killed before the archive was created
      // SIGINT finishes the started cases and exits 130; SIGKILL ends it at once.
      CHECK(status == (signal == SIGINT ? 130 : 128 + SIGKILL));
      const fs::path resume_log =
          dir / ("resume-" + std::to_string(signal) + "-" + std::to_string(delay_ms) + ".log");
      const int resume_status =
          finish(start({"run", "--resume", temporary.string()}, resume_log.string()));
      INFO("the resume's standard error: " << file_text(resume_log));
      REQUIRE(resume_status == 0);
      CHECK_FALSE(fs::exists(temporary));
      REQUIRE(fs::exists(out));
      CHECK(same_archives(reference, out));
      ++resumed;
    }
  }
  CHECK(resumed >= 2);  // some of the signals really interrupted the run
  fs::remove_all(dir);
}

TEST_CASE(
    "run killed after its archive was marked complete, before the rename: --resume renames it",
    "[smoke][resume]") {
  // ArchiveWriter::finish writes the completion flag, closes the file and then renames FILE.tmp
  // to FILE; a SIGKILL between the two left a complete FILE.tmp that --resume refused as
  // "already complete" (seen once in the signal test above).
  const fs::path dir = fs::temp_directory_path() / "gjklab-resume-complete";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path experiment = dir / "resume.toml";
  std::ofstream(experiment) << kExperiment;
  const fs::path reference = dir / "reference.h5", out = dir / "run.h5";
  REQUIRE(finish(start({"run", experiment.string(), "--out", reference.string()})) == 0);
  fs::path temporary = out;
  temporary += ".tmp";
  fs::copy_file(reference, temporary);
  const fs::path log = dir / "resume.log";
  const int status = finish(start({"run", "--resume", temporary.string()}, log.string()));
  INFO("the resume's standard error: " << file_text(log));
  CHECK(status == 0);
  CHECK_FALSE(fs::exists(temporary));
  REQUIRE(fs::exists(out));
  CHECK(same_archives(reference, out));
  // With the final archive already there, both files are kept and the resume says so.
  fs::copy_file(reference, temporary);
  CHECK(finish(start({"run", "--resume", temporary.string()}, log.string())) == 1);
  CHECK(file_text(log).find("already complete") != std::string::npos);
  CHECK(fs::exists(temporary));
  fs::remove_all(dir);
}
