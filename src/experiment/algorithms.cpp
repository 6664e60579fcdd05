#include "gjklab/experiment/algorithms.hpp"

#include <array>

#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

namespace gjklab::experiment {

void AlgorithmOptions::set_max_iterations(int n) {
  gjk_boolean.max_iterations = n;
  gjk_distance.max_iterations = n;
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
