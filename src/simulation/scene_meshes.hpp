// Mesh files in scene files (private to src/simulation): the files a `mesh` group or static
// names, and the compound bodies of the closed meshes among them (`decomposition` set): each
// file read and validated as a closed mesh, decomposed into convex pieces by the experiment
// layer's registry, and handed to the scene layer as plain pieces. Every problem is a
// ConfigError naming the key and the mesh file.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "gjklab/geometry/types.hpp"
#include "gjklab/scene/compound.hpp"
#include "scene_toml.hpp"

namespace gjklab::simulation {

/// The files `path` names (one .off/.obj/.ply/.stl file or a folder of them, in name order),
/// relative to the scene file's folder; a ConfigError at `path` when there are none.
std::vector<std::filesystem::path> mesh_paths(const SceneTable& t);

/// The compound of each file `path` names (body i takes file i mod their number), its
/// coordinates multiplied by `scale` (per axis, > 0), decomposed by `decomposition` with the
/// options of the `decomposition_options` table.
std::vector<std::shared_ptr<const scene::CompoundShape>> mesh_compounds(const SceneTable& t,
                                                                        const Vec3& scale);

}  // namespace gjklab::simulation
