#include "gjklab/experiment/meshes/mesh_query.hpp"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/experiment/meshes/piece_query.hpp"
#ifdef GJKLAB_HAVE_FCL
#include "gjklab/peers/fcl_mesh.hpp"
#endif

namespace gjklab::experiment {

namespace {

AnswerFields truth_fields(const AlgorithmInfo& algorithm, const MeshSide& a, const MeshSide& b) {
  const exact::MeshTruth t = exact::mesh_truth(a.mesh, b.mesh);
  AnswerFields f;
  f.emplace_back("algorithm", std::string(algorithm.name));
  f.emplace_back("intersect", t.intersect);
  f.emplace_back("distance", t.distance);
  f.emplace_back("distance2_num", t.distance_squared.numerator());
  f.emplace_back("distance2_den", t.distance_squared.denominator());
  f.emplace_back("method", std::string("mesh-truth"));
  f.emplace_back("contact", std::string(to_string(t.contact)));
  if (t.face_a >= 0) {
    f.emplace_back("face_a", std::int64_t{t.face_a});
    f.emplace_back("face_b", std::int64_t{t.face_b});
  }
  f.emplace_back("exact_intersection_tests", static_cast<std::int64_t>(t.exact_intersection_tests));
  f.emplace_back("exact_distance_evaluations",
                 static_cast<std::int64_t>(t.exact_distance_evaluations));
  return f;
}

AnswerFields piece_fields(const AlgorithmInfo& algorithm, const MeshSide& a, const MeshSide& b,
                          const AlgorithmOptions& options) {
  if (!a.decomposition || !b.decomposition)
    throw std::logic_error("mesh_answer_fields: a side was not decomposed");
  const PieceOutcome p = run_on_pieces(algorithm, a.pieces, b.pieces, options);
  const ScalarPrecision precision =
      takes_precision(algorithm) ? options.precision : ScalarPrecision::double_float;
  AnswerFields f = answer_fields(algorithm.name, p.outcome, precision, 0, 0);
  f.emplace_back("decomposition", a.decomposition->method);
  f.emplace_back("pieces_a", static_cast<std::int64_t>(a.pieces.size()));
  f.emplace_back("pieces_b", static_cast<std::int64_t>(b.pieces.size()));
  f.emplace_back("piece_pairs", static_cast<std::int64_t>(p.piece_pairs));
  f.emplace_back("piece_pairs_tested", static_cast<std::int64_t>(p.piece_pairs_tested));
  if (p.piece_a >= 0) {
    f.emplace_back("piece_a", p.piece_a);
    f.emplace_back("piece_b", p.piece_b);
  }
  return f;
}

#ifdef GJKLAB_HAVE_FCL
/// FCL's collide decides intersect; its distance query gives the distance and witnesses.
MeshPeerAnswer fcl_bvh(const TriangleMesh& a, const TriangleMesh& b) {
  const peers::FclMesh ma(a), mb(b);
  const peers::FclMeshAnswer collide = peers::fcl_mesh_collide(ma, mb);
  const peers::FclMeshAnswer distance = peers::fcl_mesh_distance(ma, mb);
  MeshPeerAnswer answer;
  answer.outcome.intersect = collide.intersect;
  answer.outcome.distance = distance.distance;
  answer.outcome.witness_a = distance.witness_a;
  answer.outcome.witness_b = distance.witness_b;
  const peers::FclMeshAnswer& decided = collide.intersect ? collide : distance;
  answer.face_a = decided.face_a;
  answer.face_b = decided.face_b;
  return answer;
}

constexpr std::array kMeshPeers = {
    MeshPeerInfo{"fcl-bvh",
                 "FCL's BVHModel<OBBRSS> collide and distance on the two meshes (triangles, not "
                 "solids: a mesh inside the other does not intersect)",
                 fcl_bvh},
};
#else
constexpr std::array<MeshPeerInfo, 0> kMeshPeers = {};
#endif

}  // namespace

AnswerFields mesh_peer_fields(const MeshPeerInfo& peer, const MeshPeerAnswer& answer) {
  const Outcome& o = answer.outcome;
  AnswerFields f;
  f.emplace_back("algorithm", std::string(peer.name));
  f.emplace_back("intersect", o.intersect);
  if (o.distance) f.emplace_back("distance", *o.distance);
  if (o.witness_a && o.witness_b) {
    f.emplace_back("witness_a", *o.witness_a);
    f.emplace_back("witness_b", *o.witness_b);
  }
  if (answer.face_a >= 0) {
    f.emplace_back("face_a", answer.face_a);
    f.emplace_back("face_b", answer.face_b);
  }
  return f;
}

std::span<const MeshPeerInfo> mesh_peers() {
  return kMeshPeers;
}

const MeshPeerInfo* find_mesh_peer(std::string_view name) {
  for (const MeshPeerInfo& p : mesh_peers())
    if (p.name == name) return &p;
  return nullptr;
}

void decompose_side(MeshSide& side, const DecompositionInfo& decomposition, std::string_view source,
                    const DecompositionOptions& options) {
  if (side.decomposition) return;
  side.decomposition = decomposition.decompose(side.mesh, source, options);
  side.pieces = piece_polytopes(*side.decomposition);
}

AnswerFields mesh_answer_fields(const AlgorithmInfo& algorithm, const MeshSide& a,
                                const MeshSide& b, const AlgorithmOptions& options) {
  return algorithm.kind == AnswerKind::exact ? truth_fields(algorithm, a, b)
                                             : piece_fields(algorithm, a, b, options);
}

}  // namespace gjklab::experiment
