// What the archive target's reading processes share (fuzz/archive.cpp, fuzz/archive_worker.cpp):
// whether a sanitizer report is about libhdf5 itself.
#pragma once

#include <string_view>

namespace gjklab::fuzz {

// A symbolised report's frames read "    #3 0xPC in NAME FILE:LINE:COL" for code compiled with
// debug information (gjklab's, and the headers it instantiates) and "    #3 0xPC in NAME
// (MODULE+0xOFFSET)" or "    #3 0xPC  (MODULE+0xOFFSET)" for code without it.

/// The module a frame without debug information names ("" for a frame with it).
inline std::string_view frame_module(std::string_view frame) {
  const std::size_t offset = frame.find("+0x");
  if (offset == std::string_view::npos) return {};
  const std::size_t open = frame.rfind('(', offset);
  if (open == std::string_view::npos) return {};
  return frame.substr(open + 1, offset - open - 1);
}

inline bool is_c_library_frame(std::string_view frame) {
  return frame_module(frame).find("libc.so") != std::string_view::npos ||
         frame.find("string/../sysdeps") != std::string_view::npos;
}

/// The sanitizer runtime's frames: its entry points (__interceptor_memcmp, strdup, malloc,
/// __asan_memcpy) and their helpers (MemcmpInterceptorCommon). The runtime is linked into the
/// executable without debug information, while gjklab's code there has it, so a frame of the
/// executable (a module that is no shared library) without a source line is the runtime's.
/// Only in a symbolised report: an unsymbolised frame (no NAME) may be gjklab's code.
inline bool is_runtime_frame(std::string_view frame) {
  if (frame.find(" in ") == std::string_view::npos) return false;
  for (const std::string_view prefix : {"__interceptor_", "__asan_", "__sanitizer_"})
    if (frame.find(prefix) != std::string_view::npos) return true;
  const std::string_view module = frame_module(frame);
  return !module.empty() && module.find(".so") == std::string_view::npos;
}

/// Whether the report's first frame outside the sanitizer runtime and the C library is in
/// libhdf5: an out-of-bounds read inside it (caught by the runtime's memcpy, memcmp or strdup
/// check before it segfaults), or an allocation beyond the limit asked by a corrupt size.
inline bool report_is_in_libhdf5(std::string_view report) {
  for (std::size_t at = report.find("    #"); at != std::string_view::npos;
       at = report.find("    #", at + 1)) {
    const std::string_view frame = report.substr(at, report.find('\n', at) - at);
    if (is_c_library_frame(frame) || is_runtime_frame(frame)) continue;
    return frame.find("libhdf5") != std::string_view::npos;
  }
  return false;
}

}  // namespace gjklab::fuzz
