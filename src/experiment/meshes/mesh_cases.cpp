#include "gjklab/experiment/meshes/mesh_cases.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjklab/exact/mesh_truth.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/meshes/mesh_query.hpp"
#include "gjklab/experiment/meshes/piece_query.hpp"
#include "gjklab/experiment/run/judging.hpp"

namespace gjklab::experiment {

namespace {

/// Both meshes' pieces (corners) under the spec's decomposition; `source` names the pair in
/// errors, which name the side and the decomposition.
std::array<std::vector<std::vector<Vec3>>, 2> decompose_pair(const AlgorithmSpec& spec,
                                                             const TriangleMesh& a,
                                                             const TriangleMesh& b,
                                                             const std::string& source) {
  std::array<std::vector<std::vector<Vec3>>, 2> corners;
  const TriangleMesh* meshes[] = {&a, &b};
  for (int side = 0; side < 2; ++side) {
    const std::string name = source + ", mesh " + (side == 0 ? "A" : "B");
    try {
      corners[side] =
          spec.decomposition->decompose(*meshes[side], name, spec.decomposition_options).pieces;
    } catch (const std::exception& error) {
      throw std::runtime_error(name + ": decomposition '" + std::string(spec.decomposition->name) +
                               "' failed: " + error.what());
    }
  }
  return corners;
}

std::array<std::vector<Polytope>, 2> polytopes_of(
    const std::array<std::vector<std::vector<Vec3>>, 2>& corners) {
  std::array<std::vector<Polytope>, 2> pieces;
  for (int side = 0; side < 2; ++side)
    for (const std::vector<Vec3>& piece : corners[side])
      pieces[side].emplace_back(piece);
  return pieces;
}

/// Each side's pieces under every decomposition the case's algorithms asked for, made once.
class CaseDecompositions {
 public:
  CaseDecompositions(const GeneratedCase& c) : case_(c) {}  // NOLINT: holds a reference

  /// A's and B's pieces under the spec's decomposition and options.
  const std::array<std::vector<Polytope>, 2>& pieces(const AlgorithmSpec& spec) {
    const auto described = describe_decomposition(*spec.decomposition, spec.decomposition_options);
    for (const Entry& e : entries_)
      if (e.described == described) return e.pieces;
    Entry& e = entries_.emplace_back();
    e.described = described;
    e.name = std::string(spec.decomposition->name);
    e.corners = decompose_pair(spec, *case_.mesh_a, *case_.mesh_b,
                               "case " + std::to_string(case_.record.case_id));
    e.pieces = polytopes_of(e.corners);
    return e.pieces;
  }

  /// Every piece made, for a kept case's geometry.
  std::vector<KeptPiece> kept() const {
    std::vector<KeptPiece> out;
    for (const Entry& e : entries_)
      for (int side = 0; side < 2; ++side)
        for (const std::vector<Vec3>& corners : e.corners[side])
          out.push_back({e.name, side, corners});
    return out;
  }

 private:
  struct Entry {
    std::vector<std::pair<std::string, std::string>> described;
    std::string name;
    std::array<std::vector<std::vector<Vec3>>, 2> corners;
    std::array<std::vector<Polytope>, 2> pieces;
  };
  const GeneratedCase& case_;
  std::vector<Entry> entries_;
};

/// One query's answer and what it adds for a non-convex pair.
struct MeshQuery {
  Outcome outcome;
  MeshAlgorithmRecord mesh;
};

MeshQuery run_mesh_query(const AlgorithmSpec& spec, const GeneratedCase& c,
                         CaseDecompositions& decompositions) {
  MeshQuery q;
  if (spec.mesh_peer) {
    const MeshPeerAnswer answer = spec.mesh_peer->run(*c.mesh_a, *c.mesh_b);
    q.outcome = answer.outcome;
    q.mesh.face_a = static_cast<std::int32_t>(answer.face_a);
    q.mesh.face_b = static_cast<std::int32_t>(answer.face_b);
    return q;
  }
  const auto& [a, b] = decompositions.pieces(spec);
  const PieceOutcome p = run_on_pieces(*find_algorithm(spec.name), a, b, spec.options);
  q.outcome = p.outcome;
  q.mesh.pieces_a = static_cast<std::int32_t>(a.size());
  q.mesh.pieces_b = static_cast<std::int32_t>(b.size());
  q.mesh.piece_pairs = p.piece_pairs;
  q.mesh.piece_pairs_tested = p.piece_pairs_tested;
  q.mesh.piece_a = static_cast<std::int32_t>(p.piece_a);
  q.mesh.piece_b = static_cast<std::int32_t>(p.piece_b);
  return q;
}

/// Median wall time of `repetitions` runs of the query (ns), the decompositions made already:
/// a convex algorithm's time is its queries over the pieces; a mesh peer's includes building
/// its own structures (FCL's trees), which it does per query.
double time_mesh_query(const AlgorithmSpec& spec, const GeneratedCase& c,
                       CaseDecompositions& decompositions, int repetitions) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> ns;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = Clock::now();
    const MeshQuery q = run_mesh_query(spec, c, decompositions);
    const auto stop = Clock::now();
    if (q.outcome.iterations < 0) break;  // keeps the call from being optimised away
    ns.push_back(std::chrono::duration<double, std::nano>(stop - start).count());
  }
  std::nth_element(ns.begin(), ns.begin() + static_cast<std::ptrdiff_t>(ns.size() / 2), ns.end());
  return ns[ns.size() / 2];
}

}  // namespace

