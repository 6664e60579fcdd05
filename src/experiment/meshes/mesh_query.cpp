#include "gjklab/experiment/meshes/mesh_query.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>

#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/experiment/meshes/piece_query.hpp"

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

}  // namespace

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
