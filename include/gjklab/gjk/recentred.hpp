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
#include "gjklab/geometry/scalar_cloud.hpp"
#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/trace.hpp"

namespace gjklab::detail {

/// The clouds a query can re-centre: polytopes, and clouds of another precision.
template <class S>
concept RecentrableCloud =
    std::same_as<S, Polytope> || std::same_as<S, ScalarCloud<shape_scalar_t<S>>>;

/// The shapes a query can re-centre: those clouds, and those clouds swept by a sphere.
template <class S>
concept Recentrable = RecentrableCloud<S> || std::same_as<S, SphereSwept<Polytope>> ||
    std::same_as<S, SphereSwept<ScalarCloud<shape_scalar_t<S>>>>;

template <RecentrableCloud C>
const C& core_of(const C& p) {
  return p;
}
template <RecentrableCloud C>
const C& core_of(const SphereSwept<C>& s) {
  return s.core();
}

/// The shape `original` with its core replaced by `core` (which must outlive the result).
template <RecentrableCloud C>
const C& with_core(const C&, const C& core) {
  return core;
}
template <RecentrableCloud C>
SphereSwept<C> with_core(const SphereSwept<C>& original, const C& core) {
  return SphereSwept<C>(core, original.radius());
}

/// The exact re-centring of a pair, when the options ask for it and it applies.
template <Recentrable A, Recentrable B>
auto recentring_of(const A& a, const B& b, bool recenter)
    -> std::optional<Vec3T<shape_scalar_t<A>>> {
  if (!recenter) return std::nullopt;
  // The inline quick reject of every pair near the origin: the translated pair spans at least
  // each cloud's own box, so it cannot be 8 times smaller than the largest coordinate unless
  // both boxes are.
  const auto &pa = core_of(a), &pb = core_of(b);
  const auto extent = std::max(pa.box_extent(), pb.box_extent());
  const auto magnitude = std::max(pa.max_magnitude(), pb.max_magnitude());
  if (!(8 * extent <= magnitude)) return std::nullopt;
  return exact_recentring(pa, pb);
}

/// The simplex with its points of A and B moved by t (w = a − b is unchanged).
template <class T>
SimplexT<T> translated(const SimplexT<T>& s, const Vec3T<T>& t) {
  SimplexT<T> out;
  for (SimplexVertexT<T> v : s.vertices()) {
    v.a += t;
    v.b += t;
    out.push(v);
  }
  return out;
}

/// Moves an answer's points back into the original frame (t: the re-centring translation).
template <class T>
void translate_answer(DistanceResultT<T>& r, const Vec3T<T>& t) {
  r.witness_a += t;
  r.witness_b += t;
  r.simplex = translated(r.simplex, t);
}
template <class T>
void translate_answer(PenetrationResultT<T>& r, const Vec3T<T>& t) {
  r.witness_a += t;
  r.witness_b += t;
}
template <class T>
void translate_answer(BooleanResult&, const Vec3T<T>&) {}

/// An observer that forwards every trace row with its points moved by t (trace rows are in
/// double whatever the query's precision; t is exact in double). The boolean walk's
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
