// The HDF5 results archive: one file per run, columnar 1-D datasets (one per field), chunked
// and compressed, enums as HDF5 enum types. Schema: results/README.md.
//
// A run writes to "<output>.tmp" in the same folder and renames it to the final name only when
// complete, so a file with the final name is always whole. The root attribute `complete` is
// written last, by finish(); a file without it (or with 0) holds an incomplete run.
//
// HDF5's serial build is not thread-safe: one writer, and every read_archive call, must be used
// from one thread at a time (the driver collects results from its workers and writes them from
// one thread). Both turn off HDF5's automatic error printing for the process; every failing
// HDF5 call becomes an ArchiveError naming the file and the dataset or attribute.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gjklab/experiment/cases/records.hpp"

namespace gjklab::experiment {

inline constexpr int kArchiveSchemaVersion = 2;

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
  std::string start_time;                                       ///< ISO 8601, UTC
  std::vector<std::pair<std::string, std::string>> provenance;  ///< build_provenance() etc.
  std::vector<std::string> family_names;                        ///< index = CaseRecord::family
  std::vector<std::string> algorithm_names;
  /// Options of each algorithm (same order as algorithm_names), as (key, value) strings.
  std::vector<std::vector<std::pair<std::string, std::string>>> algorithm_options;
  bool oracle = true;
  double touching_band = 1e-10;
  /// Which queries' traces the archive holds (in /traces; stored by name).
  TraceMode trace_mode = TraceMode::none;
  /// The cases are non-convex pairs (nonconvex families): the archive has a /meshes group, whose
  /// presence the reader takes this from (no root attribute).
  bool meshes = false;
};

/// Writes one archive. Not thread-safe (see above): use it from one thread.
/// The copy of an interrupted run's temporary archive taken at a checkpoint ("FILE.tmp" →
/// "FILE.tmp.checkpoint"), which `--resume` reads when a kill left the temporary file
/// unreadable.
inline std::filesystem::path snapshot_path(const std::filesystem::path& temporary) {
  std::filesystem::path p = temporary;
  p += ".checkpoint";
  return p;
}

class ArchiveWriter {
 public:
  /// Checks before any work, then creates "<final_path>.tmp" (replacing a stale one) and writes
  /// the header as root attributes and the empty columns. Throws ArchiveError, naming the path,
  /// if final_path exists and !overwrite ("FILE exists (use --force to overwrite)"), if its
  /// folder is missing or not writable, or if the header cannot be stored (an algorithm name
  /// that is not a valid group name, a provenance key that is a root attribute's name,
  /// duplicate names); nothing is left behind then.
  ArchiveWriter(const std::filesystem::path& final_path, const ArchiveHeader& header,
                bool overwrite);
  /// An unfinished writer closes the temporary file and leaves it under its temporary name
  /// (no end_time, no complete flag); read_archive still reads it.
  ~ArchiveWriter();
  ArchiveWriter(const ArchiveWriter&) = delete;
  ArchiveWriter& operator=(const ArchiveWriter&) = delete;

  /// Appends results (in case-id order) to every column, extending each by results.size().
  /// Each result must hold one AlgorithmRecord per header algorithm, and an ExactRecord exactly
  /// when the header's oracle is on; a batch that does not is refused whole, before anything
  /// is written. Geometry, where present, goes to /geometry.
  void append(std::span<const CaseResult> results);
  /// Writes end_time, flushes the file, writes `complete` (last), closes the file and, when
  /// complete, renames it to the final path (replacing an existing file only if overwrite was
  /// asked). An incomplete run keeps the temporary name with complete = 0. Call it once; after
  /// a failed append, finish(…, true) records complete = 0 and throws.
  void finish(const std::string& end_time, bool complete);

  const std::filesystem::path& temporary_path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A whole archive read back into memory.
struct Archive {
  int schema_version = 0;
  ArchiveHeader header;             ///< algorithm_options has one entry per algorithm
  std::string end_time;             ///< empty when the run stopped before finish()
  bool complete = false;            ///< false when the flag is 0 or absent
  std::vector<CaseResult> results;  ///< geometry filled for the cases that kept it
};

/// One dataset of an archive group, or one root attribute, as results/README.md documents it.
struct ArchiveColumn {
  std::string name;
  std::string type;     ///< "float64", "enum `Termination`", "float64 (rows × 3)", ...
  std::string meaning;  ///< Markdown: units and frame first
};
/// The datasets of the group "cases", "exact", "algorithms" (each algorithm's group),
/// "geometry" or "traces" (each algorithm's group) in creation order; empty for another name.
/// Read from the schema tables the writer and the reader use.
std::vector<ArchiveColumn> archive_columns(std::string_view group);
/// The root attributes with a fixed meaning, in creation order ("checkpoint_*" stands for
/// the checkpoint counts); every other root attribute is a provenance pair.
std::vector<ArchiveColumn> archive_root_attributes();

/// The Markdown table results/README.md shows for a group of archive_columns, for the root
/// attributes ("root"), or the list of every archive enum's values ("enums"); "scene/GROUP" for
/// a group of the scene archive (docs/scenes.md, scene_archive.hpp). Throws
/// std::invalid_argument for another name.
std::string archive_schema_table(std::string_view group);
/// `document` with every table between the lines "<!-- schema table: GROUP -->" and
/// "<!-- end schema table -->" replaced by archive_schema_table(GROUP): how results/README.md's
/// tables are made from the schema (`gjklab schema --update FILE`). Throws
/// std::invalid_argument for an unknown group or a table without its end line.
std::string with_schema_tables(std::string_view document);

/// Reads an archive written by ArchiveWriter, complete or not (a "<output>.tmp" file too).
/// Throws ArchiveError naming the file and the missing or malformed group, dataset or
/// attribute (or an unsupported schema_version).
Archive read_archive(const std::filesystem::path& path);

/// read_archive for files that may be corrupt (the command line's inspect, replay, resume):
/// the file is first read in a child process, because some corrupt files make libhdf5 itself
/// crash (a segfault in its global-heap reader, an upstream bug). A child that dies by a
/// signal becomes an ArchiveError saying the file is corrupt, instead of taking the program
/// down. Call it before starting threads (it forks).
Archive read_archive_isolated(const std::filesystem::path& path);

}  // namespace gjklab::experiment
