// The classic boolean GJK: walks a simplex of A − B towards the origin until the simplex
// encloses it (intersection) or a support point fails to pass it (separation).
//
// Search directions come from triple products (no closest-point computation), so the query
// answers only "do the shapes intersect?". The first support point that does not pass the
// origin, s·d < 0, proves separation: the plane through the origin with normal d separates.
//
// The start (GjkBooleanOptions::start): by default the simplex starts from c = c_A − c_B, the
// difference of the shapes' vertex means, which lies in the hull of A − B and costs no support
// evaluation, and the first direction is −c. A pair whose centres are farther apart than the
// shapes reach is then proved separated by a single support evaluation, and an enclosing
// simplex needs three support points instead of four.
//
// Rounding. A claim the walk makes is `converged` only where it is proven: contact on a
// tetrahedron that holds the origin beyond the rounding of its face tests, separation by a
// support plane below the origin beyond the rounding of its support and dot product. Anything
// else (the origin on a segment or a face within rounding, a needle's flat tetrahedron, a
// plane through the origin within rounding) is decided by the GJK distance walk, whose answer
// carries a proven bracket (gjk_distance.hpp): the walk said "touching" for a point 3e-10 from
// a needle triangle of aspect 1e7.
//
// Cycles. Triple-product directions do not make the walk monotone, and it can come back to a
// state (direction and simplex) it was in: quickstart case 7786, a separated pair, cycles
// with period 10. Brent's cycle detection catches a cycle of any period; the query then hands
// over to the GJK distance walk, whose ‖v‖ decreases at every step, and answers with its
// decision (GjkStep::cycled in the trace, then the distance walk's rows).
#pragma once

#include <array>
#include <type_traits>

#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/recentred.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/trace.hpp"

namespace gjklab {

namespace detail {

/// Simplex of the boolean GJK, newest point first (points[0] is the last support point).
template <class T>
struct BooleanSimplexT {
  Vec3T<T> points[4];
  int size = 0;
};
using BooleanSimplex = BooleanSimplexT<double>;

/// The iteration from which the walk watches for a cycle (queries that end sooner, nearly all,
/// skip the bookkeeping).
inline constexpr int kCycleWatchStart = 12;

/// The last few support points of a traced walk, to give its simplex points (kept as points
/// of A − B only) their vertices in A and B; a point not found (the centre start) is returned
/// without indices.
template <class T>
class RecentSupports {
 public:
  void add(const SimplexVertexT<T>& v) {
    supports_[next_] = v;
    next_ = (next_ + 1) % kSize;
    count_ = count_ < kSize ? count_ + 1 : kSize;
  }
  SimplexVertexT<T> find(const Vec3T<T>& w) const {
    for (int i = 0; i < count_; ++i)
      if (supports_[i].w == w) return supports_[i];
    SimplexVertexT<T> unknown;
    unknown.w = w;
    return unknown;
  }

 private:
  static constexpr int kSize = 8;  // a simplex holds at most the last four support points
  std::array<SimplexVertexT<T>, kSize> supports_{};
  int next_ = 0;
  int count_ = 0;
};

/// Puts the newest point at the front of the simplex (a fall-through switch rather than a loop
/// with a data-dependent trip count: the same moves, without the loop's mispredictions).
template <class T>
void push_front(BooleanSimplexT<T>& simplex, const Vec3T<T>& w) {
  switch (simplex.size) {
    case 3:
      simplex.points[3] = simplex.points[2];
      [[fallthrough]];
    case 2:
      simplex.points[2] = simplex.points[1];
      [[fallthrough]];
    default:
      simplex.points[1] = simplex.points[0];
  }
  simplex.points[0] = w;
  ++simplex.size;
}

/// The boolean walk's trace rows: the search direction d, the support point w, the separation
/// test's d·w (in v_dot_w; separated when < 0) and ‖d‖² (in v_norm_squared), and the simplex
/// after the step with each point's vertices in A and B, found among the recent support points
/// (the walk keeps points only). No work when the observer is disabled.
template <class T, class Observer>
class BooleanTrace {
 public:
  explicit BooleanTrace(Observer& observer) : observer_(observer) {}
  void row(int iteration, const Vec3T<T>& d, const SimplexVertexT<T>& w,
           const BooleanSimplexT<T>& simplex, GjkStep step) {
    if constexpr (Observer::enabled) {
      recent_.add(w);
      GjkIterationTrace t;  // in double whatever the query's precision
      t.iteration = iteration;
      t.direction = d.template cast<double>();
      t.support = to_double(w);
      t.v_norm_squared = static_cast<double>(d.squaredNorm());
      t.v_dot_w = static_cast<double>(w.w.dot(d));
      for (int i = 0; i < simplex.size; ++i)
        t.simplex.push(to_double(recent_.find(simplex.points[i])));
      t.step = step;
      observer_.on_iteration(t);
    }
  }

