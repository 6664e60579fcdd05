// The `stream` family's input: the narrow-phase queries a scene run recorded (`gjklab simulate`
// with `[scene] queries_every = k`: the archive's queries/ and shapes/ groups), as pairs of
// world-frame clouds, bit for bit the ones the scene's GJK queried.
#pragma once

#include <filesystem>
#include <vector>

#include "gjklab/experiment/config/config.hpp"

namespace gjklab::experiment {

/// One pair per recorded query, in the archive's order, with ids "fF:A-B" (frame F, bodies A
/// and B); A's cloud is its shape's body-frame vertices moved by the recorded pose
/// (rotation·v + translation, as Polytope::transformed computes it). Throws InputError (file,
/// line 0, problem) for a file that is not a scene archive or has no recorded queries.
std::vector<StoredPair> read_scene_stream(const std::filesystem::path& archive);

}  // namespace gjklab::experiment
