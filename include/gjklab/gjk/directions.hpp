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

/// Plain GJK: d_k = v_k.
struct PlainDirections {
  static constexpr bool momentum = false;
  void start(const Vec3&, const Vec3&) {}
  Vec3 direction(int, const Vec3& v) const { return v; }
  void observe(const Vec3&) {}
};

/// Nesterov momentum (the paper's schedule, or coal's normalised heuristic).
struct NesterovDirections {
  static constexpr bool momentum = true;
  bool normalize = false;
  Vec3 d = Vec3::Zero();       ///< d_{k−1}
  Vec3 s_prev = Vec3::Zero();  ///< s_{k−1}

  void start(const Vec3& d0, const Vec3& s0) {
    d = d0;
    s_prev = s0;
  }
  Vec3 direction(int k, const Vec3& v) {
    if (normalize) {
      const double delta = (k + 2.0) / (k + 3.0);
      const Vec3 y = delta * v + (1 - delta) * s_prev;
      const double ny = y.norm(), nd = d.norm();
      d = (ny > 0 && nd > 0) ? Vec3(delta * d / nd + (1 - delta) * y / ny) : v;
    } else {
      const double delta = (k + 1.0) / (k + 3.0);
      const Vec3 y = delta * v + (1 - delta) * s_prev;
      d = delta * d + (1 - delta) * y;
    }
    return d;
  }
  void observe(const Vec3& s) { s_prev = s; }
};

/// Polyak (heavy-ball) momentum, GJK++'s second accelerated variant.
struct PolyakDirections {
  static constexpr bool momentum = true;
  Vec3 d = Vec3::Zero();  ///< d_{k−1}

  void start(const Vec3& d0, const Vec3&) { d = d0; }
  Vec3 direction(int k, const Vec3& v) {
    const double beta = 1.0 / (k + 1.0);
    d = beta * d + (1 - beta) * v;
    return d;
  }
  void observe(const Vec3&) {}
};

}  // namespace gjklab
