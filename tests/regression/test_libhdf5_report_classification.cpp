// The archive fuzz target's rule for a sanitizer report (fuzz/libhdf5_report.hpp): a report
// whose first frame outside the sanitizer runtime and the C library is in libhdf5 is libhdf5's
// own bug, contained by read_archive_isolated; any other is a finding. The two reports under
// regression/data/fuzz/ stopped the campaign, classified as gjklab's, before the rule skipped
// the runtime's frames by their lack of a source line (strdup and MemcmpInterceptorCommon were
// not on the list of interceptor names it had).
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <string>

#include "../../fuzz/libhdf5_report.hpp"

using gjklab::fuzz::report_is_in_libhdf5;

namespace {

std::string report(const char* name) {
  std::ifstream in(std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/" + name);
  REQUIRE(in);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The report without its frames from..to (inclusive), renumbering nothing: the classifier
/// reads the frames in order, not their numbers.
std::string without_frames(const std::string& text, int from, int to) {
  std::istringstream in(text);
  std::ostringstream out;
  for (std::string line; std::getline(in, line);) {
    bool drop = false;
    for (int n = from; n <= to; ++n)
      drop = drop || line.rfind("    #" + std::to_string(n) + " ", 0) == 0;
    if (!drop) out << line << '\n';
  }
  return out.str();
}

}  // namespace

TEST_CASE("libhdf5 report: strdup over-read in H5MM_xstrdup is libhdf5's", "[regression]") {
  // The first read of archive-crash-31a99bd…: libhdf5 duplicates an unterminated name.
  CHECK(report_is_in_libhdf5(report("libhdf5_report_strdup_overread_in_H5MM_xstrdup.txt")));
}

TEST_CASE("libhdf5 report: memcmp over-read in H5T_cmp is libhdf5's", "[regression]") {
  // The second read of archive-crash-42f64fa… in one process: H5T_cmp compares an enum name
  // past its end, under the runtime's helper MemcmpInterceptorCommon and __interceptor_memcmp.
  CHECK(report_is_in_libhdf5(report("libhdf5_report_memcmp_overread_in_H5T_cmp.txt")));
}

TEST_CASE("libhdf5 report: the same over-read from gjklab's own code is a finding",
          "[regression]") {
  // Without libhdf5's frames #2-#7, gjklab's read_all (a source line) calls memcmp itself.
  const auto text = report("libhdf5_report_memcmp_overread_in_H5T_cmp.txt");
  REQUIRE(text.find("H5T_cmp") != std::string::npos);
  const auto own = without_frames(text, 2, 7);
  REQUIRE(own.find("libhdf5") == std::string::npos);
  REQUIRE(own.find("read_all") != std::string::npos);
  CHECK_FALSE(report_is_in_libhdf5(own));
  // gjklab's frame above libhdf5 (a callback libhdf5 called) is a finding too.
  const auto callback =
      "    #0 0x1 in gjklab::experiment::h5::read_all() /src/gjklab/src/x.cpp:1:1\n" +
      without_frames(text, 0, 1);
  CHECK_FALSE(report_is_in_libhdf5(callback));
}

TEST_CASE("libhdf5 report: unsymbolised frames of the executable are not skipped", "[regression]") {
  // With symbolize=0 (the worker) gjklab's frames and the runtime's look alike: the text rule
  // leaves them to the worker's rule on addresses (fuzz/archive_worker.cpp).
  const std::string text =
      "    #0 0x55bac69d30a5  (/src/gjklab/build/fuzz/fuzz/fuzz_archive_worker+0x1140a5)\n"
      "    #1 0x7f7ecd1842ad  (/lib/x86_64-linux-gnu/libhdf5_serial.so.103+0x1842ad)\n";
  CHECK_FALSE(report_is_in_libhdf5(text));
  // libhdf5's own frame first, or under the C library's, is libhdf5's in either form.
  CHECK(report_is_in_libhdf5("    #0 0x7f7ecd1842ad  (/lib/x86_64-linux-gnu/libc.so.6+0x1842ad)\n" +
                             text.substr(text.find("    #1"))));
}
