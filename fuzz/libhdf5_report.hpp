// What the archive target's reading processes share (fuzz/archive.cpp, fuzz/archive_worker.cpp):
// whether a sanitizer report is about libhdf5 itself.
#pragma once

#include <string_view>

namespace gjklab::fuzz {

inline bool is_interceptor_frame(std::string_view frame) {
  // Symbolised without the prefix in a program not linked with libFuzzer (the worker).
  for (const std::string_view name : {" in malloc ", " in calloc ", " in realloc ", " in free ",
                                      " in memcpy ", " in memmove ", " in memset "})
    if (frame.find(name) != std::string_view::npos) return true;
  return frame.find("__interceptor_") != std::string_view::npos ||
         frame.find("__asan_") != std::string_view::npos ||
         frame.find("libc.so") != std::string_view::npos ||
         frame.find("string/../sysdeps") != std::string_view::npos;
}

/// Whether the report's first frame outside the sanitizer's interceptors and the C library is in
/// libhdf5 (an out-of-bounds read inside it, caught by the sanitizer's memcpy check before it
/// segfaults, or an allocation beyond the limit asked by a corrupt size).
inline bool report_is_in_libhdf5(std::string_view report) {
  for (std::size_t at = report.find("    #"); at != std::string_view::npos;
       at = report.find("    #", at + 1)) {
    const std::string_view frame = report.substr(at, report.find('\n', at) - at);
    if (is_interceptor_frame(frame)) continue;
    return frame.find("libhdf5") != std::string_view::npos;
  }
  return false;
}

}  // namespace gjklab::fuzz
