#include "gjklab/experiment/algorithms.hpp"

#include <array>

#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/gjk_nesterov.hpp"
#include "gjklab/gjk/subalgorithms.hpp"

namespace gjklab::experiment {

void AlgorithmOptions::set_max_iterations(int n) {
  gjk_boolean.max_iterations = n;
  gjk_distance.max_iterations = n;
  gjk_nesterov.max_iterations = n;
  libccd.max_iterations = n;
}

namespace {

Outcome from_boolean(const BooleanResult& r) {
  Outcome o;
  o.intersect = r.intersect;
  o.iterations = r.iterations;
  o.support_calls = r.support_calls;
  o.termination = r.termination;
  return o;
}

Outcome from_distance(const DistanceResult& r) {
  Outcome o;
  o.intersect = r.intersect;
  o.distance = r.distance;
  o.witness_a = r.witness_a;
  o.witness_b = r.witness_b;
  o.iterations = r.iterations;
  o.support_calls = r.support_calls;
  o.termination = r.termination;
  return o;
}

Outcome run_gjk_bool(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_boolean(gjk_intersect(a, b, o.gjk_boolean));
}

Outcome run_gjk_johnson(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_distance(gjk_distance(a, b, o.gjk_distance));
}

Outcome trace_gjk_bool(const Polytope& a, const Polytope& b, const AlgorithmOptions& o,
                       TraceRecorder& trace) {
  return from_boolean(gjk_intersect(a, b, o.gjk_boolean, trace));
}

Outcome trace_gjk_johnson(const Polytope& a, const Polytope& b, const AlgorithmOptions& o,
                          TraceRecorder& trace) {
  return from_distance(gjk_distance(a, b, o.gjk_distance, trace));
}

template <class Sub>
Outcome trace_gjk_with(const Polytope& a, const Polytope& b, const AlgorithmOptions& o,
                       TraceRecorder& trace) {
  return from_distance(gjk_distance_with<Sub>(a, b, o.gjk_distance, trace));
}

Outcome trace_gjk_nesterov(const Polytope& a, const Polytope& b, const AlgorithmOptions& o,
                           TraceRecorder& trace) {
  return from_distance(gjk_nesterov(a, b, o.gjk_nesterov, trace));
}

Outcome run_gjk_johnson_backup(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_distance(gjk_distance_with<JohnsonBackupSubAlgorithm>(a, b, o.gjk_distance));
}

Outcome run_gjk_sv(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_distance(gjk_distance_with<SignedVolumesSubAlgorithm>(a, b, o.gjk_distance));
}

Outcome run_gjk_voronoi(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_distance(gjk_distance_with<VoronoiSubAlgorithm>(a, b, o.gjk_distance));
}

Outcome run_gjk_nesterov(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_distance(gjk_nesterov(a, b, o.gjk_nesterov));
}

Outcome run_libccd_gjk(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_boolean(peers::libccd_gjk_intersect(a, b, o.libccd));
}

Outcome run_libccd_mpr(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_boolean(peers::libccd_mpr_intersect(a, b, o.libccd));
}

Outcome run_exact(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  Outcome out;
  exact::OracleAnswer answer = exact::solve(a.vertices(), b.vertices(), o.oracle);
  out.intersect = answer.intersect;
  out.distance = answer.distance;
  out.exact = std::move(answer);
  return out;
}

constexpr std::array kAlgorithms = {
    AlgorithmInfo{"gjk-bool", AnswerKind::boolean,
                  "boolean GJK walking a simplex with triple-product directions", run_gjk_bool,
                  trace_gjk_bool},
    AlgorithmInfo{"gjk-johnson", AnswerKind::distance,
                  "GJK distance with Johnson's distance sub-algorithm", run_gjk_johnson,
                  trace_gjk_johnson},
    AlgorithmInfo{"libccd-gjk", AnswerKind::boolean, "libccd's ccdGJKIntersect", run_libccd_gjk},
    AlgorithmInfo{"libccd-mpr", AnswerKind::boolean, "libccd's ccdMPRIntersect", run_libccd_mpr},
    AlgorithmInfo{"gjk-johnson-backup", AnswerKind::distance,
                  "GJK distance with Johnson's sub-algorithm and van den Bergen's backup "
                  "procedure",
                  run_gjk_johnson_backup, trace_gjk_with<JohnsonBackupSubAlgorithm>},
    AlgorithmInfo{"gjk-sv", AnswerKind::distance,
                  "GJK distance with the signed-volumes sub-algorithm (Montanari et al. 2017)",
                  run_gjk_sv, trace_gjk_with<SignedVolumesSubAlgorithm>},
    AlgorithmInfo{"gjk-voronoi", AnswerKind::distance,
                  "GJK distance with Voronoi-region tests (Ericson 2005)", run_gjk_voronoi,
                  trace_gjk_with<VoronoiSubAlgorithm>},
    AlgorithmInfo{"gjk-nesterov", AnswerKind::distance,
                  "Nesterov-accelerated GJK distance (Montaut et al. 2022), signed volumes",
                  run_gjk_nesterov, trace_gjk_nesterov},
    AlgorithmInfo{"exact", AnswerKind::exact, "exact answer from CGAL in rational arithmetic",
                  run_exact},
};

}  // namespace

std::span<const AlgorithmInfo> algorithms() { return kAlgorithms; }

const AlgorithmInfo* find_algorithm(std::string_view name) {
  for (const AlgorithmInfo& a : kAlgorithms)
    if (a.name == name) return &a;
  return nullptr;
}

std::string algorithm_names() {
  std::string names;
  for (const AlgorithmInfo& a : kAlgorithms) {
    if (!names.empty()) names += ", ";
    names += a.name;
  }
  return names;
}

}  // namespace gjklab::experiment
