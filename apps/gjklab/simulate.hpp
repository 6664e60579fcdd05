// `gjklab simulate SCENE.toml`: steps a scene (scene_file.hpp) and writes its HDF5 archive:
// frames/ one row per frame, bodies/ poses every k frames, contacts/ every k frames.
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
};

CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args);

/// 0 on success; 1 for a bad scene file, an existing archive without --force, or a failed
/// write (the message names the file, line and key, or the archive).
int run_simulate_command(const SimulateArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