 private:
  struct Nothing {};
  Observer& observer_;
  // Only a traced walk keeps the recent support points: an untraced query (the hot path)
  // neither builds nor clears them.
  [[no_unique_address]] std::conditional_t<Observer::enabled, RecentSupports<T>, Nothing> recent_;
};

/// Brent's cycle detection on the walk's states (search direction and simplex, bit for bit).
/// The walk is deterministic, so a state that comes back means a cycle that would repeat until
/// the step limit. One state is kept, replaced whenever the count since it reaches the next
/// power of two, so a cycle of any period p is caught within about 2·max(p, steps before it)
/// steps. (A ring of the last six states missed the period-10 cycle of quickstart case 7786.)
/// A support point alone may legitimately come back: the boolean walk is not monotone.
template <class T>
class CycleDetector {
 public:
  /// Records the state; true if it equals the kept one (the walk is in a cycle).
  bool seen(const Vec3T<T>& direction, const BooleanSimplexT<T>& simplex) {
    if (kept_ && kept_direction_ == direction && same(kept_simplex_, simplex)) return true;
    if (!kept_ || ++since_kept_ == period_bound_) {
      kept_ = true;
      kept_direction_ = direction;
      kept_simplex_ = simplex;
      since_kept_ = 0;
      period_bound_ *= 2;
    }
    return false;
  }

