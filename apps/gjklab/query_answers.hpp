// `gjklab query`'s answers for one case: one JSON line per algorithm asked, in the fields of
// experiment::answer_fields (convex shapes) or experiment::mesh_answer_fields (a mesh side).
#pragma once

#include <string>
#include <vector>

#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/meshes/mesh_query.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

namespace gjklab::cli {

/// What every case is asked.
struct QueryAsked {
  std::vector<const experiment::AlgorithmInfo*> algorithms;
  /// Peers that answer for two meshes only (fcl-bvh): asked of the cases with a mesh side.
  std::vector<const experiment::MeshPeerInfo*> mesh_peers;
  /// The algorithms were named (not the default set): each answers or says why not.
  bool named = false;
  /// The pieces the convex algorithms see of a mesh side.
  const experiment::DecompositionInfo* decomposition = nullptr;
  experiment::DecompositionOptions decomposition_options;
  experiment::AlgorithmOptions options;
};

/// One JSON line per algorithm asked (an error line for one that cannot answer the case).
std::vector<std::string> answer_lines(const experiment::PointCase& c, const QueryAsked& asked);

/// The JSON line of a problem with a case (and the algorithm, when one is at fault).
std::string error_line(const std::string& id, const std::string& problem,
                       const experiment::AlgorithmInfo* algorithm = nullptr);

}  // namespace gjklab::cli
