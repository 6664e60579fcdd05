// The [[family]] and [placement] tables of experiment files (private to src/experiment/config).
#pragma once

#include <string>

#include "experiment/config/toml_section.hpp"
#include "gjklab/experiment/config/config.hpp"

namespace gjklab::experiment {

/// [placement] (or a family's placement keys) over `base`.
PlacementSpec read_placement(const Section& s, PlacementSpec base);
/// One [[family]] table; paths in it are relative to `experiment_file`'s folder.
FamilySpec read_family(const Section& s, const PlacementSpec& placement,
                       const std::string& experiment_file);

}  // namespace gjklab::experiment
