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
                  "boolean GJK walking a simplex with triple-product directions", run_gjk_bool},
    AlgorithmInfo{"gjk-johnson", AnswerKind::distance,
                  "GJK distance with Johnson's distance sub-algorithm", run_gjk_johnson},
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

// ---- benchmark loops ---------------------------------------------------------------------

namespace gjklab::experiment {

namespace {

void tally(BenchTally& t, const BooleanResult& r) {
  ++t.queries;
  t.iterations += r.iterations;
  t.support_calls += r.support_calls;
  t.intersections += r.intersect;
}

void tally(BenchTally& t, const DistanceResult& r) {
  ++t.queries;
  t.iterations += r.iterations;
  t.support_calls += r.support_calls;
  t.intersections += r.intersect;
  t.distance_sum += r.distance;
}

/// One loop shape for every algorithm: `query` is called directly (and inlined where the
/// compiler can see it), once per pair and repetition.
template <class Query>
BenchTally bench_loop(std::span<const BenchPair> pairs, int repetitions, Query&& query) {
  BenchTally t;
  for (int r = 0; r < repetitions; ++r)
    for (const BenchPair& p : pairs) tally(t, query(*p.a, *p.b));
  return t;
}

BenchTally bench_gjk_bool(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps) {
  return bench_loop(pairs, reps, [&](const Polytope& a, const Polytope& b) {
    return gjk_intersect(a, b, o.gjk_boolean);
  });
}

BenchTally bench_gjk_johnson(std::span<const BenchPair> pairs, const AlgorithmOptions& o,
                             int reps) {
  return bench_loop(pairs, reps, [&](const Polytope& a, const Polytope& b) {
    return gjk_distance(a, b, o.gjk_distance);
  });
}

BenchTally bench_libccd_gjk(std::span<const BenchPair> pairs, const AlgorithmOptions& o,
                            int reps) {
  return bench_loop(pairs, reps, [&](const Polytope& a, const Polytope& b) {
    return peers::libccd_gjk_intersect(a, b, o.libccd);
  });
}

BenchTally bench_libccd_mpr(std::span<const BenchPair> pairs, const AlgorithmOptions& o,
                            int reps) {
  return bench_loop(pairs, reps, [&](const Polytope& a, const Polytope& b) {
    return peers::libccd_mpr_intersect(a, b, o.libccd);
  });
}

struct NamedBenchLoop {
  std::string_view name;
  BenchLoop loop;
};

constexpr std::array kBenchLoops = {
    NamedBenchLoop{"gjk-bool", bench_gjk_bool},
    NamedBenchLoop{"gjk-johnson", bench_gjk_johnson},
    NamedBenchLoop{"libccd-gjk", bench_libccd_gjk},
    NamedBenchLoop{"libccd-mpr", bench_libccd_mpr},
};

}  // namespace

BenchLoop find_bench_loop(std::string_view name) {
  for (const NamedBenchLoop& l : kBenchLoops)
    if (l.name == name) return l.loop;
  return nullptr;
}

BenchTally run_bench_loop_via_registry(const AlgorithmInfo& algorithm,
                                       std::span<const BenchPair> pairs,
                                       const AlgorithmOptions& options, int repetitions) {
  BenchTally t;
  for (int r = 0; r < repetitions; ++r) {
    for (const BenchPair& p : pairs) {
      const Outcome o = algorithm.run(*p.a, *p.b, options);
      ++t.queries;
      t.iterations += o.iterations;
      t.support_calls += o.support_calls;
      t.intersections += o.intersect;
      if (o.distance) t.distance_sum += *o.distance;
    }
  }
  return t;
}

}  // namespace gjklab::experiment
