// Search-direction policies of the GJK distance driver (gjk_distance.hpp).
//
// GJK is the Frank–Wolfe method on min ‖x‖² over A − B with a fully corrective step (the
// sub-algorithm): iteration k takes the support point s_k = argmin over A − B of d_k·x. Plain
// GJK uses d_k = v_k, the closest point of the current simplex. The accelerated variants mix
// in a momentum (Montaut, Le Lidec, Petrik, Sivic and Carpentier: "Collision detection
// accelerated: an optimization perspective", RSS 2022, and "GJK++: leveraging acceleration
// methods for faster collision detection", IEEE T-RO 2024):
//
//   Nesterov:  δ_k = (k+1)/(k+3),  y_k = δ_k v_k + (1−δ_k) s_{k−1},  d_k = δ_k d_{k−1} + (1−δ_k)
//   y_k Nesterov, normalised (coal's heuristic for shapes that are not strictly convex):
//              δ_k = (k+2)/(k+3),  d_k = δ_k d_{k−1}/‖d_{k−1}‖ + (1−δ_k) y_k/‖y_k‖
//   Polyak:    β_k = 1/(k+1),      d_k = β_k d_{k−1} + (1−β_k) v_k   (heavy-ball averaging)
//
// k counts main-loop iterations from 1. d_0 is the direction of the query's first support
// point (the centre difference or options.initial_direction, whichever the start used), scaled
// to the length of that point so that d_k mixes quantities of one unit and the query stays
// scale-free. The driver owns everything else: the momentum is dropped for good (restart) the
// first time the duality gap at the momentum's support point passes the stopping test, the
// point repeats, or the step does not decrease ‖v‖; from then on d_k = v_k.
//
// A policy is a small value type: `momentum` (false: the driver never asks for a direction),
// start(d0, s0), direction(k, v) → d_k, and observe(s_k) after each support point.
#pragma once

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// Plain GJK: d_k = v_k (in any precision).
struct PlainDirections {
  static constexpr bool momentum = false;
  template <class P>
  void start(const P&, const P&) {}
  template <class P>
  P direction(int, const P& v) const {
    return v;
  }
  template <class P>
  void observe(const P&) {}
};

/// Nesterov momentum (the paper's schedule, or coal's normalised heuristic), in precision T.
template <class T>
struct NesterovDirectionsT {
  using Point = Vec3T<T>;
  static constexpr bool momentum = true;
  bool normalize = false;
  Point d = Point::Zero();       ///< d_{k−1}
  Point s_prev = Point::Zero();  ///< s_{k−1}

  void start(const Point& d0, const Point& s0) {
    d = d0;
    s_prev = s0;
  }
  Point direction(int k, const Point& v) {
    if (normalize) {
      const T delta = T(k + 2) / T(k + 3);
      const Point y = delta * v + (1 - delta) * s_prev;
      const T ny = y.norm(), nd = d.norm();
      d = (ny > 0 && nd > 0) ? Point(delta * d / nd + (1 - delta) * y / ny) : v;
    } else {
      const T delta = T(k + 1) / T(k + 3);
      const Point y = delta * v + (1 - delta) * s_prev;
      d = delta * d + (1 - delta) * y;
    }
    return d;
  }
  void observe(const Point& s) { s_prev = s; }
};
using NesterovDirections = NesterovDirectionsT<double>;

/// Polyak (heavy-ball) momentum, GJK++'s second accelerated variant, in precision T.
template <class T>
struct PolyakDirectionsT {
  using Point = Vec3T<T>;
  static constexpr bool momentum = true;
  Point d = Point::Zero();  ///< d_{k−1}

  void start(const Point& d0, const Point&) { d = d0; }
  Point direction(int k, const Point& v) {
    const T beta = T(1) / T(k + 1);
    d = beta * d + (1 - beta) * v;
    return d;
  }
  void observe(const Point&) {}
};
using PolyakDirections = PolyakDirectionsT<double>;

}  // namespace gjklab
