// Adapter from gjklab's polytopes to libccd's boolean GJK and MPR (libccd 2.1).
//
// Facts about libccd 2.1 this adapter relies on (src/ccd.c, src/mpr.c, src/support.c):
//  * One Minkowski support point is one call of support1(obj1, d) followed by one call of
//    support2(obj2, −d), both with a private copy of the direction; libccd then forms
//    v = v1 − v2 (__ccdSupport).
//  * ccdGJKIntersect evaluates one support point in the direction first_dir before its main loop
//    and exactly one at the start of every pass of the loop, which runs while
//    iterations < ccd_t::max_iterations. A pass ends the query with "separated" when
//    v·d < 0 (d: the direction of that pass), with "separated" when the simplex update rejects a
//    degenerate simplex or leaves a (near-)zero direction, and with "intersecting" when the
//    simplex contains the origin. When the loop runs out it also returns "separated": the
//    return value alone cannot tell the iteration limit from a separation proof.
//  * ccdMPRIntersect never reads ccd_t::max_iterations. Portal discovery asks for two support
//    points in straight-line code and then loops (unbounded) until it has a portal, one support
//    point per pass; portal refinement is an unbounded while(1) loop with one support point per
//    pass (a pass that finds the origin inside the portal returns before evaluating one). Both
//    keep all their state in stack variables of plain C types and allocate nothing, so leaving
//    them from inside a support callback with longjmp skips no cleanup.
//  * ccdGJKPenetration runs the same GJK, then turns its simplex into a polytope (simplex of
//    four points: no support evaluation, or two if the origin lies on a face; three points: two;
//    two points: at most ccd_points_on_sphere_len + 3) and expands it in an unbounded loop
//    (EPA). Each pass takes the polytope element nearest to the origin (its nearest point p,
//    squared distance ‖p‖²); unless that element is a vertex or ‖p‖² is zero it evaluates one
//    support point w in direction p and stops when w·p − ‖p‖² < epa_tolerance, or when w is
//    within squared distance epa_tolerance of the element; otherwise it adds w. The polytope
//    lives on the heap (freed before returning), so that loop must end by its own test.
//  * ccdMPRPenetration runs MPR's portal discovery and refinement and then an expansion
//    towards the depth; none of them allocates.
#include <ccd/ccd.h>
#include <ccd/vec3.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <limits>
#include <new>
#include <stdexcept>
#include <type_traits>

#include "gjklab/peers/libccd.hpp"

#include "gjklab/geometry/support.hpp"

