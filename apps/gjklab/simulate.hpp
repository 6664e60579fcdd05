// `gjklab simulate SCENE.toml`: steps a scene (simulation/scene_run.hpp) and writes its archive:
// frames/ one row per frame, bodies/ poses every k frames, contacts/ every k frames. A run
// stopped by SIGINT/SIGTERM (or --stop-after) or killed leaves FILE.h5.tmp, a checkpoint with
// the world's state/, which --resume continues into the archive an uninterrupted run writes.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct SimulateArgs {
  std::string scene;
  std::string output;       ///< default: results/<scene name>.h5
  std::int64_t frames = 0;  ///< 0: the file's
  bool force = false;
  std::string resume;  ///< FILE.h5.tmp (or FILE.h5) of an interrupted run
  /// Frames between checkpoints (FILE.h5.tmp rewritten with the world's state; 0: none).
  std::int64_t checkpoint = 500;
  std::int64_t stop_after = 0;  ///< stop after this many frames (0: run to the end)
  int threads = 0;              ///< narrow-phase threads (0: the file's [narrow_phase] threads)
};

CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args);

/// 0 on success; 1 for a bad scene file, an existing archive without --force, or a failed
/// write (the message names the file, line and key, or the archive).
int run_simulate_command(const SimulateArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
