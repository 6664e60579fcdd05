// What the fuzz targets share: a private scratch folder for the files the readers take by
// path, and the one way a target reports a violated property (a trap, which libFuzzer records
// as a crash with the input that caused it).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>
#include <system_error>

namespace gjklab::fuzz {

/// Prints the violated property and stops: libFuzzer saves the input as crash-<hash>.
[[noreturn]] inline void violated(std::string_view what) {
  std::fprintf(stderr, "fuzz property violated: %.*s\n", static_cast<int>(what.size()),
               what.data());
  std::fflush(stderr);
  __builtin_trap();
}

/// A folder of this process's own under the system temporary folder (so that parallel fuzzing
/// jobs never share files), made on first use and removed when the process exits normally.
inline const std::filesystem::path& scratch_folder() {
  static const std::filesystem::path folder = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "gjklab-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) violated("cannot create the scratch folder");
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_folder(), ec);
    });
    return std::filesystem::path(pattern);
  }();
  return folder;
}

/// Writes bytes to a file of the scratch folder (replacing it); returns its path.
inline std::filesystem::path write_scratch_file(std::string_view name,
                                                std::span<const std::uint8_t> bytes) {
  const std::filesystem::path path = scratch_folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) violated("cannot write a scratch file");
  return path;
}

inline std::filesystem::path write_scratch_file(std::string_view name, std::string_view text) {
  return write_scratch_file(
      name, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

/// Empties the scratch folder, so that no file from an earlier input changes what the next
/// one reads (a base experiment, a cases file).
inline void clear_scratch_folder() {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(scratch_folder(), ec))
    std::filesystem::remove_all(entry.path(), ec);
}

}  // namespace gjklab::fuzz
