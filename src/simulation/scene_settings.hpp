// A scene file's [physics], [broad_phase] and [narrow_phase] tables as the world's settings
// (private to src/simulation): the narrow phase is any registry algorithm that answers a
// distance, the GJK distance variants through their warm-startable query.
#pragma once

#include "scene_toml.hpp"

#include "gjklab/scene/world.hpp"

namespace gjklab::simulation {

/// Reads the settings tables of the scene file `root` into `s`. Throws ConfigError naming the
/// file, line and key of the first bad value.
void read_settings(const SceneTable& root, scene::WorldSettings& s);

}  // namespace gjklab::simulation
