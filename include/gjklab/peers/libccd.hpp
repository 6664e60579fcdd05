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
// Penetration depth. libccd_gjk_penetration (ccdGJKPenetration: GJK, then libccd's EPA) and
// libccd_mpr_penetration (ccdMPRPenetration: MPR, then its portal search for the depth) answer
// with a LibccdPenetration. Their counts and terminations:
//   support_calls  Minkowski support evaluations of the whole query (all phases).
//   iterations     support_calls − 1 (GJK+EPA) or max(support_calls − 2, 0) (MPR), as for the
//                  intersection tests: the adapter cannot tell libccd's phases apart.
//   termination    converged: libccd finished by its own tests.
//                  step_limit: the support budget ran out (see LibccdOptions). For GJK+EPA
//                  this can only happen in EPA's expansion loop: the answer is then libccd's
//                  nearest polytope face at that point (intersect is true and the depth is a
//                  lower bound). For MPR the answer is undetermined (intersect false).
//                  numerical_failure: a non-finite value appeared (a direction, support point,
//                  depth or normal). intersect is libccd's answer when it finished (GJK+EPA),
//                  false otherwise; non-finite parts of the answer are replaced by depth 0 and
//                  normal (1, 0, 0). libccd 2.1's EPA produces such values on simple inputs:
//                  on two axis-aligned cubes of side 2 at z = 0 and z = 1.9 it answers depth 0
//                  with a NaN direction (or, with other support tie-breaking, asks for support
//                  in a NaN direction).
// libccd's EPA allocates its polytope on the heap, so the adapter avoids leaving it by
// longjmp. When the budget runs out, or a direction is not finite, the support callbacks
// return the origin for both shapes: libccd's expansion test (new support value along the
// nearest point p minus ‖p‖² below epa_tolerance) fails for it whenever ‖p‖ > 0, and libccd
// returns its current nearest face, releasing its memory. Only if libccd keeps asking after
// four such answers to non-finite directions does the query leave by longjmp, leaking that
// polytope (a few hundred bytes).
//
// Sphere-swept shapes. With non-zero radii (SweptRadii) each shape's support point is its
// polytope's plus radius·d/‖d‖ (the support map of the polytope swept by a ball), and libccd
// runs on those shapes as given; the centres MPR starts from are the vertex means, which lie
// inside the swept shapes too. The depth is then that of the swept shapes.
//
// The functions are re-entrant: every query keeps its state in its own stack frame.
#pragma once

#include <string>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/swept.hpp"
#include "gjklab/gjk/termination.hpp"

namespace gjklab::peers {

struct LibccdDefaults {
  static constexpr int max_iterations = 64;
  /// libccd's own default (CCD_INIT).
  static constexpr double mpr_tolerance = 1e-4;
  /// libccd's defaults for the EPA and distance tolerances. ccdGJKIntersect and ccdMPRIntersect
  /// never read them; the adapter sets them explicitly so the ccd_t it passes is fully specified.
  static constexpr double epa_tolerance = 1e-4;
  static constexpr double dist_tolerance = 1e-6;
  /// Support evaluations allowed for the depth phase of the penetration queries.
  static constexpr int max_depth_iterations = 128;
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
  /// ccd_t::epa_tolerance (absolute, >= 0), read by libccd_gjk_penetration only. libccd stops
  /// EPA when the new support point w along the nearest point p of the polytope gains less than
  /// this over the polytope, measured as w·p − ‖p‖² (length², scaled by the depth), or when w
  /// lies within squared distance epa_tolerance of the nearest face.
  double epa_tolerance = LibccdDefaults::epa_tolerance;
  /// Penetration queries: support evaluations allowed beyond those of the boolean phase
  /// (>= 0). The adapter enforces one total budget: GJK+EPA gets max_iterations + 1 (libccd's
  /// own GJK bound) + the at most ccd_points_on_sphere_len + 3 evaluations that turn GJK's
  /// simplex into a polytope + max_depth_iterations; MPR gets max_iterations + 2 +
  /// max_depth_iterations for its discovery, refinement and depth loops together.
  int max_depth_iterations = LibccdDefaults::max_depth_iterations;
};

/// Answer of a libccd penetration query (libccd reports no distance for separated shapes).
struct LibccdPenetration {
  bool intersect = false;
  /// Penetration depth when intersecting (0 otherwise): translating B by depth·normal brings
  /// the shapes into touching contact (libccd's own convention, as in PenetrationResult).
  double depth = 0;
  /// Unit direction; libccd gives none for some touching contacts (a zero vector), which is
  /// reported as (1, 0, 0).
  Vec3 normal = Vec3::UnitX();
  /// libccd's contact position (GJK+EPA: the mean of the support points of the nearer half of
  /// the polytope's vertices; MPR: from the portal's barycentric coordinates).
  Vec3 position = Vec3::Zero();
  int iterations = 0;
  int support_calls = 0;
  Termination termination = Termination::converged;
};

/// libccd's ccdGJKIntersect on the two polytopes (both in world coordinates).
/// Throws std::invalid_argument if the options are invalid.
BooleanResult libccd_gjk_intersect(const Polytope& a, const Polytope& b,
                                   const LibccdOptions& options = {}, const SweptRadii& radii = {});
/// libccd's ccdMPRIntersect on the two polytopes (both in world coordinates); the interior
/// point MPR starts from is the difference of the vertex means.
/// Throws std::invalid_argument if the options are invalid.
BooleanResult libccd_mpr_intersect(const Polytope& a, const Polytope& b,
                                   const LibccdOptions& options = {}, const SweptRadii& radii = {});

/// libccd's ccdGJKPenetration (GJK, then EPA) on the two polytopes, with a bounded EPA.
/// Throws std::invalid_argument if the options are invalid, std::bad_alloc if libccd's
/// polytope allocation fails.
LibccdPenetration libccd_gjk_penetration(const Polytope& a, const Polytope& b,
                                         const LibccdOptions& options = {},
                                         const SweptRadii& radii = {});
/// The total support-evaluation budget libccd_gjk_penetration enforces with these options.
long libccd_gjk_penetration_budget(const LibccdOptions& options);
/// libccd's ccdMPRPenetration on the two polytopes (interior point: difference of the vertex
/// means), bounded by the adapter. Throws std::invalid_argument if the options are invalid.
LibccdPenetration libccd_mpr_penetration(const Polytope& a, const Polytope& b,
                                         const LibccdOptions& options = {},
                                         const SweptRadii& radii = {});

/// Version of libccd the adapter was built with (for provenance).
std::string libccd_version();

}  // namespace gjklab::peers
