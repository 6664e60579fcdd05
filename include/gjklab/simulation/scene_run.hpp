// A scene run: steps a scene (scene_file.hpp) frame after frame, records it, writes checkpoints
// (FILE.h5.tmp, with the world's state/) and finally the scene archive (FILE.h5). A run stopped
// or killed continues from its last checkpoint into the archive an uninterrupted run writes.
#pragma once

#include <atomic>
#include <cstdint>
#include <iosfwd>
#include <string>

#include "gjklab/experiment/archive/scene_archive.hpp"
#include "gjklab/simulation/scene_file.hpp"

namespace gjklab::simulation {

/// Where a run stands and when it writes checkpoints.
struct RunProgress {
  std::int64_t done = 0;        ///< frames simulated
  std::int64_t target = 0;      ///< frames the run is to reach
  std::int64_t checkpoint = 0;  ///< frames between checkpoints (0: none)
  std::int64_t stop_after = 0;  ///< stop after this many frames of this invocation (0: never)
};

enum class RunOutcome { finished, stopped, not_finite };

struct SceneRun {
  SceneSetup setup;
  std::string scene_path;    ///< the scene file as given (archived)
  std::string archive_path;  ///< FILE.h5; checkpoints go to FILE.h5.tmp
  /// The recording so far (frames/, bodies/ poses, contacts/, audit/, queries/); the rest of
  /// the archive is filled from the world when it is written.
  experiment::SceneArchive archive;
  RunProgress progress;
};

/// FILE.h5.tmp, the checkpoint of FILE.h5.
std::string checkpoint_path(const std::string& archive_path);
/// The archive a checkpoint belongs to: FILE.h5 for FILE.h5.tmp (or FILE.h5 itself).
std::string archive_path_of(const std::string& given);

/// A new run of `setup` to `target` frames into `archive_path`.
SceneRun new_scene_run(SceneSetup setup, const std::string& scene_path,
                       const std::string& archive_path, std::int64_t target);
/// The run an interrupted one left in `given` (FILE.h5.tmp or FILE.h5): its scene as it read
/// it, the recording and the world's state. Throws experiment::ArchiveError (no checkpoint, not
/// a scene archive, or a state that does not match the scene) or ConfigError.
SceneRun resume_scene_run(const std::string& given);

/// Steps from progress.done to progress.target, writing a checkpoint every progress.checkpoint
/// frames; stops early when the state stops being finite, when *stop becomes true (after the
/// current frame) or after progress.stop_after frames. Then writes the archive (finished or
/// not finite) or the checkpoint (stopped). Throws experiment::ArchiveError.
RunOutcome run_scene(SceneRun& run, const std::atomic<bool>* stop);

/// The end of a finished (or not finite) run: bodies, frames, penetration, iterations, audit.
void print_scene_summary(const SceneRun& run, std::ostream& out);

}  // namespace gjklab::simulation
