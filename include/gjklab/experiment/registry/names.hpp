// Everything the program selects by name, as one JSON document (`gjklab names --json`): the
// algorithms with their group, answers and options (type, default, accepted values, meaning),
// the shapes, contacts and placements an experiment's families name, the hunt objectives and
// the benchmark suites. Tools (figures, studies) read it instead of keeping lists of their own,
// so a new algorithm or shape reaches them with its registry line.
#pragma once

#include <nlohmann/json_fwd.hpp>

namespace gjklab::experiment {

/// The document, built from the registries and name tables, in their order:
///   {"algorithms": [{"name", "group", "kind", "answers": {"boolean", "distance", "depth"},
///                    "description", "swept", "traceable", "precisions", "warm_start",
///                    "options": [{"key", "type", "default", "accepts", "choices"?,
///                                 "meaning", "settable"}]}],
///    "shapes": [{"name", "description"}], "contacts": [...], "placements": [...],
///    "hunt_objectives": [{"name", "meaning"}], "bench_suites": [...],
///    "decompositions": [{"name", "description", "options": [{"key", "meaning"}]}],
///    "mesh_peers": [{"name", "description"}]}
/// Keys keep this order (ordered_json), so the text reads as documented.
nlohmann::ordered_json names_document();

}  // namespace gjklab::experiment
