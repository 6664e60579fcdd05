// What an experiment records about each case: plain values handed from the driver to the
// archive writer. One CaseResult per case; the writer stores them as columns.
//
// Conventions for the archive: lengths in the pair's world units; "relative" means divided by
// the pair's size (the larger bounding-box diagonal of the two clouds); NaN marks a value that
// does not apply (a boolean algorithm's distance, an untimed query's time, a depth not asked).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/exact/hint.hpp"
#include "gjklab/geometry/enum_names.hpp"
#include "gjklab/geometry/types.hpp"
#include "gjklab/gjk/termination.hpp"
#include "gjklab/gjk/trace.hpp"

namespace gjklab::experiment {

/// How the pair was placed relative to each other.
enum class Placement : std::uint8_t {
  separated,    ///< apart by a drawn gap along an axis
  overlapping,  ///< extents overlap by a drawn depth along an axis
  random,       ///< B's centre uniform in a cube around A's
  touching,     ///< built in exact contact (distance exactly 0), no gap drawn
  as_given,     ///< the pair exactly as read from a cases file
};

/// Which queries keep a per-iteration trace in the archive (only GJK algorithms can be traced).
enum class TraceMode : std::uint8_t {
  none,     ///< no traces, no /traces group
  failing,  ///< the queries whose failure class is not none
  all,      ///< every traceable query
};
inline constexpr auto kTraceModeNames = std::to_array<EnumName<TraceMode>>({
    {TraceMode::none, "none"},
    {TraceMode::failing, "failing"},
    {TraceMode::all, "all"},
});
static_assert(in_value_order(kTraceModeNames) && ends_at(kTraceModeNames, TraceMode::all));
constexpr std::string_view to_string(TraceMode m) {
  return name_of(kTraceModeNames, m);
}
inline std::optional<TraceMode> trace_mode_from_string(std::string_view name) {
  return value_named(kTraceModeNames, name);
}

/// The exact answer's class: separated, within the touching band, or intersecting.
/// The band is |distance| or depth ≤ touching_band · size (see ExperimentConfig).
enum class ContactClass : std::uint8_t { separated, touching_band, intersecting };

/// Why a query counts as failing, most specific first; `none` for a converged query whose
/// boolean is right and whose distance error is within the touching band.
enum class FailureClass : std::uint8_t {
  none,
  touching_band,       ///< the answer differs from the exact one, but the pair is in the band
  step_limit,          ///< stopped by max_iterations
  no_progress,         ///< stopped because ‖v‖ did not decrease
  degenerate_simplex,  ///< the sub-algorithm could not decide
  cycling,             ///< a support point came back
  non_finite,          ///< a NaN or infinity appeared
  wrong_boolean,       ///< converged, yet the boolean is wrong outside the band
  distance_error,      ///< converged, boolean right, distance error above the band
};

/// Which cloud generator made a shape.
enum class ShapeKind : std::uint8_t {
  sphere_points,     ///< points uniform on the unit sphere
  ball_points,       ///< points uniform in the unit ball
  cube_points,       ///< points uniform in the cube [-1, 1]^3
  gaussian,          ///< standard normal cloud
  box,               ///< demo box (8 vertices)
  cone,              ///< demo cone (apex + ring)
  cylinder,          ///< demo cylinder (two rings)
  uv_sphere,         ///< demo UV sphere
  flat_points,       ///< points uniform in the unit disk of the plane z = 0 (exactly coplanar)
  collinear_points,  ///< points uniform on the segment [-1, 1] of the x axis (exactly collinear)
  duplicate_points,  ///< n points drawn from only three distinct points on the unit sphere
  single_point,      ///< one point at the origin, whatever n
  sliver,            ///< box of extents 1 × 1 × 1/aspect (aspect drawn from the family's range)
  prism,             ///< triangular prism with its ridge along y at z = 0 (contact families)
  pyramid,           ///< square pyramid with its apex at the origin (contact families)
  from_file,         ///< a cloud read from a cases file
  mesh,              ///< a mesh: a file's vertices (their hull), or a nonconvex family's solid
  sphere,            ///< sphere-swept point: the origin, swept by the case's radius
  capsule,           ///< sphere-swept segment: (±1, 0, 0), swept by the case's radius
  // Parts of the thin contact families (ContactType::crossing_segments and after).
  segment,  ///< a segment of length 2
  needle,   ///< a triangle of base 2 and height 2/aspect
  rod,      ///< a k-gon prism of length 2 and radius 1/aspect
  wedge,    ///< a triangular prism with a ridge of opening angle 2·atan(1/aspect)
  plate,    ///< a box of extents 2 x 2 x 1/aspect
};

/// Contact configurations of the `contact` families, built from exactly representable
/// coordinates so that the exact distance is 0 before any ε is applied.
enum class ContactType : std::uint8_t {
  none,
  face_face,
  edge_edge,
  vertex_face,
  edge_face,
  vertex_edge,
  vertex_vertex,
  parallel_edges,  ///< two edges at a small angle (not exactly representable)
  // Thin configurations where GJK's sub-simplex solves are ill conditioned: A below the plane
  // z = 0, B above, touching at the origin before the placement moves B along z; the angle θ
  // (family `angle`) and the thinness (family `aspect`) are drawn log-uniformly.
  crossing_segments,  ///< two segments of length 2 crossing at the origin at angle θ
  needle_point,       ///< a needle triangle (aspect) and a point on it
  needle_segment,     ///< a needle triangle and a segment crossing it at angle θ
  thin_rods,          ///< two k-gon rods (k = 3…8, radius 1/aspect) touching, at angle θ
  crossing_wedges,    ///< two sharp wedges (aspect) whose ridges cross, at angle θ or 90°·U
  tilted_plates,      ///< two thin plates (aspect) face to face, B tilted by θ about an edge
};

/// The six contact types built from exactly representable coordinates (distance exactly 0
/// before the placement): the ones `placement.mode = "touching"` and `contact = "any"` use.
constexpr bool exact_contact(ContactType t) {
  return t == ContactType::face_face || t == ContactType::edge_edge ||
         t == ContactType::vertex_face || t == ContactType::edge_face ||
         t == ContactType::vertex_edge || t == ContactType::vertex_vertex;
}

/// The case as generated: everything needed to describe and regenerate it.
struct CaseRecord {
  std::uint64_t case_id = 0;
  std::uint32_t family = 0;  ///< index into the experiment's [[family]] list
  ShapeKind shape_a = ShapeKind::sphere_points;
  ShapeKind shape_b = ShapeKind::sphere_points;
  Placement placement = Placement::random;
  std::int32_t vertices_a = 0;  ///< input cloud sizes
  std::int32_t vertices_b = 0;
  double scale = 1;         ///< the family's scale parameter
  double size = 0;          ///< larger bounding-box diagonal of the two clouds
  double intended_gap = 0;  ///< drawn gap (> 0) or overlap (< 0), relative to size
  /// Sphere-swept shapes: each cloud's hull is swept by a ball of this radius (length units,
  /// world frame); 0 for plain polytopes.
  double radius_a = 0;
  double radius_b = 0;
};

/// The exact oracle's answer for a case.
struct ExactRecord {
  bool intersect = false;
  double distance = 0;              ///< nearest double of the exact distance
  std::string distance2_num = "0";  ///< exact squared distance as a decimal rational
  std::string distance2_den = "1";
  double depth = std::numeric_limits<double>::quiet_NaN();  ///< NaN unless computed
  std::int32_t hull_vertices_a = 0;  ///< −1 when not computed ([oracle] hull_vertices)
  std::int32_t hull_vertices_b = 0;
  ContactClass contact = ContactClass::separated;
  /// How the squared distance was obtained: certified from a hint, or by the QP.
  exact::AnswerMethod method = exact::AnswerMethod::qp;
  /// How the depth was obtained (`none` when it was not computed).
  exact::AnswerMethod depth_method = exact::AnswerMethod::none;
};

/// One algorithm's answer for a case, with its error against the exact answer.
struct AlgorithmRecord {
  bool intersect = false;
  double distance = std::numeric_limits<double>::quiet_NaN();  ///< NaN for boolean algorithms
  /// |distance − exact distance| (length units) and that divided by size; NaN when either
  /// distance is missing.
  double abs_error = std::numeric_limits<double>::quiet_NaN();
  double rel_error = std::numeric_limits<double>::quiet_NaN();
  /// intersect equals the exact intersect (always true inside the touching band, where
  /// either answer is acceptable); true when the oracle is off.
  bool boolean_correct = true;
  std::int32_t iterations = 0;
  std::int32_t support_calls = 0;
  Termination termination = Termination::converged;
  double time_ns = std::numeric_limits<double>::quiet_NaN();  ///< median ns per query, or NaN
  FailureClass failure = FailureClass::none;
  /// Penetration depth reported for an intersecting pair (length units); NaN otherwise.
  double depth = std::numeric_limits<double>::quiet_NaN();
  /// |depth − exact depth| and that divided by size, when both pairs of answers intersect and
  /// the exact depth was computed; NaN otherwise.
  double depth_abs_error = std::numeric_limits<double>::quiet_NaN();
  double depth_rel_error = std::numeric_limits<double>::quiet_NaN();
  /// The witness points the algorithm reported (world frame): closest points of a separated
  /// answer, or the deepest points of a penetration answer; NaN when it reports none.
  Vec3 witness_a = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Vec3 witness_b = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Exact errors of the witnesses (length units, correctly rounded): the distance of each
  /// from its own hull (0 when on or inside it), and for a separated answer
  /// | ‖witness_a − witness_b‖ − exact distance |. NaN without witnesses, without the oracle,
  /// for sphere-swept shapes (witnesses on the swept surfaces), and the last for intersecting
  /// answers.
  double witness_error_a = std::numeric_limits<double>::quiet_NaN();
  double witness_error_b = std::numeric_limits<double>::quiet_NaN();
  double witness_distance_error = std::numeric_limits<double>::quiet_NaN();
  /// For a query in float or long double (the precision option): the exact distance of the
  /// inputs rounded to that precision (nearest double; 0 when the rounded clouds intersect),
  /// so that input rounding (this against the exact distance) and the query's own error (its
  /// distance against this) can be told apart. NaN for queries in double and without the
  /// oracle.
  double rounded_exact_distance = std::numeric_limits<double>::quiet_NaN();
  /// The same for the penetration depth (nearest double) where the rounded clouds intersect;
  /// NaN otherwise.
  double rounded_exact_depth = std::numeric_limits<double>::quiet_NaN();
  /// The query's own proven bracket of the exact distance (GJK distance queries; NaN for the
  /// others): lower_bound ≤ exact distance ≤ upper_bound, and `converged` means it is within
  /// the query's tolerance.
  double lower_bound = std::numeric_limits<double>::quiet_NaN();
  double upper_bound = std::numeric_limits<double>::quiet_NaN();
};

/// One convex piece of a kept non-convex case's decomposition (world frame, the corners as
/// the queries saw them).
struct KeptPiece {
  std::string decomposition;  ///< the decomposition's name
  std::int32_t side = 0;      ///< 0: a piece of A, 1: of B
  std::vector<Vec3> corners;
};

/// Both clouds of a case, kept in the archive when any answer was wrong or not converged. For
/// a non-convex pair the clouds are the meshes' vertices, with their faces and the pieces of
/// every decomposition the algorithms ran on.
struct CaseGeometry {
  std::vector<Vec3> a, b;
  std::vector<std::array<std::uint32_t, 3>> faces_a, faces_b;  ///< empty for convex pairs
  std::vector<KeptPiece> pieces;                               ///< empty for convex pairs
};

/// What the exact truth of a non-convex pair adds to its ExactRecord (exact/mesh_truth.hpp).
struct MeshExactRecord {
  /// How the truth was decided: separated, triangles_meet, a_inside_b or b_inside_a.
  std::string contact = "separated";
  /// The triangles that meet or attain the distance (indices into the faces); −1 for a
  /// containment.
  std::int32_t face_a = -1, face_b = -1;
  /// Triangle pairs evaluated in exact arithmetic (the rest were ruled out by proven bounds).
  std::uint64_t exact_intersection_tests = 0;
  std::uint64_t exact_distance_evaluations = 0;
};

/// What one query on a non-convex pair adds to its AlgorithmRecord.
struct MeshAlgorithmRecord {
  /// The pieces of each side's decomposition; 0 for a mesh peer (it answers the meshes).
  std::int32_t pieces_a = 0, pieces_b = 0;
  std::uint64_t piece_pairs = 0;         ///< pieces_a · pieces_b
  std::uint64_t piece_pairs_tested = 0;  ///< the pairs of pieces the algorithm ran on
  /// The deciding pair of pieces (intersecting, or nearest of those run); −1 when none.
  std::int32_t piece_a = -1, piece_b = -1;
  /// A mesh peer's deciding triangles; −1 when it reports none (and for pieces).
  std::int32_t face_a = -1, face_b = -1;
};

/// The non-convex part of a case's result (nonconvex families only).
struct MeshCaseResult {
  std::optional<MeshExactRecord> exact;         ///< absent when the oracle is off
  std::vector<MeshAlgorithmRecord> algorithms;  ///< in the experiment's algorithm order
};

struct CaseResult {
  CaseRecord record;
  std::optional<ExactRecord> exact;         ///< absent when the oracle is off
  std::vector<AlgorithmRecord> algorithms;  ///< in the experiment's algorithm order
  std::optional<CaseGeometry> geometry;     ///< present for failing or degenerate cases
  /// Pieces, deciding faces and the exact truth's witnesses of a non-convex pair.
  std::optional<MeshCaseResult> mesh;
  /// Per-iteration traces, one list per algorithm (same order), filled by the trace mode of
  /// the experiment; empty lists for untraced queries and algorithms that cannot be traced.
  std::vector<std::vector<GjkIterationTrace>> traces;
};

std::string_view to_string(Placement p);
std::string_view to_string(ContactClass c);
std::string_view to_string(ShapeKind s);
std::string_view to_string(ContactType c);
std::string_view to_string(FailureClass f);

/// The failure class of an algorithm's record (see FailureClass); `band` is the touching band
/// relative to size. Without an exact answer only the termination can fail.
FailureClass classify_failure(const AlgorithmRecord& r, const ExactRecord* exact, double band);

}  // namespace gjklab::experiment
