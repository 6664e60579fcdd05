// Between a world and its scene archive (private to src/simulation): what the archive holds
// beyond the recording (settings, bodies, shapes, the world's state) and the way back.
#pragma once

#include <cstdint>

#include "gjklab/simulation/scene_run.hpp"

namespace gjklab::simulation {

/// Fills run.archive's header, bodies, shapes and (for a checkpoint, !complete) state from the
/// run's world and progress.
void fill_archive(SceneRun& run, bool finite, bool complete);

/// Restores a checkpoint's state/ into a world built from the same scene; returns the run's
/// target frame count. Throws experiment::ArchiveError naming `file` when it does not match.
std::int64_t restore_state(const experiment::SceneState& state, scene::World& w,
                           const std::string& file);

}  // namespace gjklab::simulation