CaseResult evaluate_mesh_case(const ExperimentConfig& config, GeneratedCase generated) {
  CaseResult result;
  result.record = generated.record;
  MeshCaseResult& mesh = result.mesh.emplace();
  const double size = generated.record.size;
  if (config.oracle) {
    const MeshTruthRecords truth = mesh_truth_records(
        exact::mesh_truth(*generated.mesh_a, *generated.mesh_b), config.touching_band * size);
    result.exact = truth.exact;
    mesh.exact = truth.mesh;
  }
  CaseDecompositions decompositions(generated);
  for (const AlgorithmSpec& spec : config.algorithms) {
    const MeshQuery q = run_mesh_query(spec, generated, decompositions);
    AlgorithmRecord r = algorithm_record(q.outcome);
    if (result.exact) judge(r, q.outcome, *result.exact, size);
    // The witnesses' exact errors are measured against hulls: not reported for solids.
    if (q.outcome.witness_a && q.outcome.witness_b) {
      r.witness_a = *q.outcome.witness_a;
      r.witness_b = *q.outcome.witness_b;
    }
    if (config.timing)
      r.time_ns = time_mesh_query(spec, generated, decompositions, config.repetitions);
    r.failure = classify_failure(r, result.exact ? &*result.exact : nullptr, config.touching_band);
    result.algorithms.push_back(r);
    mesh.algorithms.push_back(q.mesh);
  }
  if (worth_keeping(result, config.touching_band)) {
    CaseGeometry& g = result.geometry.emplace();
    g.a = std::move(generated.a);
    g.b = std::move(generated.b);
    g.faces_a = generated.mesh_a->faces;
    g.faces_b = generated.mesh_b->faces;
    g.pieces = decompositions.kept();
  }
  return result;
}

}  // namespace gjklab::experiment

namespace gjklab::experiment {

MeshTruthRecords mesh_truth_records(const exact::MeshTruth& t, double band) {
  MeshTruthRecords out;
  out.answer.intersect = t.intersect;
  out.answer.distance_squared = t.distance_squared;
  out.answer.distance = t.distance;
  out.answer.hull_vertices_a = out.answer.hull_vertices_b = -1;
  out.answer.method = exact::AnswerMethod::mesh_truth;
  ExactRecord& r = out.exact;
  r.intersect = t.intersect;
  r.distance = t.distance;
  r.distance2_num = t.distance_squared.numerator();
  r.distance2_den = t.distance_squared.denominator();
  r.hull_vertices_a = r.hull_vertices_b = -1;
  r.contact = t.intersect          ? ContactClass::intersecting
              : t.distance <= band ? ContactClass::touching_band
                                   : ContactClass::separated;
  r.method = exact::AnswerMethod::mesh_truth;
  MeshExactRecord& m = out.mesh;
  m.contact = std::string(to_string(t.contact));
  m.face_a = static_cast<std::int32_t>(t.face_a);
  m.face_b = static_cast<std::int32_t>(t.face_b);
  m.exact_intersection_tests = t.exact_intersection_tests;
  m.exact_distance_evaluations = t.exact_distance_evaluations;
  return out;
}

Outcome run_mesh_algorithm(const AlgorithmSpec& spec, const TriangleMesh& a, const TriangleMesh& b,
                           const std::string& source) {
  if (spec.mesh_peer) return spec.mesh_peer->run(a, b).outcome;
  const auto pieces = polytopes_of(decompose_pair(spec, a, b, source));
  return run_on_pieces(*find_algorithm(spec.name), pieces[0], pieces[1], spec.options).outcome;
}

}  // namespace gjklab::experiment