 private:
  static bool same(const BooleanSimplexT<T>& x, const BooleanSimplexT<T>& y) {
    if (x.size != y.size) return false;
    for (int i = 0; i < x.size; ++i)
      if (x.points[i] != y.points[i]) return false;
    return true;
  }
  bool kept_ = false;
  Vec3T<T> kept_direction_ = Vec3T<T>::Zero();
  BooleanSimplexT<T> kept_simplex_;
  int since_kept_ = 0;
  int period_bound_ = 1;
};

/// Updates simplex and direction for the segment, triangle or tetrahedron case.
/// Returns true when the origin is enclosed (on the boundary counts). Defined for T = float,
/// double and long double.
template <class T>
bool boolean_gjk_step(BooleanSimplexT<T>& simplex, Vec3T<T>& direction);

}  // namespace detail

namespace detail {

/// The answer of a boolean walk that cycled, decided by the GJK distance walk on the same
/// shapes (bounded by the same max_iterations); its iterations and support calls add to the
/// walk's, and its termination is the query's.
template <SupportMap A, SupportMap B, class Observer>
BooleanResult decide_by_distance(const A& a, const B& b, const GjkBooleanOptions& options,
                                 BooleanResult out, Observer& observer) {
  GjkDistanceOptions distance;
  distance.max_iterations = options.max_iterations;
  distance.recenter = false;  // the walk's shapes are re-centred already where it applies
  const auto r = gjk_distance(a, b, distance, observer);
  out.intersect = r.intersect;
  out.iterations += r.iterations;
  out.support_calls += r.support_calls;
  out.termination = r.termination;
  return out;
}

/// The boolean walk on the shapes as given (gjk_intersect below re-centres first).
/// True if the origin is certainly inside the tetrahedron y[0..3]: for every face, strictly on
/// the side of the opposite vertex by more than the rounding of the signed distances (the
/// bound of origin_outside_tetrahedron in gjk_distance.hpp, with ‖n‖ ≤ ‖e1‖‖e2‖, compared
/// squared: no square root on the path of every intersecting query). A walk that ends on a
/// tetrahedron the triple products say holds the origin has proven contact only then; a flat
/// one (a needle triangle lifted by rounding) leaves the decision to the distance walk.
template <class T>
bool origin_inside_tetrahedron(const Vec3T<T> (&y)[4]) {
  T mm = 0;  // max‖y_i‖²
  for (const Vec3T<T>& p : y)
    mm = std::max(mm, p.squaredNorm());
  const T c = 32 * dot_roundoff<T>;
  for (int k = 0; k < 4; ++k) {
    const Vec3T<T>& y0 = y[(k + 1) % 4];
    const Vec3T<T> e1 = y[(k + 2) % 4] - y0, e2 = y[(k + 3) % 4] - y0;
    const Vec3T<T> n = e1.cross(e2);
    // bound² = (32·kDotRoundoff)²·max‖y‖²·‖e1‖²·‖e2‖² ≥ the bound above, squared.
    const T bound_squared = c * c * mm * e1.squaredNorm() * e2.squaredNorm();
    T s_origin = -n.dot(y0), s_vertex = n.dot(y[k] - y0);
    if (s_vertex < 0) {
      s_origin = -s_origin;
      s_vertex = -s_vertex;
    }
    const T room = s_vertex - s_origin;  // the origin's distance from the opposite vertex's plane
    if (!(s_origin > 0 && room > 0 && s_origin * s_origin > bound_squared &&
          room * room > bound_squared))
      return false;
  }
  return true;
}

/// Whether the walk's claim stands as a proof: contact on a tetrahedron that certainly holds
/// the origin (other contacts, on a segment or a zero direction, are rounding's call), or
/// separation by a support plane d·x = d·w below the origin by more than the rounding of its
/// support and dot product (bracket_rounding(μ)·‖d‖, bracket.hpp). Shapes without a magnitude
/// (sphere-swept support maps) prove nothing this way, and their claims stand as before.
template <class T>
bool boolean_claim_proven(bool contact, const BooleanSimplexT<T>& simplex, T dw, const Vec3T<T>& d,
                          T magnitude) {
  if (!std::isfinite(magnitude)) return true;
  if (contact) return simplex.size == 4 && origin_inside_tetrahedron(simplex.points);
  const T e = bracket_rounding(magnitude);  // dw < −E·‖d‖, compared squared
  return dw < 0 && dw * dw > e * e * d.squaredNorm();
}

template <SupportMap A, SupportMap B, class Observer>
BooleanResult gjk_intersect_as_given(const A& a, const B& b, const GjkBooleanOptions& options,
                                     Observer& observer) {
  using T = shape_scalar_t<A>;
  using Point = Vec3T<T>;
  BooleanResult out;
  detail::BooleanSimplexT<T> simplex;
  Point direction;
  Point centre;
  const bool from_centre =
      options.start != GjkBooleanStart::fixed_direction && detail::centre_difference(a, b, centre);

  detail::BooleanTrace<T, Observer> tracer{observer};
  auto trace = [&](const Point& d, const SimplexVertexT<T>& w, GjkStep step) {
    tracer.row(out.iterations, d, w, simplex, step);
  };
  auto finish = [&](bool intersect, Termination t) {
    out.intersect = intersect;
    out.termination = t;
    return out;
  };
  detail::CycleDetector<T> cycles;
  const T magnitude = pair_magnitude<T>(a, b);
  // A claim the walk cannot prove is decided by the distance walk, whose answer is bracketed.
  auto decide = [&](bool contact, T dw, const Point& d) {
    if (boolean_claim_proven(contact, simplex, dw, d, magnitude))
      return finish(contact, Termination::converged);
    return decide_by_distance(a, b, options, out, observer);
  };
  if (from_centre && options.start == GjkBooleanStart::centre_point) {
    // c is a point of the hull of A − B: a simplex vertex like any support point, but free.
    simplex.points[0] = centre;
    simplex.size = 1;
    direction = -centre;
    out.iterations = 0;
  } else {
    const Point first_direction =
        from_centre ? Point(-centre) : Point(options.initial_direction.cast<T>());
    const SimplexVertexT<T> first = detail::minkowski_support(a, b, first_direction);
    out.support_calls = 1;
    if (!is_finite(first.w)) return finish(false, Termination::numerical_failure);
    // Only the centre direction points towards the origin, so only there can the first point
    // prove separation (with fixed_direction the test is skipped, keeping its counts).
    if (const T dw = first.w.dot(first_direction); from_centre && dw < 0) {
      out.iterations = 1;  // the one evaluation was the whole search
      trace(first_direction, first, GjkStep::separated);
      return decide(false, dw, first_direction);
    }
    simplex.points[0] = first.w;
    simplex.size = 1;
    direction = -first.w;
  }

  for (out.iterations = 1; out.iterations <= options.max_iterations; ++out.iterations) {
    // A zero direction means the origin lies on the current simplex: the shapes touch.
    if (is_zero(direction)) {
      trace(direction, {}, GjkStep::contact);
      return decide(true, T(0), direction);
    }
    if (!is_finite(direction)) {
      trace(direction, {}, GjkStep::non_finite);
      return finish(false, Termination::numerical_failure);
    }
    // A state seen before: the walk cycles, and the triple-product directions will not decide.
    // The monotone distance walk (‖v‖ decreases at every step) decides from here. Watched only
    // from kCycleWatchStart on: typical queries end before it and pay nothing.
    if (out.iterations >= detail::kCycleWatchStart && cycles.seen(direction, simplex)) {
      trace(direction, {}, GjkStep::cycled);
      return decide_by_distance(a, b, options, out, observer);
    }
    const Point d = direction;
    const SimplexVertexT<T> w = detail::minkowski_support(a, b, d);
    ++out.support_calls;
    if (!is_finite(w.w)) {
      trace(d, w, GjkStep::non_finite);
      return finish(false, Termination::numerical_failure);
    }
    if (const T dw = w.w.dot(d); dw < 0) {
      trace(d, w, GjkStep::separated);
      return decide(false, dw, d);
    }
    detail::push_front(simplex, w.w);
    if (detail::boolean_gjk_step(simplex, direction)) {
      trace(d, w, GjkStep::contact);
      return decide(true, T(0), d);
    }
    trace(d, w,
          out.iterations == options.max_iterations ? GjkStep::step_limit : GjkStep::continued);
  }
  out.iterations = options.max_iterations;
  // No separating plane was found within the budget; the answer is undetermined and reported
  // as "not intersecting" only together with step_limit.
  return finish(false, Termination::step_limit);
}

}  // namespace detail

/// Boolean GJK: do the hulls of A and B intersect? On the exactly re-centred pair when
/// options.recenter applies to two polytopes (or swept polytopes) far from the origin
/// (recentred.hpp), else on the shapes as given.
template <SupportMap A, SupportMap B, class Observer = NoTrace>
BooleanResult gjk_intersect(const A& a, const B& b, const GjkBooleanOptions& options = {},
                            Observer&& observer = {}) {
  using Traced = std::remove_reference_t<Observer>;
  if constexpr (detail::Recentrable<A> && detail::Recentrable<B>) {
    if (const auto t = detail::recentring_of(a, b, options.recenter)) {
      const auto core_a = detail::core_of(a).translated(-*t);
      const auto core_b = detail::core_of(b).translated(-*t);
      detail::TranslatedTrace<Traced> moved_trace{observer, t->template cast<double>(), false};
      return detail::gjk_intersect_as_given(detail::with_core(a, core_a),
                                            detail::with_core(b, core_b), options, moved_trace);
    }
  }
  return detail::gjk_intersect_as_given(a, b, options, observer);
}

}  // namespace gjklab
