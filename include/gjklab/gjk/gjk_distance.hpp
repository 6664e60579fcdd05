// GJK distance query (Gilbert, Johnson and Keerthi 1988) with an interchangeable
// sub-algorithm (Johnson's by default).
//
// Iterates v_k, the point of the current simplex closest to the origin, towards the point of
// A − B closest to the origin. Each iteration takes the support point w = s_A(−v) − s_B(v),
// tests termination, adds w to the simplex and reduces it with the sub-algorithm.
// Upper bound of the distance: ‖v‖; lower bound: v·w/‖v‖.
#pragma once

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/bracket.hpp"
#include "gjklab/gjk/closest_on_simplex.hpp"
#include "gjklab/gjk/directions.hpp"
#include "gjklab/gjk/distance_state.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/recentred.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/simplex.hpp"
#include "gjklab/gjk/trace.hpp"

namespace gjklab {

namespace detail {

/// The starting simplex of a distance query and its closest point. Cold start (`warm` empty):
/// the support point of A − B in options.initial_direction (one support call). Warm start:
/// the given points, each re-evaluated on the current shapes from its vertex indices when the
/// shape reports them (so a previous query's final simplex stays valid after the shapes
/// moved); points without indices are taken as given and must be points of the current A and
/// B. Repeated and non-finite points are skipped, and the rest is reduced by the sub-algorithm;
/// when nothing usable remains or the reduction fails, the query starts cold.
///
/// Returns d_0, the direction the start minimised over A − B (the negated direction of the
/// first support call), or the start's closest point after a warm start (see directions.hpp).
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class T>
Vec3T<T> start_simplex(const Sub& sub, const A& a, const B& b, const GjkDistanceOptions& options,
                       std::span<const SimplexVertexT<T>> warm, SimplexT<T>& simplex,
                       ClosestOnSimplexT<T>& best, int& support_calls) {
  simplex.clear();
  for (const SimplexVertexT<T>& given : warm) {
    if (simplex.full()) break;
    SimplexVertexT<T> v = given;
    if constexpr (requires { a.vertices(); }) {
      if (v.index_a >= 0 && static_cast<std::size_t>(v.index_a) < a.vertices().size())
        v.a = a.vertices()[v.index_a];
    }
    if constexpr (requires { b.vertices(); }) {
      if (v.index_b >= 0 && static_cast<std::size_t>(v.index_b) < b.vertices().size())
        v.b = b.vertices()[v.index_b];
    }
    v.w = v.a - v.b;
    if (is_finite(v.w) && !simplex.contains(v.w)) simplex.push(v);
  }
  if (!simplex.empty()) {
    SimplexT<T> reduced = simplex;
    if (sub.reduce(reduced, best) && is_finite(best.v)) {
      simplex = reduced;
      return best.v;
    }
  }
  Vec3T<T> centre;
  const bool from_centre =
      options.start == GjkDistanceStart::centre_direction && centre_difference(a, b, centre);
  const Vec3T<T> search =
      from_centre ? Vec3T<T>(-centre) : Vec3T<T>(options.initial_direction.cast<T>());
  const SimplexVertexT<T> first = minkowski_support(a, b, search);
  ++support_calls;
  simplex.clear();
  simplex.push(first);
  best = {first.w, first.a, first.b, {1, 0, 0, 0}};
  return -search;
}

/// What becomes of a step whose simplex plus w was solved: taken (‖v‖ decreased, or a bounded
/// stall), the momentum dropped (restart), or the query stops: converged when the gap is within
/// its rounding (optimal), else with no_progress (stop).
enum class StepOutcome : std::uint8_t { progressed, stalled, restart, optimal, stop };

/// The quantities of one iteration that the step needs: ‖v‖², v·s and ‖s‖² for the support
/// point s, and whether separation is proven.
template <class T>
struct StepInputs {
  T vv, vw, ww;
  bool separation_proven;
};

/// What a step did: the trace step to record, and the stop when the query ends there.
struct StepVerdict {
  GjkStep step;
  std::optional<DistanceStop> stop;
};

/// Solves the simplex plus the support point `next` with the sub-algorithm and takes the step
/// (contact, progress, a bounded stall), drops the momentum, or stops; the simplex changes only
/// once the answer is accepted.
template <class Sub, class T, class Observer>
StepVerdict solve_step(const Sub& sub, DistanceQueryState<T, Observer>& q,
                       const SimplexVertexT<T>& next, const StepInputs<T>& in, bool& accelerated,
                       int& stalls) {
  SimplexT<T>& simplex = q.simplex();
  ClosestOnSimplexT<T>& best = q.best;
  std::array<Vec3T<T>, 4> y = simplex.points();
  y[simplex.size()] = next.w;
  const auto s = sub.solve(y, simplex.size() + 1);
  if (!s.found) return {GjkStep::degenerate, DistanceStop{Termination::degenerate_simplex, false}};
  if (!is_finite(s.closest))
    return {GjkStep::non_finite, DistanceStop{Termination::numerical_failure, false}};
  const bool full = s.subset == 0xF;
  // A full simplex is contact unless its tetrahedron provably misses the origin: flat within
  // rounding, with the origin off its plane (kissing faces), where the sub-algorithm's
  // weights are rounding noise. Then the query goes on from the nearest face, as after a
  // separation certificate.
  const bool contact = full ? !origin_outside_tetrahedron(y)
                            : q.in_contact(s.closest, max_norm_squared(y, s.subset));
  if (!in.separation_proven && contact) {
    apply_solution(s, next, simplex, best);
    return {GjkStep::contact, DistanceStop{Termination::converged, true}};
  }
  // The upper bound ‖v‖ must decrease strictly. When rounding hides the decrease, a plain
  // query takes the step only as a bounded stall (may_stall), else keeps the old v and stops;
  // an accelerated query drops its momentum instead. The stop is convergence when the gap
  // ‖v‖² − v·w is not certified (within the rounding of its two products): then v·w/‖v‖ is a
  // lower bound of the distance to that rounding, and ‖v‖ is within 4·kDotRoundoff·(‖v‖ + ‖w‖)
  // of the distance, the precision of the pair's scale (near contact, where ‖v‖ ≪ ‖w‖, no
  // relative gap of ‖v‖² can be met). A certified gap left is a descent cut short: no_progress.
  auto judge = [&](T new_vv, bool keeps_next) {
    if (new_vv < in.vv) return StepOutcome::progressed;
    if (accelerated) return StepOutcome::restart;
    if (may_stall(in.vv, in.vw, in.ww, new_vv, keeps_next, stalls)) return StepOutcome::stalled;
    return gap_certified(in.vv, in.vw, in.ww) ? StepOutcome::stop : StepOutcome::optimal;
  };
  const auto taken = [](StepOutcome o) {
    return o == StepOutcome::progressed || o == StepOutcome::stalled;
  };
  StepOutcome outcome;
  if (full) {
    // Contact is ruled out (by the separation certificate or the tetrahedron test): the
    // closest point lies on one of the faces.
    SimplexT<T> reduced = simplex;
    reduced.push(next);
    ClosestOnSimplexT<T> candidate;
    if (!detail::reduce_to_closest_face(sub, reduced, candidate))
      return {GjkStep::degenerate, DistanceStop{Termination::degenerate_simplex, false}};
    outcome = judge(candidate.v.squaredNorm(), reduced.contains(next.w));
    if (taken(outcome)) {
      simplex = reduced;
      best = candidate;
    }
  } else {
    outcome = judge(s.closest.squaredNorm(), (s.subset >> simplex.size()) & 1u);
    if (taken(outcome)) apply_solution(s, next, simplex, best);
  }
  switch (outcome) {
    case StepOutcome::restart:
      accelerated = false;
      return {GjkStep::momentum_restart, std::nullopt};
    case StepOutcome::optimal:
      return {GjkStep::gap_converged, DistanceStop{Termination::converged, false}};
    case StepOutcome::stop:
      return {GjkStep::no_progress, DistanceStop{Termination::no_progress, false}};
    case StepOutcome::stalled:
      ++stalls;
      return {GjkStep::stalled, std::nullopt};
    case StepOutcome::progressed:
      break;
  }
  stalls = 0;
  return {GjkStep::continued, std::nullopt};
}

/// The iteration's search direction: the momentum direction while the query is accelerated,
/// else v. A vanishing or non-finite momentum direction carries no information: the query goes
/// plain from there.
template <class T, class Directions>
Vec3T<T> search_direction(Directions& directions, int iteration, const Vec3T<T>& v,
                          bool& accelerated) {
  if constexpr (Directions::momentum) {
    if (accelerated) {
      const Vec3T<T> d = directions.direction(iteration, v);
      if (is_finite(d) && !is_zero(d)) return d;
      accelerated = false;
    }
  }
  return v;
}

/// What the support point s found in direction −d says: the plane d·x = d·s supports A − B, so
/// for d·s > 0 the distance is at least about d·s/‖d‖ (the proven bound: bracket.hpp), and
/// d·s beyond its rounding certifies that the shapes do not intersect (dw = d·s, dd = ‖d‖²,
/// ww = ‖s‖²).
template <class T, class Observer>
void note_support_plane(DistanceQueryState<T, Observer>& q, bool& separation_proven, T dw, T dd,
                        T ww) {
  q.note_lower_bound(dw, dd);
  if (!separation_proven && separation_certified(dw, dd, ww)) separation_proven = true;
}

/// The GJK distance loop of every variant: the search direction comes from `directions` (see
/// directions.hpp), everything else is shared: the cold or warm start, the stopping tests, the
/// separation certificate, the sub-algorithm's step, stalls and the momentum restart.
/// q.out.simplex and q.best hold the answer when it returns.
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class T, class Observer, class Directions>
DistanceStop gjk_distance_loop(const A& a, const B& b, std::span<const SimplexVertexT<T>> warm,
                               DistanceQueryState<T, Observer>& q, Directions& directions) {
  const Sub sub{};
  const GjkDistanceOptions& options = q.options;
  DistanceResultT<T>& out = q.out;
  SimplexT<T>& simplex = q.simplex();
  ClosestOnSimplexT<T>& best = q.best;
  const Vec3T<T> d0 = start_simplex(sub, a, b, options, warm, simplex, best, out.support_calls);

  if (!is_finite(simplex[0].w)) return {Termination::numerical_failure, false};
  // A warm start may begin with a tetrahedron that encloses the origin.
  if (simplex.full() || q.in_contact(best.v, simplex)) return {Termination::converged, true};

  // Set once some support point s satisfies d·s > 0 beyond rounding: then the plane d·x = d·s
  // separates the origin from A − B, a certificate that the shapes do not intersect. A
  // sub-algorithm that later claims contact has accepted a numerically flat simplex.
  bool separation_proven = false;
  // Steps in a row whose decrease of ‖v‖ rounding hid (see may_stall).
  int stalls = 0;
  bool accelerated = Directions::momentum;
  if constexpr (Directions::momentum) {
    const T n0 = d0.norm();
    directions.start(n0 > 0 ? Vec3T<T>(d0 / n0 * simplex[0].w.norm()) : best.v, simplex[0].w);
  }

  // A continuation (gjk_distance_run_as_given) counts on from the iterations already made.
  for (++out.iterations; out.iterations <= options.max_iterations; ++out.iterations) {
    const Vec3T<T> v = best.v;
    const T vv = v.squaredNorm();
    const Vec3T<T> d = search_direction(directions, out.iterations, v, accelerated);
    auto trace = [&](const SimplexVertexT<T>& w, T vw, GjkStep step) {
      q.trace(-d, w, vv, vw, step);
    };
    const SimplexVertexT<T> next = detail::minkowski_support(a, b, Vec3T<T>(-d));
    ++out.support_calls;
    if (!is_finite(next.w)) {
      trace(next, std::numeric_limits<T>::quiet_NaN(), GjkStep::non_finite);
      return {Termination::numerical_failure, false};
    }
    directions.observe(next.w);
    const T vw = v.dot(next.w);
    const T ww = next.w.squaredNorm();
    if (accelerated)
      note_support_plane(q, separation_proven, d.dot(next.w), d.squaredNorm(), ww);
    else
      note_support_plane(q, separation_proven, vw, vv, ww);

    // The duality gap at s: the stopping test when plain, the restart test when accelerated.
    const bool gap_met = gap_converged(options, vv, vw);
    // s already in the simplex: in exact arithmetic its gap would be 0 (every retained point
    // lies on the plane v·x = ‖v‖²), so the new point brings no information.
    const bool repeated = !gap_met && simplex.contains(next.w);
    if (accelerated && (gap_met || repeated)) {
      accelerated = false;
      trace(next, vw, GjkStep::momentum_restart);
      continue;
    }
    if (gap_met) {
      trace(next, vw, GjkStep::gap_converged);
      return {Termination::converged, false};
    }
    if (repeated) {
      trace(next, vw, GjkStep::repeated_support);
      return {Termination::converged, false};
    }
    const StepVerdict verdict =
        solve_step(sub, q, next, StepInputs<T>{vv, vw, ww, separation_proven}, accelerated, stalls);
    const bool last = out.iterations == options.max_iterations;
    trace(next, vw,
          verdict.stop || verdict.step == GjkStep::momentum_restart || !last ? verdict.step
                                                                             : GjkStep::step_limit);
    if (verdict.stop) return *verdict.stop;
  }
  out.iterations = options.max_iterations;
  return {Termination::step_limit, false};
}

/// For shapes whose support is not a full scan (hill climbing), the support plane that a full
/// scan of both shapes in the final direction −v proves (the loop's planes prove nothing
/// there, bracket.hpp); one scan per shape, once per query.
template <SupportMap A, SupportMap B, class T, class Observer>
void scan_lower_bound(const A& a, const B& b, DistanceQueryState<T, Observer>& q) {
  if constexpr (requires {
                  a.scan_support_index(q.best.v);
                  b.scan_support_index(q.best.v);
                }) {
    if (q.planes_prove || !std::isfinite(q.rounding) || is_zero(q.best.v)) return;
    const Vec3T<T>& v = q.best.v;
    const Vec3T<T> w =
        a.vertices()[a.scan_support_index(Vec3T<T>(-v))] - b.vertices()[b.scan_support_index(v)];
    q.planes_prove = true;
    q.note_lower_bound(v.dot(w), v.squaredNorm());
  }
}

/// Whether a loop's stop leaves a continuation something to try: its answer is not proven
/// (the termination finish() judged is not converged), it ended on its own merits rather than
/// on a NaN or the step limit, and iterations are left.
template <class T>
bool worth_continuing(const DistanceResultT<T>& r, const GjkDistanceOptions& options) {
  return r.termination != Termination::converged &&
         r.termination != Termination::numerical_failure &&
         r.termination != Termination::step_limit && r.iterations < options.max_iterations;
}

/// Runs the loop on the shapes as given and builds the result in the returned object itself.
///
/// Where the sub-algorithm's answer cannot be proven (its bracket is too wide, bracket.hpp), the
/// query goes on from its final simplex with the sub-simplex solved in double-word arithmetic
/// (PreciseSubAlgorithm) and plain directions, within the same iteration budget, and keeps the
/// answer with the narrower bracket: the stop of a needle triangle or of nearly parallel
/// segments, where every sub-algorithm's decisions in double are rounding noise, is then
/// decided at 106 bits. The lower bound carries over (every support plane is a proof).
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class Observer, class Directions,
          class T = shape_scalar_t<A>>
DistanceResultT<T> gjk_distance_run_as_given(const A& a, const B& b,
                                             const GjkDistanceOptions& options,
                                             std::span<const SimplexVertexT<T>> warm,
                                             Observer& observer, Directions directions) {
  DistanceResultT<T> out;
  DistanceQueryState<T, Observer> q{options, observer, out};
  q.measure(a, b);
  const DistanceStop stop = gjk_distance_loop<Sub>(a, b, warm, q, directions);
  scan_lower_bound(a, b, q);
  q.finish(stop);
  if (!worth_continuing(out, options)) return out;

  DistanceResultT<T> again;
  again.iterations = out.iterations;
  again.support_calls = out.support_calls;
  DistanceQueryState<T, Observer> p{options, observer, again};
  p.measure(a, b);
  p.lower_bound = q.lower_bound;
  p.provable_contact = bracket_resolution(p.magnitude) - p.rounding;
  const SimplexT<T> start = out.simplex;
  PlainDirections plain;
  const DistanceStop precise_stop =
      gjk_distance_loop<PreciseSubAlgorithm>(a, b, start.vertices(), p, plain);
  scan_lower_bound(a, b, p);
  p.finish(precise_stop);
  const bool better = again.termination == Termination::converged ||
                      again.upper_bound - again.lower_bound < out.upper_bound - out.lower_bound;
  if (better) return again;
  // The first answer stands, judged again with the lower bound the continuation proved, at the
  // cost of both.
  q.lower_bound = std::max(q.lower_bound, p.lower_bound);
  q.finish(stop);
  out.iterations = again.iterations;
  out.support_calls = again.support_calls;
  return out;
}

/// Runs the query: on the exactly re-centred pair when options.recenter applies to two
/// clouds far from the origin (recentred.hpp), else on the shapes as given.
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class Observer,
          class Directions = PlainDirections, class T = shape_scalar_t<A>>
DistanceResultT<T> gjk_distance_run(const A& a, const B& b, const GjkDistanceOptions& options,
                                    std::span<const SimplexVertexT<T>> warm, Observer&& observer,
                                    Directions directions = {}) {
  using Traced = std::remove_reference_t<Observer>;
  if constexpr (RecentrableCloud<A> && std::same_as<A, B>) {
    if (const auto t = recentring_of(a, b, options.recenter)) {
      const A moved_a = a.translated(-*t), moved_b = b.translated(-*t);
      // Warm-start points are re-read from their indices; points without indices move too.
      std::vector<SimplexVertexT<T>> start(warm.begin(), warm.end());
      for (SimplexVertexT<T>& v : start) {
        v.a -= *t;
        v.b -= *t;
      }
      TranslatedTrace<Traced> moved_trace{observer, t->template cast<double>()};
      DistanceResultT<T> out = gjk_distance_run_as_given<Sub>(
          moved_a, moved_b, options, std::span<const SimplexVertexT<T>>(start), moved_trace,
          directions);
      translate_answer(out, *t);
      return out;
    }
  }
  return gjk_distance_run_as_given<Sub>(a, b, options, warm, observer, directions);
}

}  // namespace detail

/// Distance between two convex shapes given by support maps (both in the same frame), with
/// sub-algorithm Sub and an observer that receives a trace of every iteration when enabled.
/// The result's termination says why the loop stopped; on any stop other than `converged` the
/// answer is the best upper bound found so far (‖v‖ and its witnesses). The query runs in the
/// shapes' scalar type (double; float or long double for ScalarCloud, scalar_cloud.hpp).
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class Observer = NoTrace>
DistanceResultT<shape_scalar_t<A>> gjk_distance_with(const A& a, const B& b,
                                                     const GjkDistanceOptions& options,
                                                     Observer&& observer = {}) {
  return detail::gjk_distance_run<Sub>(a, b, options, {}, std::forward<Observer>(observer));
}

/// The same query warm-started from a simplex, typically the previous query's final simplex
/// (`result.simplex.vertices()`) in a sequence of queries on a moving pair. Polytopes report
/// vertex indices, so each point is re-evaluated on the current shapes (see
/// detail::start_simplex); a usable start costs no support call. Same answer and termination
/// vocabulary as the cold query, usually in fewer iterations when the pair moved little.
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class Observer = NoTrace>
DistanceResultT<shape_scalar_t<A>> gjk_distance_warm_with(
    const A& a, const B& b, std::span<const SimplexVertexT<shape_scalar_t<A>>> start,
    const GjkDistanceOptions& options, Observer&& observer = {}) {
  return detail::gjk_distance_run<Sub>(a, b, options, start, std::forward<Observer>(observer));
}

/// `gjk-johnson`: GJK distance with Johnson's sub-algorithm.
template <SupportMap A, SupportMap B, class Observer = NoTrace>
DistanceResultT<shape_scalar_t<A>> gjk_distance(const A& a, const B& b,
                                                const GjkDistanceOptions& options = {},
                                                Observer&& observer = {}) {
  return gjk_distance_with<JohnsonSubAlgorithm>(a, b, options, std::forward<Observer>(observer));
}

}  // namespace gjklab
