// What an experiment of nonconvex families reads beyond a convex one (private to
// src/experiment/config): the decompositions its convex algorithms run on, the mesh peers it may
// list, and what such an experiment cannot take.
#pragma once

#include <vector>

#include "experiment/config/toml_section.hpp"
#include "gjklab/experiment/config/config.hpp"

namespace gjklab::experiment {

/// The keys a convex algorithm's table adds in a nonconvex experiment.
inline constexpr std::string_view kDecompositionKeys[] = {"decomposition", "decomposition_options"};

/// A mesh peer's [[algorithm]] table (`name`, optional `label`); `nonconvex`: whether the
/// experiment's families are. Fails for a mesh peer in a convex experiment.
AlgorithmSpec read_mesh_peer(const Section& s, const MeshPeerInfo& peer, bool nonconvex);

/// A convex algorithm's table read into `spec`, once per decomposition it lists
/// (`decomposition = "exact"` or a list; `hull` when absent), each labelled
/// "name@decomposition=NAME" when the table lists any; with their `decomposition_options`.
/// In a convex experiment the keys are refused and `spec` is returned alone.
std::vector<AlgorithmSpec> with_decompositions(const Section& s, AlgorithmSpec spec,
                                               bool nonconvex);

/// Refuses what a nonconvex experiment cannot take: convex families beside nonconvex ones, a
/// geometry sweep, traces, and the [oracle] keys of the convex oracle (depth, certificates,
/// verify, hull_vertices).
void check_nonconvex_experiment(const Section& top, const ExperimentConfig& config);

}  // namespace gjklab::experiment
