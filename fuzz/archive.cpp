// Result archives: `gjklab inspect`, `replay` and `resume` read them with
// experiment::read_archive_isolated, which reads the file once in a forked child (libhdf5
// itself crashes on some corrupt files, an upstream bug) and, if the child neither failed nor
// crashed, again in the calling process. `inspect` then summarises the results.
//
// Input: the archive file's bytes. The target makes the same two reads, the first one in a
// long-lived worker process (fuzz/archive_worker.cpp) instead of a child forked per input: the
// fork, and the page faults of two processes sharing 80 MB copy-on-write after it, were most
// of the time per input (measured: 14 ms of 16 in the kernel). How the reads are checked:
//  - The worker's read (read_archive, what read_archive_isolated's child runs). It answers
//    whether the file was read or threw (then the input is an ArchiveError, as for a user, and
//    is not read again). A sanitizer report in the worker whose first frame is not in libhdf5
//    (our reader's code, undefined behaviour) ends it with a status the target traps on, so
//    libFuzzer saves the input; the report is on stderr.
//  - If the worker crashed (libhdf5's own crash, or a sanitizer report inside libhdf5, which
//    the worker raises as SIGSEGV as the same read segfaults in the program) or did not answer
//    within its time limit (kWorkerCpuSeconds), a new worker starts for the next input, and the
//    file is read by read_archive_isolated itself, the product's containment, in a fresh forked
//    child (the first 4 such files of a run, then one in 16: isolated_read_due): it must give an
//    ArchiveError (or, if the crash was the worker's state rather than the file's, an archive,
//    checked as below). That child inherits libFuzzer's and the sanitizers' handlers; a
//    pthread_atfork handler puts the default action back on SIGSEGV, SIGBUS, SIGFPE and
//    SIGILL, so that a libhdf5 crash kills it by the signal as in the program, and its
//    sanitizer reports are handled as the worker's (libhdf5's: SIGSEGV; any other: a flag in
//    memory shared with the parent, which traps).
//  - The in-process read (the second one) of every file the worker read runs under libFuzzer
//    and the sanitizers like any other target: a crash, a sanitizer report or a leak there is a
//    finding.
// Every read, the worker's, the in-process one and read_archive_isolated's, starts from a library
// that has read nothing (H5close before it), as in `gjklab inspect`, which reads one file: libhdf5
// keeps state between reads (its datatype conversion paths), and some corrupt files that read
// cleanly the first time make H5T_cmp compare an enum name past its end when read again (the
// worker reading a file twice shows it). Without the reset, the worker's answer for a file did
// not say how the target's own read of it would go.
// Properties: reading gives an Archive or an ArchiveError, nothing else; a read archive has
// one options list per algorithm and one record per algorithm in every result; the inspect
// summary of it is printed without error.
#include <fcntl.h>
#include <hdf5.h>
#include <poll.h>
#include <pthread.h>
#include <sanitizer/allocator_interface.h>
#include <sanitizer/asan_interface.h>
#include <sanitizer/common_interface_defs.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/run/summary.hpp"
#include "libhdf5_report.hpp"
#include "support.hpp"

extern char** environ;

namespace {

using gjklab::fuzz::violated;
namespace experiment = gjklab::experiment;

/// A flag shared with the forked children: set when a child's sanitizer reported an error in
/// gjklab's code.
std::atomic<int>* child_reported = nullptr;

/// Whether the child's sanitizer report is about libhdf5 itself. Set by the report callback.
bool report_in_libhdf5 = false;

void child_sanitizer_report(const char* report) {
  report_in_libhdf5 = gjklab::fuzz::report_is_in_libhdf5(report);
}

/// A report about libhdf5 (an out-of-bounds read inside it, caught by the sanitizer's memcpy
/// check before it segfaults) ends the child by SIGSEGV, as the same read does in the program,
/// where read_archive_isolated contains it; any other report is a finding.
void child_sanitizer_death() {
  if (report_in_libhdf5) {
    ::signal(SIGSEGV, SIG_DFL);
    ::raise(SIGSEGV);
  }
  child_reported->store(1);
  ::_exit(1);
}

/// Runs in every forked child (before read_archive_isolated's child code).
void in_forked_child() {
  for (const int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL})
    ::signal(s, SIG_DFL);
  __asan_set_error_report_callback(child_sanitizer_report);
  __sanitizer_set_death_callback(child_sanitizer_death);
}

void check_archive(const experiment::Archive& archive) {
  const auto& h = archive.header;
  if (h.algorithm_options.size() != h.algorithm_names.size())
    violated("an archive read with a different number of option lists and algorithms");
  for (const auto& r : archive.results)
    if (r.algorithms.size() != h.algorithm_names.size())
      violated("an archive result with a different number of records and algorithms");
  // What `gjklab inspect` does with it.
  std::ostringstream out;
  experiment::SummaryBuilder summary(h.algorithm_names);
  experiment::FamilySummaryBuilder by_family(h.family_names, h.algorithm_names);
  for (const auto& r : archive.results) {
    summary.add(r);
    by_family.add(r);
  }
  experiment::print_summary(out, summary.build());
  experiment::print_family_table(out, by_family.build());
  if (h.oracle)
    experiment::print_oracle_methods(
        out, experiment::oracle_method_counts(archive.results, h.family_names));
}

