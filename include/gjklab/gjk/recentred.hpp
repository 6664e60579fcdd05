// GJK queries on exactly re-centred pairs (geometry/recentring.hpp). With the queries'
// `recenter` option (on by default) a pair of polytopes far from the origin is translated
// exactly towards it before the query, and every point of the answer (witnesses, simplex
// points, trace rows) is moved back, so the caller sees the original frame. Pairs near the
// origin are queried as given.
#pragma once

#include <algorithm>
#include <concepts>
#include <optional>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/recentring.hpp"
#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/trace.hpp"

namespace gjklab::detail {

/// The shapes a query can re-centre: polytopes, and polytopes swept by a sphere.
template <class S>
concept Recentrable = std::same_as<S, Polytope> || std::same_as<S, SphereSwept<Polytope>>;

inline const Polytope& core_of(const Polytope& p) {
  return p;
}
inline const Polytope& core_of(const SphereSwept<Polytope>& s) {
  return s.core();
}

/// The shape `original` with its core replaced by `core` (which must outlive the result).
inline const Polytope& with_core(const Polytope&, const Polytope& core) {
  return core;
}
inline SphereSwept<Polytope> with_core(const SphereSwept<Polytope>& original,
                                       const Polytope& core) {
  return SphereSwept<Polytope>(core, original.radius());
}

/// The exact re-centring of a pair, when the options ask for it and it applies.
template <Recentrable A, Recentrable B>
std::optional<Vec3> recentring_of(const A& a, const B& b, bool recenter) {
  if (!recenter) return std::nullopt;
  // The inline quick reject of every pair near the origin: the translated pair spans at least
  // each cloud's own box, so it cannot be 8 times smaller than the largest coordinate unless
  // both boxes are.
  const Polytope &pa = core_of(a), &pb = core_of(b);
  const double extent = std::max(pa.box_extent(), pb.box_extent());
  const double magnitude = std::max(pa.max_magnitude(), pb.max_magnitude());
  if (!(8 * extent <= magnitude)) return std::nullopt;
  return exact_recentring(pa, pb);
}

/// The simplex with its points of A and B moved by t (w = a − b is unchanged).
inline Simplex translated(const Simplex& s, const Vec3& t) {
  Simplex out;
  for (SimplexVertex v : s.vertices()) {
    v.a += t;
    v.b += t;
    out.push(v);
  }
  return out;
}

/// Moves an answer's points back into the original frame (t: the re-centring translation).
inline void translate_answer(DistanceResult& r, const Vec3& t) {
  r.witness_a += t;
  r.witness_b += t;
  r.simplex = translated(r.simplex, t);
}
inline void translate_answer(PenetrationResult& r, const Vec3& t) {
  r.witness_a += t;
  r.witness_b += t;
}
inline void translate_answer(BooleanResult&, const Vec3&) {}

/// An observer that forwards every trace row with its points moved by t. The boolean walk's
/// simplex rows hold points of A − B only (a and b unknown), so `simplex_points` is false there.
template <class Observer>
struct TranslatedTrace {
  static constexpr bool enabled = Observer::enabled;
  Observer& inner;
  Vec3 t;
  bool simplex_points = true;

  void on_iteration(const GjkIterationTrace& row) {
    if constexpr (enabled) {
      GjkIterationTrace moved = row;
      moved.support.a += t;
      moved.support.b += t;
      if (simplex_points) moved.simplex = translated(row.simplex, t);
      inner.on_iteration(moved);
    }
  }
};

}  // namespace gjklab::detail
