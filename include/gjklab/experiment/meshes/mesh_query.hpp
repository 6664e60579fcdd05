// One algorithm's answer for a pair of closed meshes, in the fields `gjklab query` prints and
// Python returns: `exact` answers the solids themselves (exact::mesh_truth); every other
// algorithm answers the pieces of the chosen decomposition (run_on_pieces), and says which
// decomposition, how many pieces and how many pairs of them it ran.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/registry/answer_fields.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"

namespace gjklab::experiment {

/// One side of a non-convex pair: its closed mesh and, once a convex algorithm needs them, its
/// decomposition's pieces.
struct MeshSide {
  TriangleMesh mesh;
  std::optional<Decomposition> decomposition;
  std::vector<Polytope> pieces;
};

/// Decomposes the side unless it already is; `source` names the mesh in errors.
void decompose_side(MeshSide& side, const DecompositionInfo& decomposition, std::string_view source,
                    const DecompositionOptions& options);

/// The answer fields of `algorithm` for the pair. For `exact`: algorithm, intersect, distance,
/// the exact squared distance (distance2_num, distance2_den), method "mesh-truth", contact, the
/// deciding faces (face_a, face_b, when triangles decide) and the exact evaluations made. For
/// the others: answer_fields of the pieces' answer, then decomposition, pieces_a, pieces_b,
/// piece_pairs, piece_pairs_tested and the deciding pieces; both sides must be decomposed.
AnswerFields mesh_answer_fields(const AlgorithmInfo& algorithm, const MeshSide& a,
                                const MeshSide& b, const AlgorithmOptions& options);

/// A mesh peer's answer: intersect, distance and witnesses where it reports them, and the
/// deciding triangles (−1 when none).
struct MeshPeerAnswer {
  Outcome outcome;
  std::int64_t face_a = -1, face_b = -1;
};

/// A peer that answers for two meshes themselves, not for convex pieces: FCL's BVHModel
/// (`fcl-bvh`, when FCL was built), what robotics code queries non-convex meshes with.
struct MeshPeerInfo {
  std::string_view name;
  std::string_view description;
  MeshPeerAnswer (*run)(const TriangleMesh& a, const TriangleMesh& b);
};

/// A mesh peer's answer fields: algorithm, intersect, distance, witnesses where there are, and
/// the deciding faces.
AnswerFields mesh_peer_fields(const MeshPeerInfo& peer, const MeshPeerAnswer& answer);

/// Every mesh peer built into this binary.
std::span<const MeshPeerInfo> mesh_peers();
/// The mesh peer of that name, or nullptr.
const MeshPeerInfo* find_mesh_peer(std::string_view name);

}  // namespace gjklab::experiment
