// Result archives: `gjklab inspect`, `replay` and `resume` read them with
// experiment::read_archive_isolated, which reads the file once in a forked child (libhdf5
// itself crashes on some corrupt files, an upstream bug) and, if the child neither failed nor
// crashed, again in the calling process. `inspect` then summarises the results.
//
// Input: the archive file's bytes. How the two reads are checked:
//  - The in-process read (the second one) runs under libFuzzer and the sanitizers like any
//    other target: a crash, a sanitizer report or a leak there is a finding.
//  - The forked child inherits libFuzzer's and the sanitizers' handlers. A child crash that the
//    parent contains must look as it does in the program, so the child (pthread_atfork) puts
//    the default action back on SIGSEGV, SIGBUS, SIGFPE and SIGILL: a libhdf5 crash kills it
//    by that signal and read_archive_isolated turns it into an ArchiveError, as for a user.
//    The sanitizer also catches some libhdf5 faults before they segfault (an out-of-bounds
//    memcpy inside libhdf5): a report whose first frame past the interceptors is in libhdf5
//    ends the child by SIGSEGV too, as that read does in the program.
//    Any other sanitizer report in the child (our reader's code, undefined behaviour) must not
//    be swallowed: the child's sanitizer death callback marks a flag in memory shared with the
//    parent and exits, and the parent traps, so libFuzzer saves the input. The child's report
//    is printed on stderr before it exits.
// Properties: reading gives an Archive or an ArchiveError, nothing else; a read archive has
// one options list per algorithm and one record per algorithm in every result; the inspect
// summary of it is printed without error.
#include <pthread.h>
#include <sanitizer/allocator_interface.h>
#include <sanitizer/asan_interface.h>
#include <sanitizer/common_interface_defs.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <span>
#include <sstream>
#include <string_view>

#include "gjklab/experiment/archive.hpp"
#include "gjklab/experiment/summary.hpp"
#include "support.hpp"

namespace {

using gjklab::fuzz::violated;
namespace experiment = gjklab::experiment;

/// A flag shared with the forked children: set when a child's sanitizer reported an error in
/// gjklab's code.
std::atomic<int>* child_reported = nullptr;

/// Whether the child's sanitizer report is about libhdf5 itself: its first frame outside the
/// sanitizer's interceptors and the C library is in libhdf5. Set by the report callback.
bool report_in_libhdf5 = false;

bool is_interceptor_frame(std::string_view frame) {
  return frame.find("__interceptor_") != std::string_view::npos ||
         frame.find("__asan_") != std::string_view::npos ||
         frame.find("libc.so") != std::string_view::npos ||
         frame.find("string/../sysdeps") != std::string_view::npos;
}

void child_sanitizer_report(const char* report) {
  std::string_view text(report);
  for (std::size_t at = text.find("    #"); at != std::string_view::npos;
       at = text.find("    #", at + 1)) {
    const std::string_view frame = text.substr(at, text.find('\n', at) - at);
    if (is_interceptor_frame(frame)) continue;
    report_in_libhdf5 = frame.find("libhdf5") != std::string_view::npos;
    return;
  }
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

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  void* shared = ::mmap(nullptr, sizeof(std::atomic<int>), PROT_READ | PROT_WRITE,
                        MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED) violated("cannot map the flag shared with the children");
  child_reported = new (shared) std::atomic<int>(0);
  if (::pthread_atfork(nullptr, nullptr, in_forked_child) != 0)
    violated("cannot register the fork handler");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = gjklab::fuzz::write_scratch_file("run.h5", std::span(data, size));
  // The fork copies the page tables of every page this process holds, and most of them are
  // ASan's quarantine of freed blocks (up to 256 MB): 340 MB resident without this, 80 MB with
  // it, and half the CPU time per input (measured on 200 inputs: 6.6 s, 3.3 s). A use after
  // free within one input is still caught: the quarantine fills again during the input.
  __sanitizer_purge_allocator();
  try {
    check_archive(experiment::read_archive_isolated(path));
  } catch (const experiment::ArchiveError&) {
  }
  if (child_reported->load() != 0) violated("a sanitizer report in the archive-reading child");
  return 0;
}
