// libccd as a peer: its GJK and MPR intersection tests run on gjklab's own shapes.
//
// libccd reports an int and no iteration count, and its MPR loops have no iteration bound of
// their own; this adapter counts support calls, enforces max_iterations for both, and maps the
// outcome to gjklab's Termination vocabulary.
//
// What the fields of BooleanResult mean here (libccd 2.1, double precision):
//   support_calls  Minkowski support evaluations: one call of the support function of each
//                  shape (s_A(d) and s_B(−d)). The centre queries MPR makes are not counted.
//   iterations     GJK: passes of ccdGJKIntersect's main loop. libccd evaluates one support point
//                  before the loop and exactly one per pass, so iterations = support_calls − 1.
//                  MPR: support evaluations made inside MPR's two loops (portal discovery's
//                  search for the third portal vertex, then portal refinement). The first two
//                  evaluations of portal discovery precede those loops, so
//                  iterations = max(support_calls − 2, 0). A final refinement pass that only
//                  finds the origin inside the portal evaluates nothing and is not counted.
//   termination    converged: libccd's own test decided the answer.
//                  step_limit: the iteration budget ran out; intersect is then false, but the
//                  answer is undetermined (libccd had not found an intersection yet).
//                  numerical_failure: a non-finite search direction, support point or centre
//                  appeared; the query is abandoned and intersect is false (undetermined).
//
// libccd decides with absolute thresholds (DBL_EPSILON on dot products and squared lengths, and
// mpr_tolerance in length units), so unlike gjklab's own queries its answers are not
// scale-invariant.
//
// The functions are re-entrant: every query keeps its state in its own stack frame.
#pragma once

#include <string>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/result.hpp"

namespace gjklab::peers {

struct LibccdDefaults {
  static constexpr int max_iterations = 64;
  /// libccd's own default (CCD_INIT).
  static constexpr double mpr_tolerance = 1e-4;
  /// libccd's defaults for the EPA and distance tolerances. ccdGJKIntersect and ccdMPRIntersect
  /// never read them; the adapter sets them explicitly so the ccd_t it passes is fully specified.
  static constexpr double epa_tolerance = 1e-4;
  static constexpr double dist_tolerance = 1e-6;
};

struct LibccdOptions {
  /// Iteration budget (must be >= 0). libccd's own default is unbounded ((unsigned long)-1).
  /// GJK: passed to libccd as ccd_t::max_iterations, the bound of its main loop.
  /// MPR: libccd ignores ccd_t::max_iterations in ccdMPRIntersect, so the adapter enforces the
  /// budget itself: at most max_iterations + 2 support evaluations (see `iterations` above).
  int max_iterations = LibccdDefaults::max_iterations;
  /// ccd_t::mpr_tolerance (absolute, length units of the Minkowski difference, >= 0): MPR
  /// reports "no intersection" once a new support point would move the portal face outward by
  /// no more than this distance (measured along the face's unit normal). Not used by GJK.
  double mpr_tolerance = LibccdDefaults::mpr_tolerance;
};

/// libccd's ccdGJKIntersect on the two polytopes (both in world coordinates).
/// Throws std::invalid_argument if the options are invalid.
BooleanResult libccd_gjk_intersect(const Polytope& a, const Polytope& b,
                                   const LibccdOptions& options = {});
/// libccd's ccdMPRIntersect on the two polytopes (both in world coordinates); the interior
/// point MPR starts from is the difference of the vertex means.
/// Throws std::invalid_argument if the options are invalid.
BooleanResult libccd_mpr_intersect(const Polytope& a, const Polytope& b,
                                   const LibccdOptions& options = {});

/// Version of libccd the adapter was built with (for provenance).
std::string libccd_version();

}  // namespace gjklab::peers