/// How long the worker may take over one file before it is killed and the file goes to
/// read_archive_isolated: libhdf5 loops forever on some corrupt global heaps (a profile of a
/// run found the workers in that loop 90 % of the time with a limit of 10 s, 71 % with 1 s,
/// and still 40 % with 0.1 s). 50 ms of the worker's CPU time, 2.5 times its slowest read of a
/// corpus file (20 ms: five reads of each of the 60 largest files), or 10 s of wall time (the
/// worker is starved beside other jobs). A file that a sound reader only reads slowly
/// (libhdf5 clearing a gigabyte it was asked for) is counted as timed out, not as a finding.
/// The target sets read_archive_isolated's own limit (GJKLAB_ARCHIVE_READ_SECONDS, wall time)
/// to 0.25 s unless given (its child loops until then: at 2 s, the isolated reads of looping
/// files were a sixth of a run's CPU time): both together stay within libFuzzer's -timeout
/// (run_target.sh: 25 s).
constexpr double kWorkerCpuSeconds = 0.05;
constexpr int kWorkerSeconds = 10;
constexpr const char* kIsolatedReadSeconds = "0.25";
/// Inputs a worker reads before a new one replaces it, so that whatever a corrupt file leaves
/// in libhdf5's state stays bounded.
constexpr int kWorkerInputs = 2000;
/// The worker's exit status for a sanitizer report in our code (fuzz/archive_worker.cpp).
constexpr int kWorkerSanitizerReport = 77;

struct Worker {
  pid_t pid = -1;
  int requests = -1;  ///< the worker's standard input
  int answers = -1;   ///< its standard output
  int served = 0;
};
Worker worker;
std::string worker_binary;
std::vector<std::string> worker_environment;

/// The worker's environment: this one, with ASan's allocations limited to libFuzzer's memory
/// limit (run_target.sh: 2560 MB) and a null return beyond it. A corrupt size makes libhdf5 ask
/// for gigabytes often (3 % of the inputs, measured): libhdf5 then fails with an error (an
/// ArchiveError), where the forked child met libFuzzer's own limit, wrote an `oom-` input and
/// exited, 3 s each, most of the time of the run. `operator new` beyond the limit (our reader's
/// allocations) is still a sanitizer report, so a finding.
void make_worker_environment() {
  std::string asan = "ASAN_OPTIONS=";
  for (char** e = environ; *e; ++e) {
    const std::string_view entry(*e);
    if (entry.starts_with("ASAN_OPTIONS="))
      asan = std::string(entry) + ":";
    else
      worker_environment.emplace_back(entry);
  }
  worker_environment.push_back(
      asan + "max_allocation_size_mb=2560:allocator_may_return_null=1:symbolize=0");
}

/// What the workers did, printed when the run ends.
struct Counts {
  long reads = 0, threw = 0, died = 0, timed_out = 0, workers = 0, isolated = 0;
} counts;

void stop_worker() {
  if (worker.pid < 0) return;
  ::close(worker.requests);
  ::close(worker.answers);
  ::kill(worker.pid, SIGKILL);
  while (::waitpid(worker.pid, nullptr, 0) < 0 && errno == EINTR) {
  }
  worker = Worker{};
}

