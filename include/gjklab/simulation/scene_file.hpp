// Scene files (TOML) for `gjklab simulate`: the world's settings, static containers and body
// groups with their placement. Errors are experiment::ConfigError "FILE:LINE: key 'K': ..."
// like the experiment files'. The format is documented in docs/scenes.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gjklab/scene/world.hpp"

namespace gjklab::simulation {

/// A scene ready to simulate: the world with every body placed, and how to record it.
struct SceneSetup {
  std::string name;
  std::uint64_t seed = 1;
  std::int64_t frames = 0;
  /// Body poses are archived every `pose_every` frames, contacts every `contacts_every`.
  std::int64_t pose_every = 10;
  std::int64_t contacts_every = 10;
  /// Time all three broad phases on every frame's boxes (and check they agree).
  bool compare_broad_phases = false;
  /// Record the narrow-phase queries of every k-th frame (0: none) in queries/, with the
  /// shapes' vertices in shapes/: the input of the experiments' `stream` family.
  std::int64_t queries_every = 0;
  /// [oracle] audit_every: the exact answers of the pairs queried in every k-th frame
  /// (0: none); depth: also their exact penetration depths.
  std::int64_t audit_every = 0;
  bool audit_depth = false;
  std::unique_ptr<scene::World> world;
  /// Per body: the name of its shape kind ("box", "cone", …, "funnel", "hull").
  std::vector<std::string> shape_names;
  /// The scene's length scale: the median dynamic body's size (hull diagonal).
  double body_size = 1;
  std::string text;  ///< the file as read, for the archive
  /// Deprecated spellings the file used ("FILE:LINE: key 'K': ..."), for the command to print;
  /// the scene is built as the spelling always meant.
  std::vector<std::string> warnings;
};

/// Reads and builds a scene. Throws experiment::ConfigError (also for an unreadable file).
SceneSetup load_scene(const std::string& path);
/// The same from text; `source` names it in errors.
SceneSetup parse_scene(const std::string& text, const std::string& source);

}  // namespace gjklab::simulation
