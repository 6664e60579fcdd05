// The HDF5 results archive: one file per run, columnar 1-D datasets (one per field), chunked
// and compressed, enums as HDF5 enum types. Schema: results/README.md.
//
// A run writes to "<output>.tmp" in the same folder and renames it to the final name only when
// complete, so a file with the final name is always whole.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gjklab/experiment/records.hpp"

namespace gjklab::experiment {

inline constexpr int kArchiveSchemaVersion = 1;

class ArchiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Everything about a run that is known before its first case: the root attributes.
struct ArchiveHeader {
  std::string experiment_name;
  std::string experiment_text;  ///< the full experiment file
  std::uint64_t seed = 0;
  std::uint64_t cases_planned = 0;
  std::string start_time;       ///< ISO 8601, UTC
  std::vector<std::pair<std::string, std::string>> provenance;  ///< build_provenance() etc.
  std::vector<std::string> family_names;  ///< index = CaseRecord::family
  std::vector<std::string> algorithm_names;
  /// Options of each algorithm (same order as algorithm_names), as (key, value) strings.
  std::vector<std::vector<std::pair<std::string, std::string>>> algorithm_options;
  bool oracle = true;
  double touching_band = 1e-10;
};

class ArchiveWriter {
 public:
  /// Creates the temporary file next to final_path. Throws ArchiveError, naming the path,
  /// if final_path exists and !overwrite, or if the folder is not writable.
  ArchiveWriter(const std::filesystem::path& final_path, const ArchiveHeader& header,
                bool overwrite);
  ~ArchiveWriter();  ///< an unfinished writer closes the temporary file and leaves it
  ArchiveWriter(const ArchiveWriter&) = delete;
  ArchiveWriter& operator=(const ArchiveWriter&) = delete;

  /// Appends results (in case-id order) to every column.
  void append(std::span<const CaseResult> results);
  /// Writes the end time and the completion flag (last), closes the file and, when complete,
  /// renames it to the final path. An incomplete run keeps the temporary name.
  void finish(const std::string& end_time, bool complete);

  const std::filesystem::path& temporary_path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A whole archive read back into memory.
struct Archive {
  int schema_version = 0;
  ArchiveHeader header;
  std::string end_time;
  bool complete = false;
  std::vector<CaseResult> results;  ///< geometry filled for the cases that kept it
};

/// Reads an archive written by ArchiveWriter. Throws ArchiveError naming the file and the
/// missing or malformed dataset.
Archive read_archive(const std::filesystem::path& path);

}  // namespace gjklab::experiment
