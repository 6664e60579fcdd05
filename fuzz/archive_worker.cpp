// The archive target's reading worker (fuzz/archive.cpp): the first of the two reads that
// experiment::read_archive_isolated makes, kept in one long-lived process instead of a fork per
// input. Built with ASan and UBSan like the target, without libFuzzer.
//
// Usage: fuzz_archive_worker FILE. For each byte read on standard input it reads FILE with
// experiment::read_archive (what read_archive_isolated's child runs) and answers one byte on
// standard output: 'r' read, 'e' an exception (the child's failure, an ArchiveError for the
// user). It ends at the end of its input. Anything the reader prints goes to standard error.
// How it ends otherwise, as the target sees it:
//  - killed by a signal: libhdf5 crashed on the file (as read_archive_isolated's child would),
//    or a sanitizer report whose first frame is in libhdf5 (raised as SIGSEGV, as the same
//    read segfaults in the program);
//  - exit status kSanitizerReport: any other sanitizer report (our reader's code, undefined
//    behaviour), printed on standard error first: a finding.
// The target starts it with ASan's symbolize=0 (frames as addresses; see frames_in_libhdf5). For
// a finding's report with names: `printf x | fuzz_archive_worker FILE` on the saved input.
#include <dlfcn.h>
#include <hdf5.h>
#include <sanitizer/asan_interface.h>
#include <sanitizer/common_interface_defs.h>
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include "gjklab/experiment/archive/archive.hpp"
#include "libhdf5_report.hpp"

namespace {

constexpr int kSanitizerReport = 77;  ///< the exit status for a finding (fuzz/archive.cpp)

bool report_in_libhdf5 = false;

/// Whether the report's first frame outside the sanitizer runtime and the C library is in
/// libhdf5, from the frames' addresses: the worker runs with symbolize=0 (fuzz/archive.cpp),
/// since starting the symbolizer in every worker that dies on a libhdf5 crash (a few in a
/// hundred inputs) took longer than all the reads. The runtime's entry points (interceptors,
/// __asan_*) are the executable's exported symbols; its internal helpers and gjklab's own
/// functions are not exported, so dladdr names neither. A helper is always called by an entry
/// point (MemcmpInterceptorCommon by __interceptor_memcmp, the frame below it): unnamed frames
/// of the executable count as the runtime's only above a named one. An unnamed frame of the
/// executable below a named one is gjklab's code (a finding), and so is one directly above
/// libhdf5 (a callback that libhdf5 called).
bool frames_in_libhdf5(std::string_view report) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  bool seen_entry_point = false;
  bool helpers_closed = true;  // every unnamed frame so far has a named entry point below it
  for (std::size_t at = report.find("    #"); at != std::string_view::npos;
       at = report.find("    #", at + 1)) {
    const std::size_t hex = report.find("0x", at);
    if (hex == std::string_view::npos) return false;
    const auto pc = std::strtoull(std::string(report.substr(hex, 18)).c_str(), nullptr, 16);
    Dl_info info{};
    if (pc == 0 || ::dladdr(reinterpret_cast<void*>(pc), &info) == 0 || !info.dli_fname)
      return false;
    const std::string_view module = info.dli_fname;
    if (module.find("libhdf5") != std::string_view::npos) return helpers_closed;
    if (module.find("libc.so") != std::string_view::npos) continue;
    const bool in_self = std::filesystem::path(module) == self || module == "" ||
                         std::filesystem::weakly_canonical(std::string(module)) == self;
    if (!in_self) return false;
    if (info.dli_sname) {  // a runtime entry point
      seen_entry_point = true;
      helpers_closed = true;
      continue;
    }
    if (seen_entry_point) return false;  // gjklab's code below the runtime
    helpers_closed = false;              // a runtime helper, if an entry point follows
  }
  return false;
}

void on_report(const char* report) {
  // A symbolised report (symbolize=1 given) names the frames; otherwise use the addresses.
  report_in_libhdf5 = gjklab::fuzz::report_is_in_libhdf5(report) || frames_in_libhdf5(report);
}

void on_death() {
  if (report_in_libhdf5) {
    ::signal(SIGSEGV, SIG_DFL);
    ::raise(SIGSEGV);
  }
  ::_exit(kSanitizerReport);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  // Ends with the target, also in the middle of a read (libhdf5 loops forever on some corrupt
  // global heaps): a worker left behind by an interrupted run spun for an hour.
  if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() == 1) return 2;
  const std::filesystem::path path = argv[1];
  // Answers go to the original standard output; the reader's own output, if any, to stderr.
  const int answers = ::dup(STDOUT_FILENO);
  if (answers < 0 || ::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) return 2;
  __asan_set_error_report_callback(on_report);
  __sanitizer_set_death_callback(on_death);
  char request;
  while (::read(STDIN_FILENO, &request, 1) == 1) {
    char answer = 'r';
    H5close();  // each read starts from a library that has read nothing (fuzz/archive.cpp)
    try {
      (void)gjklab::experiment::read_archive(path);
    } catch (const std::exception&) {
      answer = 'e';
    }
    if (::write(answers, &answer, 1) != 1) break;
  }
  ::_exit(0);  // no leak check at the end: the target checks leaks in its own process
}
