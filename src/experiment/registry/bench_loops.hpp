// The benchmark loops of the registry's entries (private to src/experiment/registry): one loop
// shape for every algorithm, each query called directly so that the loop times the library and
// not the registry. Included by algorithms.cpp alone.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "experiment/registry/queries.hpp"

namespace gjklab::experiment::registry_parts {


// ---- benchmark loops (see algorithms.hpp) ------------------------------------------------

/// Adds one query to the tallies; `distance` is added to the distance sum (0 when the answer
/// has none, or when the shapes intersect, as the registry's Outcome reports it).
inline void count_query(BenchTally& t, long long iterations, long long support_calls, bool intersect,
                 double distance = 0) {
  ++t.queries;
  t.iterations += iterations;
  t.support_calls += support_calls;
  t.intersections += intersect;
  t.distance_sum += distance;
}

// The same tallies as run_bench_loop_via_registry takes from each algorithm's Outcome.
inline void tally(BenchTally& t, const BooleanResult& r) {
  count_query(t, r.iterations, r.support_calls, r.intersect);
}
template <class T>
void tally(BenchTally& t, const DistanceResultT<T>& r) {
  count_query(t, r.iterations, r.support_calls, r.intersect, static_cast<double>(r.distance));
}
inline void tally(BenchTally& t, const PenetrationResult& r) {
  count_query(t, r.iterations, r.support_calls, r.intersect, r.intersect ? 0.0 : r.distance);
}
template <class T>
void tally(BenchTally& t, const EpaResultT<T>& r) {
  // As run_epa: GJK's iterations, then EPA's.
  count_query(t, r.gjk_iterations + r.iterations, r.support_calls, r.intersect,
              r.intersect ? 0.0 : static_cast<double>(r.distance));
}
inline void tally(BenchTally& t, const peers::LibccdPenetration& r) {
  count_query(t, r.iterations, r.support_calls, r.intersect);
}
inline void tally(BenchTally& t, const CertifiedAnswer& r) {
  count_query(t, r.iterations, r.support_calls, r.answer.intersect,
              r.answer.intersect ? 0.0 : r.answer.distance);
}
inline void tally(BenchTally& t, const peers::SatResult& r) {
  count_query(t, r.axes_tested, r.support_calls, r.intersect);
}

/// One loop shape for every algorithm: `query` is called directly (and inlined where the
/// compiler can see it), once per pair and repetition.
template <class Query>
BenchTally bench_loop(std::span<const BenchPair> pairs, int repetitions, Query&& query) {
  BenchTally t;
  for (int r = 0; r < repetitions; ++r)
    for (const BenchPair& p : pairs)
      tally(t, query(*p.a, *p.b));
  return t;
}

template <class Prepare, class Query>
BenchTally prepared_bench_loop(std::span<const BenchPair> pairs, int repetitions, Prepare&& prepare,
                               Query&& query);

/// The loop of a GJK query in float or long double: the shapes rounded to T are prepared once
/// per polytope (rounded<T>, as the peers' prepared shapes), so the loop times the queries.
template <class T, class Query>
BenchTally rounded_bench_loop(std::span<const BenchPair> pairs, int repetitions, Query&& query) {
  return prepared_bench_loop(pairs, repetitions, rounded<T>, query);
}

/// A GJK query's loop in the precision of the options (`query` takes shapes of any scalar).
template <class Query>
BenchTally gjk_bench_loop(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps,
                          Query&& query) {
  switch (o.precision) {
    case ScalarPrecision::single_float:
      return rounded_bench_loop<float>(pairs, reps, query);
    case ScalarPrecision::long_double:
      return rounded_bench_loop<long double>(pairs, reps, query);
    case ScalarPrecision::double_float:
      break;
  }
  return bench_loop(pairs, reps, query);
}

inline BenchTally bench_gjk_bool(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps) {
  return gjk_bench_loop(pairs, o, reps, [&](const auto& a, const auto& b) {
    return gjk_intersect(a, b, o.gjk_boolean);
  });
}

/// The loop of a GJK distance variant, from its core query.
template <class Core>
BenchTally bench_distance(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps) {
  return gjk_bench_loop(
      pairs, o, reps, [&](const auto& a, const auto& b) { return Core::run(a, b, o, NoTrace{}); });
}

inline BenchTally bench_epa(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps) {
  return gjk_bench_loop(pairs, o, reps, [&](const auto& a, const auto& b) {
    // Buffers reused across the batch's queries, as run_epa's per thread (one per precision).
    thread_local EpaPolytopeT<shape_scalar_t<std::remove_cvref_t<decltype(a)>>> workspace;
    return gjk_epa(a, b, o.gjk_distance, o.epa, workspace);
  });
}

/// The bench loop of a libccd adapter (the bench's shapes are polytopes: radii 0).
template <auto Query>
BenchTally bench_libccd(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps) {
  return bench_loop(pairs, reps, [&](const Polytope& a, const Polytope& b) {
    return Query(a, b, o.libccd, SweptRadii{});
  });
}

/// The loop of an algorithm that queries shapes prepared for it (`Prepare`: Polytope → shared
/// pointer to the prepared shape): each pair's prepared shapes are looked up once per call,
/// before its repetitions, so the timed queries call the library directly, as the other loops.
template <class Prepare, class Query>
BenchTally prepared_bench_loop(std::span<const BenchPair> pairs, int repetitions, Prepare&& prepare,
                               Query&& query) {
  using Shape = decltype(prepare(std::declval<const Polytope&>()));
  std::vector<std::pair<Shape, Shape>> shapes;
  shapes.reserve(pairs.size());
  for (const BenchPair& p : pairs)
    shapes.emplace_back(prepare(*p.a), prepare(*p.b));
  BenchTally t;
  for (int r = 0; r < repetitions; ++r)
    for (const auto& [a, b] : shapes)
      tally(t, query(*a, *b));
  return t;
}

inline BenchTally bench_gjk_certified(std::span<const BenchPair> pairs, const AlgorithmOptions& o,
                               int reps) {
  const exact::OracleOptions options = certified_query_options(o);
  return bench_loop(pairs, reps, [&](const Polytope& a, const Polytope& b) {
    return solve_certified(a, b, SweptRadii{}, options);
  });
}

inline BenchTally bench_sat(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps) {
  return prepared_bench_loop(pairs, reps, sat_shape,
                             [&](const peers::SatShape& a, const peers::SatShape& b) {
                               return peers::sat_query(a, b, o.sat);
                             });
}

#ifdef GJKLAB_HAVE_FCL
template <peers::FclSolver Solver>
BenchTally bench_fcl(std::span<const BenchPair> pairs, const AlgorithmOptions& o, int reps) {
  return prepared_bench_loop(pairs, reps, fcl_shape,
                             [&](const peers::FclShape& a, const peers::FclShape& b) {
                               return peers::fcl_query(a, b, Solver, o.fcl);
                             });
}
#endif

#ifdef GJKLAB_HAVE_BULLET
template <PenetrationResult (*Query)(const peers::BulletShape&, const peers::BulletShape&)>
BenchTally bench_bullet(std::span<const BenchPair> pairs, const AlgorithmOptions&, int reps) {
  return prepared_bench_loop(pairs, reps, bullet_shape, Query);
}
#endif

}  // namespace gjklab::experiment::registry_parts