namespace gjklab::peers {
namespace {

// Values handed to longjmp; 0 is what setjmp returns when called directly.
enum Escape : int {
  kNoEscape = 0,
  kBudgetExhausted = 1,  ///< a support evaluation beyond the adapter's budget was requested
  kNonFinite = 2,        ///< a direction, support point or centre was NaN or infinite
};

// State of one query. It lives in the adapter function's frame, which a longjmp returns to and
// never skips, and it is reached from the callbacks only through the object pointer libccd
// passes back, so queries on different threads share nothing.
struct Query {
  const Polytope* a = nullptr;
  const Polytope* b = nullptr;
  /// Radii of sphere-swept shapes (0: the polytopes themselves).
  SweptRadii radii;
  /// Minkowski support evaluations allowed; a request for one more leaves libccd by longjmp.
  long support_budget = 0;
  /// Minkowski support evaluations completed (pairs of shape support calls).
  long evaluations = 0;
  /// Direction of the evaluation in progress, as libccd handed it to shape A.
  double direction[3] = {0, 0, 0};
  /// Support point of shape A of the evaluation in progress.
  double support_a[3] = {0, 0, 0};
  /// Whether the latest Minkowski point v satisfied v·d < 0, libccd's GJK separation test.
  bool last_point_separating = false;
  /// GJK+EPA penetration: when the budget is spent, answer the origin for both shapes (which
  /// ends libccd's EPA loop) instead of leaving by longjmp.
  bool soft_budget = false;
  bool budget_hit = false;
  /// Soft mode only: a non-finite direction or support point was answered with the origin.
  bool non_finite_seen = false;
  int origins_served_for_non_finite = 0;
  bool serving_origin = false;  ///< support_a answered the origin; support_b must too
  /// Outputs of the penetration entry points.
  ccd_real_t depth = 0;
  ccd_vec3_t dir{};
  ccd_vec3_t pos{};
  std::jmp_buf escape;
};

// A longjmp out of a callback must skip no frame holding an object with a non-trivial
// destructor (otherwise its behaviour is undefined). The callbacks below only hold scalars,
// pointers and, inside helpers that have returned before any longjmp, Vec3 values.
static_assert(std::is_trivially_destructible_v<Vec3>);
static_assert(std::is_trivially_destructible_v<Query>);

Query& query_of(const void* obj) {
  return *static_cast<Query*>(const_cast<void*>(obj));
}

bool all_finite(const double (&v)[3]) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

/// Writes the support point in direction d of shape swept by a ball of the given radius to out;
/// false if the point is not finite.
bool evaluate_support(const Polytope& shape, double radius, const double (&d)[3],
                      double (&out)[3]) noexcept {
  const Vec3 dir(d[0], d[1], d[2]);
  const Vec3 s =
      radius == 0 ? shape.support(dir) : SphereSwept<Polytope>(shape, radius).support(dir);
  out[0] = s.x();
  out[1] = s.y();
  out[2] = s.z();
  return all_finite(out);
}

/// Writes the vertex mean of shape to out; false if it is not finite (overflow).
bool evaluate_center(const Polytope& shape, double (&out)[3]) noexcept {
  const Vec3 c = shape.vertex_mean();
  out[0] = c.x();
  out[1] = c.y();
  out[2] = c.z();
  return all_finite(out);
}

}  // namespace

// The callbacks get C language linkage to match libccd's function pointer types. Every check
// that may longjmp comes before or after (never during) the evaluation helpers, so the only
// frames a longjmp skips are these callbacks (scalars only) and libccd's own C frames.
extern "C" {

// In soft mode a non-finite direction is answered with the origin too, which ends libccd's EPA
// when its nearest face is finite; should libccd keep asking, the query leaves by longjmp.
constexpr int kOriginsForNonFinite = 4;

static void serve_origin(Query& q, ccd_vec3_t* out) {
  q.serving_origin = true;
  out->v[0] = out->v[1] = out->v[2] = 0;
}

static void gjklab_ccd_support_a(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  Query& q = query_of(obj);
  if (q.evaluations >= q.support_budget) {
    if (!q.soft_budget) std::longjmp(q.escape, kBudgetExhausted);
    q.budget_hit = true;
    return serve_origin(q, out);
  }
  if (!all_finite(dir->v) || q.non_finite_seen) {
    if (!q.soft_budget || ++q.origins_served_for_non_finite > kOriginsForNonFinite)
      std::longjmp(q.escape, kNonFinite);
    q.non_finite_seen = true;
    return serve_origin(q, out);
  }
  std::copy(dir->v, dir->v + 3, q.direction);
  if (!evaluate_support(*q.a, q.radii.a, dir->v, out->v)) std::longjmp(q.escape, kNonFinite);
  std::copy(out->v, out->v + 3, q.support_a);
}

static void gjklab_ccd_support_b(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  Query& q = query_of(obj);
  if (q.serving_origin) {
    q.serving_origin = false;
    q.last_point_separating = false;
    out->v[0] = out->v[1] = out->v[2] = 0;
    return;
  }
  if (!all_finite(dir->v)) std::longjmp(q.escape, kNonFinite);
  if (!evaluate_support(*q.b, q.radii.b, dir->v, out->v)) std::longjmp(q.escape, kNonFinite);
  ++q.evaluations;
  // Replays libccd's GJK separation test on the point it is about to form, with the same
  // operations in the same order: v = v1 − v2 componentwise, then (v·d) < 0.
  const double vx = q.support_a[0] - out->v[0];
  const double vy = q.support_a[1] - out->v[1];
  const double vz = q.support_a[2] - out->v[2];
  const double dot = vx * q.direction[0] + vy * q.direction[1] + vz * q.direction[2];
  q.last_point_separating = dot < 0.0;
}

static void gjklab_ccd_center_a(const void* obj, ccd_vec3_t* center) {
  Query& q = query_of(obj);
  if (!evaluate_center(*q.a, center->v)) std::longjmp(q.escape, kNonFinite);
}

static void gjklab_ccd_center_b(const void* obj, ccd_vec3_t* center) {
  Query& q = query_of(obj);
  if (!evaluate_center(*q.b, center->v)) std::longjmp(q.escape, kNonFinite);
}

}  // extern "C"

namespace {

using LibccdEntry = int (*)(const void*, const void*, const ccd_t*);

// The only function that calls setjmp. Its parameters are never modified and everything the
// query changes lives in *q and *answer, outside this frame, so nothing read after a longjmp
// is indeterminate. (GCC never inlines a function that calls setjmp; noinline says so.)
[[gnu::noinline]] Escape run_guarded(LibccdEntry entry, const ccd_t* ccd, Query* q, int* answer) {
  switch (setjmp(q->escape)) {
    case kNoEscape:
      *answer = entry(q, q, ccd);
      return kNoEscape;
    case kBudgetExhausted:
      return kBudgetExhausted;
    default:
      return kNonFinite;
  }
}

void validate(const LibccdOptions& options) {
  // The upper bound keeps max_iterations + 2 support evaluations representable in an int.
  if (options.max_iterations < 0 || options.max_iterations > std::numeric_limits<int>::max() - 2)
    throw std::invalid_argument("libccd: max_iterations must be in [0, INT_MAX - 2]");
  if (!std::isfinite(options.mpr_tolerance) || options.mpr_tolerance < 0)
    throw std::invalid_argument("libccd: mpr_tolerance must be finite and non-negative");
  if (!std::isfinite(options.epa_tolerance) || options.epa_tolerance < 0)
    throw std::invalid_argument("libccd: epa_tolerance must be finite and non-negative");
  // Keeps every penetration budget (see libccd.hpp) representable in an int.
  if (options.max_depth_iterations < 0 ||
      options.max_depth_iterations > std::numeric_limits<int>::max() / 2 ||
      options.max_iterations > std::numeric_limits<int>::max() / 2 - 1000)
    throw std::invalid_argument(
        "libccd: max_depth_iterations must be in [0, INT_MAX / 2] and max_iterations below "
        "INT_MAX / 2 - 1000 for the penetration queries");
}

ccd_t make_ccd(const LibccdOptions& options) {
  ccd_t ccd;
  ccd.first_dir = ccdFirstDirDefault;  // (1, 0, 0)
  ccd.support1 = gjklab_ccd_support_a;
  ccd.support2 = gjklab_ccd_support_b;
  ccd.center1 = gjklab_ccd_center_a;
  ccd.center2 = gjklab_ccd_center_b;
  ccd.max_iterations = static_cast<unsigned long>(options.max_iterations);
  ccd.epa_tolerance = options.epa_tolerance;
  ccd.mpr_tolerance = options.mpr_tolerance;
  ccd.dist_tolerance = LibccdDefaults::dist_tolerance;
  return ccd;
}

/// Runs one libccd query with the given support budget and fills everything but `iterations`.
BooleanResult run_query(LibccdEntry entry, const Polytope& a, const Polytope& b, const ccd_t& ccd,
                        long support_budget, Escape& escape, Query& q) {
  q.a = &a;
  q.b = &b;
  q.support_budget = support_budget;
  int answer = 0;
  escape = run_guarded(entry, &ccd, &q, &answer);

  BooleanResult result;
  result.support_calls = static_cast<int>(q.evaluations);
  switch (escape) {
    case kNoEscape:
      result.intersect = answer != 0;
      result.termination = Termination::converged;
      break;
    case kBudgetExhausted:
      // libccd had not decided when its budget ran out: the answer is undetermined, and
      // "no intersection found" is all that can be reported.
      result.intersect = false;
      result.termination = Termination::step_limit;
      break;
    case kNonFinite:
      result.intersect = false;
      result.termination = Termination::numerical_failure;
      break;
  }
  return result;
}

}  // namespace

BooleanResult libccd_gjk_intersect(const Polytope& a, const Polytope& b,
                                   const LibccdOptions& options, const SweptRadii& radii) {
  validate(options);
  const ccd_t ccd = make_ccd(options);  // libccd bounds its own loop by max_iterations
  const long max_evaluations = options.max_iterations + 1L;
  Query q;
  q.radii = radii;
  Escape escape = kNoEscape;
  // libccd 2.1 never asks for more than max_iterations + 1 support points; the budget is only a
  // safeguard against a libccd whose loop bound means something else.
  BooleanResult result = run_query(ccdGJKIntersect, a, b, ccd, max_evaluations, escape, q);
  result.iterations = std::max(result.support_calls - 1, 0);

  // libccd returns "separated" both for a proof of separation and when its loop runs out.
  // The loop ran out only if all max_iterations passes were made (max_iterations + 1 support
  // points) and the last pass did not end the query. Of the ways a pass ends the query with
  // "separated", the support-point test v·d < 0 is replayed in the callback; the other two
  // (the simplex update rejecting a degenerate simplex, or leaving a near-zero direction) are
  // not visible from outside, so if one of them happens in the very last allowed pass this
  // reports step_limit although libccd stopped by its own test. Both are rare degenerate cases,
  // and neither proves separation either.
  if (escape == kNoEscape && !result.intersect && q.evaluations == max_evaluations &&
      !q.last_point_separating)
    result.termination = Termination::step_limit;
  return result;
}

BooleanResult libccd_mpr_intersect(const Polytope& a, const Polytope& b,
                                   const LibccdOptions& options, const SweptRadii& radii) {
  validate(options);
  const ccd_t ccd = make_ccd(options);  // max_iterations is recorded but unused by libccd's MPR
  // Portal discovery evaluates two support points before its loop; every further evaluation is
  // one pass of discovery's loop or of refinement's. Allowing max_iterations of those bounds
  // both unbounded loops; a request beyond that leaves libccd by longjmp (step_limit).
  const long max_evaluations = options.max_iterations + 2L;
  Query q;
  q.radii = radii;
  Escape escape = kNoEscape;
  BooleanResult result = run_query(ccdMPRIntersect, a, b, ccd, max_evaluations, escape, q);
  result.iterations = std::max(result.support_calls - 2, 0);
  return result;
}

namespace {

int gjk_penetration_entry(const void* obj1, const void* obj2, const ccd_t* ccd) {
  Query& q = query_of(obj1);
  return ccdGJKPenetration(obj1, obj2, ccd, &q.depth, &q.dir, &q.pos);
}

int mpr_penetration_entry(const void* obj1, const void* obj2, const ccd_t* ccd) {
  Query& q = query_of(obj1);
  return ccdMPRPenetration(obj1, obj2, ccd, &q.depth, &q.dir, &q.pos);
}

Vec3 to_vec(const ccd_vec3_t& v) {
  return {v.v[0], v.v[1], v.v[2]};
}

/// Fills the answer of a penetration query that libccd reported as intersecting; non-finite
/// parts are replaced (depth 0, normal (1, 0, 0), position 0) and reported as a numerical
/// failure.
void fill_contact(const Query& q, LibccdPenetration& r) {
  r.intersect = true;
  const Vec3 dir = to_vec(q.dir), pos = to_vec(q.pos);
  const double n = dir.norm();
  const bool finite = std::isfinite(q.depth) && pos.allFinite() && std::isfinite(n);
  if (std::isfinite(q.depth)) r.depth = q.depth;
  if (pos.allFinite()) r.position = pos;
  if (n > 0 && std::isfinite(n)) r.normal = dir / n;
  if (!finite) r.termination = Termination::numerical_failure;
}

}  // namespace

long libccd_gjk_penetration_budget(const LibccdOptions& options) {
  // GJK's own bound, the polytope set-up's worst case, then the EPA loop's share.
  return options.max_iterations + 1L + static_cast<long>(ccd_points_on_sphere_len) + 3 +
         options.max_depth_iterations;
}

LibccdPenetration libccd_gjk_penetration(const Polytope& a, const Polytope& b,
                                         const LibccdOptions& options, const SweptRadii& radii) {
  validate(options);
  const ccd_t ccd = make_ccd(options);
  const long gjk_evaluations = options.max_iterations + 1L;
  Query q;
  q.radii = radii;
  q.a = &a;
  q.b = &b;
  q.soft_budget = true;
  q.support_budget = libccd_gjk_penetration_budget(options);
  int answer = 0;
  const Escape escape = run_guarded(gjk_penetration_entry, &ccd, &q, &answer);

  LibccdPenetration r;
  if (escape != kNoEscape) {
    r.termination = Termination::numerical_failure;  // the soft budget never escapes
  } else if (answer == -2) {
    throw std::bad_alloc();
  } else if (q.non_finite_seen) {
    r.intersect = answer == 0;  // libccd's answer, computed after a non-finite value
    r.termination = Termination::numerical_failure;
  } else if (answer == 0) {
    fill_contact(q, r);
    if (r.termination == Termination::converged && q.budget_hit)
      r.termination = Termination::step_limit;
  } else {
    // Separated, or GJK's loop ran out (see libccd_gjk_intersect).
    r.termination = q.evaluations == gjk_evaluations && !q.last_point_separating
                        ? Termination::step_limit
                        : Termination::converged;
  }
  r.support_calls = static_cast<int>(q.evaluations);
  r.iterations = std::max(r.support_calls - 1, 0);
  return r;
}

LibccdPenetration libccd_mpr_penetration(const Polytope& a, const Polytope& b,
                                         const LibccdOptions& options, const SweptRadii& radii) {
  validate(options);
  const ccd_t ccd = make_ccd(options);
  Query q;
  q.radii = radii;
  q.a = &a;
  q.b = &b;
  q.support_budget = options.max_iterations + 2L + options.max_depth_iterations;
  int answer = 0;
  const Escape escape = run_guarded(mpr_penetration_entry, &ccd, &q, &answer);

  LibccdPenetration r;
  switch (escape) {
    case kNoEscape:
      if (answer == 0) fill_contact(q, r);
      break;
    case kBudgetExhausted:
      r.termination = Termination::step_limit;  // undetermined: intersect stays false
      break;
    case kNonFinite:
      r.termination = Termination::numerical_failure;
      break;
  }
  r.support_calls = static_cast<int>(q.evaluations);
  r.iterations = std::max(r.support_calls - 2, 0);
  return r;
}

}  // namespace gjklab::peers
