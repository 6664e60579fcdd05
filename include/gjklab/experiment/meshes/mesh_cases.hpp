// One case of a nonconvex family, evaluated: the exact truth of the two solids
// (exact::mesh_truth), then every algorithm of the experiment on them: a convex algorithm on the
// pieces of its decomposition (run_on_pieces), a mesh peer on the meshes. Each side is
// decomposed once per decomposition (and options) the algorithms ask for; the pieces of a kept
// case go into its geometry.
//
// Judging is the convex cases' (judging.hpp) with the solids' truth: the boolean against the
// solids' intersect, the distance error against their exact distance. The truth has no depth, so
// an intersecting pair is never in the touching band: a barely overlapping pair answered
// "apart" counts as a wrong boolean.
#pragma once

#include <string>

#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/cases/records.hpp"
#include "gjklab/experiment/config/config.hpp"

namespace gjklab::experiment {

/// The case's result (its meshes are generated.mesh_a and mesh_b). Throws std::runtime_error
/// naming the case, the side and the decomposition when a decomposition fails.
CaseResult evaluate_mesh_case(const ExperimentConfig& config, GeneratedCase generated);

/// The solids' truth as an exact answer and its archive records (contact class with the
/// absolute band `band`, length units; no depth).
struct MeshTruthRecords {
  exact::OracleAnswer answer;  ///< intersect, distance, distance_squared; method mesh_truth
  ExactRecord exact;
  MeshExactRecord mesh;
};
MeshTruthRecords mesh_truth_records(const exact::MeshTruth& truth, double band);

/// One algorithm of the experiment on two meshes: a convex algorithm over the pieces of its
/// decomposition (both sides decomposed here; `source` names the pair in errors), a mesh peer
/// on the meshes. Throws std::runtime_error when a decomposition fails.
Outcome run_mesh_algorithm(const AlgorithmSpec& spec, const TriangleMesh& a, const TriangleMesh& b,
                           const std::string& source);

}  // namespace gjklab::experiment