void start_worker(const std::filesystem::path& file) {
  int to[2], from[2];
  if (::pipe2(to, O_CLOEXEC) != 0 || ::pipe2(from, O_CLOEXEC) != 0)
    violated("cannot make the worker's pipes");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, to[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, from[1], STDOUT_FILENO);
  const std::string file_arg = file.string();
  std::vector<char*> args{worker_binary.data(), const_cast<char*>(file_arg.c_str()), nullptr};
  std::vector<char*> env;
  for (std::string& e : worker_environment)
    env.push_back(e.data());
  env.push_back(nullptr);
  pid_t pid = -1;
  // posix_spawn does not run the pthread_atfork handlers, and the worker is a new program.
  const int error =
      ::posix_spawn(&pid, worker_binary.c_str(), &actions, nullptr, args.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  ::close(to[0]);
  ::close(from[1]);
  if (error != 0) {
    std::fprintf(stderr, "cannot start %s: %s\n", worker_binary.c_str(), std::strerror(error));
    violated("cannot start the archive-reading worker");
  }
  worker = Worker{pid, to[1], from[0], 0};
  ++counts.workers;
}

/// The CPU time the worker has used so far, in seconds (0 if it cannot be read).
double worker_cpu_seconds() {
  clockid_t clock;
  timespec t{};
  if (::clock_getcpuclockid(worker.pid, &clock) != 0 || ::clock_gettime(clock, &t) != 0) return 0;
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

enum class WorkerRead { read, threw, died };

/// Asks the worker to read the file; waits for its answer.
WorkerRead read_in_worker(const std::filesystem::path& file) {
  if (worker.pid >= 0 && worker.served >= kWorkerInputs) stop_worker();
  if (worker.pid < 0) start_worker(file);
  ++worker.served;
  const char request = 1;
  char answer = 0;
  bool answered = ::write(worker.requests, &request, 1) == 1;
  if (answered) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kWorkerSeconds);
    const double cpu_deadline = worker_cpu_seconds() + kWorkerCpuSeconds;
    answered = false;
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                            deadline - std::chrono::steady_clock::now())
                            .count();
      const double cpu_left = cpu_deadline - worker_cpu_seconds();
      if (left <= 0 || cpu_left < 0) break;
      // The worker's CPU time grows no faster than wall time, so a wait as long as its CPU time
      // left cannot overshoot the limit (in whole milliseconds, at least 1).
      const long long slice = std::max(1LL, static_cast<long long>(cpu_left * 1000) + 1);
      pollfd p{worker.answers, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, slice)));
      if (ready < 0 && errno == EINTR) continue;
      if (ready == 0) continue;
      if (ready < 0) break;
      const ssize_t n = ::read(worker.answers, &answer, 1);
      if (n < 0 && errno == EINTR) continue;
      answered = n == 1;
      break;
    }
  }
  if (answered && answer == 'r') return ++counts.reads, WorkerRead::read;
  if (answered && answer == 'e') return ++counts.threw, WorkerRead::threw;
  ++counts.died;
  // No answer: it crashed, reported, or is still reading. Kill it if it still runs, then see
  // how it ended.
  ::close(worker.requests);
  ::close(worker.answers);
  ::kill(worker.pid, SIGKILL);
  int status = 0;
  while (::waitpid(worker.pid, &status, 0) < 0 && errno == EINTR) {
  }
  worker = Worker{};
  // Killed by this process's SIGKILL: it was still reading at the limit.
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) ++counts.timed_out;
  if (WIFEXITED(status) && WEXITSTATUS(status) == kWorkerSanitizerReport)
    violated("a sanitizer report in the archive-reading worker");
  return WorkerRead::died;
}

/// Whether the file that ended the worker goes to read_archive_isolated: the first 4 such
/// files, then one in 16. That read forks this process (hundreds of MB of ASan's memory) and
/// its child symbolises the sanitizer's report again, about half a second of each crashing
/// input's time, and a few in a hundred inputs crash libhdf5 (mostly one corrupt global heap);
/// the worker's death already shows that read_archive_isolated's child dies on the file, and
/// how the parent then answers does not depend on the file.
bool isolated_read_due() {
  return counts.died <= 4 || counts.died % 16 == 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char*** argv) {
  void* shared = ::mmap(nullptr, sizeof(std::atomic<int>), PROT_READ | PROT_WRITE,
                        MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED) violated("cannot map the flag shared with the children");
  child_reported = new (shared) std::atomic<int>(0);
  if (::pthread_atfork(nullptr, nullptr, in_forked_child) != 0)
    violated("cannot register the fork handler");
  // The worker is built next to the target (fuzz/CMakeLists.txt).
  std::error_code ec;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) self = (*argv)[0];
  // Run from a copy, so that relinking the worker while a run goes on changes nothing in it
  // (a worker started from the half-written file, or a report symbolised from the new one).
  const std::filesystem::path copy = gjklab::fuzz::scratch_folder() / "fuzz_archive_worker";
  std::filesystem::copy_file(self.parent_path() / "fuzz_archive_worker", copy, ec);
  if (ec) violated("cannot copy the archive-reading worker (fuzz_archive_worker)");
  worker_binary = copy.string();
  make_worker_environment();
  ::setenv("GJKLAB_ARCHIVE_READ_SECONDS", kIsolatedReadSeconds, 0);
  // A worker that has exited makes a write to its pipe raise SIGPIPE: an error return instead.
  ::signal(SIGPIPE, SIG_IGN);
  std::atexit([] {
    std::fprintf(
        stderr,
        "archive target: %ld files read by the worker, %ld refused, %ld that ended it "
        "(%ld of them still reading at the limit; %ld then read by read_archive_isolated); "
        "%ld workers started\n",
        counts.reads, counts.threw, counts.died, counts.timed_out, counts.isolated, counts.workers);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  H5close();  // the reads below start from a library that has read nothing (see the top)
  const auto path = gjklab::fuzz::write_scratch_file("run.h5", std::span(data, size));
  switch (read_in_worker(path)) {
    case WorkerRead::threw:
      return 0;  // an ArchiveError for the user; read_archive_isolated reads no further
    case WorkerRead::read:
      try {
        check_archive(experiment::read_archive(path));
      } catch (const experiment::ArchiveError&) {
      }
      return 0;
    case WorkerRead::died:
      if (!isolated_read_due()) return 0;
      break;
  }
  // The file crashed (or hung) the reader: the product's containment must hold on it. The fork
  // copies the page tables of every page this process holds, most of them ASan's quarantine of
  // freed blocks unless emptied first (340 MB resident instead of 80 MB, measured).
  __sanitizer_purge_allocator();
  ++counts.isolated;
  try {
    check_archive(experiment::read_archive_isolated(path));
  } catch (const experiment::ArchiveError&) {
  }
  if (child_reported->load() != 0) violated("a sanitizer report in the archive-reading child");
  return 0;
}
