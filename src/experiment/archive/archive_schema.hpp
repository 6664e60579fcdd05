// The archive's schema as data (private to src/experiment): one table of column descriptors per
// record type. Creating, writing, reading, closing and checkpointing a group all walk its table,
// so a column is named once, here, and results/README.md's tables are checked against it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "gjklab/experiment/cases/records.hpp"
#include "hdf5_util.hpp"

namespace gjklab::experiment {

/// True for the root attributes with a fixed meaning (and every checkpoint_*); any other root
/// attribute is a provenance pair.
bool is_root_attribute(std::string_view name);

}  // namespace gjklab::experiment

namespace gjklab::experiment::schema {

/// One row of /traces/<algorithm>: a GjkIterationTrace flattened to fixed widths (unused
/// simplex slots hold 0 and index −1).
struct TraceRow {
  std::uint64_t case_id = 0;
  std::int32_t iteration = 0;
  GjkStep step = GjkStep::continued;
  Vec3 direction = Vec3::Zero();
  Vec3 support = Vec3::Zero();
  std::int32_t index_a = -1;
  std::int32_t index_b = -1;
  double v_norm_squared = 0;
  double v_dot_w = 0;
  double lower_bound = 0;
  std::int32_t simplex_size = 0;
  std::array<double, 12> simplex{};
  std::array<std::int32_t, 4> simplex_index_a{};
  std::array<std::int32_t, 4> simplex_index_b{};
  std::array<double, 4> weights{};
};
TraceRow flatten(std::uint64_t case_id, const GjkIterationTrace& t);
/// The trace a row describes; the caller has checked simplex_size (0 to 4).
GjkIterationTrace unflatten(const TraceRow& row);

/// One row of /geometry's index: where a kept case's clouds lie in the vertex datasets.
struct GeometryRow {
  std::uint64_t case_id = 0;
  std::uint64_t a_offset = 0;
  std::uint64_t a_count = 0;
  std::uint64_t b_offset = 0;
  std::uint64_t b_count = 0;
};

/// One row of /geometry/vertices_a or vertices_b.
struct VertexRow {
  Vec3 point = Vec3::Zero();
};

/// One row of /meshes/geometry's index: where a kept non-convex case's faces and pieces lie.
struct MeshGeometryRow {
  std::uint64_t case_id = 0;
  std::uint64_t faces_a_offset = 0;
  std::uint64_t faces_a_count = 0;
  std::uint64_t faces_b_offset = 0;
  std::uint64_t faces_b_count = 0;
  std::uint64_t pieces_offset = 0;
  std::uint64_t pieces_count = 0;
};

/// One row of /meshes/faces_a or faces_b.
struct FaceRow {
  std::array<std::uint32_t, 3> face{};
};

/// One row of /meshes/pieces: a kept piece, its corners in /meshes/piece_corners.
struct PieceRow {
  std::string decomposition;
  std::int32_t side = 0;
  std::uint64_t corners_offset = 0;
  std::uint64_t corners_count = 0;
};

/// The record's member a column stores; its type decides the HDF5 type and the row width.
template <class R>
using Field = std::variant<std::uint64_t R::*, std::uint32_t R::*, std::int32_t R::*, double R::*,
                           bool R::*, std::string R::*, Vec3 R::*, std::array<double, 4> R::*,
                           std::array<double, 12> R::*, std::array<std::int32_t, 4> R::*,
                           std::array<std::uint32_t, 3> R::*,
                           ShapeKind R::*, Placement R::*, ContactClass R::*, Termination R::*,
                           FailureClass R::*, GjkStep R::*, exact::AnswerMethod R::*>;

/// Whether archives of this schema version may lack a column.
enum class Presence : std::uint8_t {
  required,
  /// Added after the first archives of the schema version: an archive without the column reads
  /// the record's default value for it.
  optional,
};

/// One column: its dataset's name, the member it stores, what a value means (Markdown, as
/// results/README.md shows it: units and frame first) and whether archives may lack it.
template <class R>
struct ColumnSpec {
  std::string_view name;
  Field<R> field;
  std::string_view meaning;
  Presence presence = Presence::required;
};

inline constexpr auto kCaseColumns = std::to_array<ColumnSpec<CaseRecord>>({
    {"case_id", &CaseRecord::case_id, "the case's id (with the seed, enough to regenerate it)"},
    {"family", &CaseRecord::family, "index into `family_names`"},
    {"shape_a", &CaseRecord::shape_a, "generator of cloud A"},
    {"shape_b", &CaseRecord::shape_b, "generator of cloud B"},
    {"placement", &CaseRecord::placement, "how B was placed relative to A"},
    {"vertices_a", &CaseRecord::vertices_a, "points in cloud A"},
    {"vertices_b", &CaseRecord::vertices_b, "points in cloud B"},
    {"scale", &CaseRecord::scale, "the family's scale (world units)"},
    {"size", &CaseRecord::size,
     "world units: the larger bounding-box diagonal of the clouds (of the swept shapes: each "
     "box grown by its radius on every side)"},
    {"intended_gap", &CaseRecord::intended_gap,
     "relative to `size`: the drawn gap (> 0) or overlap (< 0); NaN when the placement drew "
     "none"},
    // Added with sphere-swept shapes: older archives read radius 0, a plain polytope.
    {"radius_a", &CaseRecord::radius_a,
     "world units: sphere-swept shape A is cloud A's hull swept by a ball of this radius; 0 for "
     "a plain polytope",
     Presence::optional},
    {"radius_b", &CaseRecord::radius_b, "the same for B", Presence::optional},
});

inline constexpr auto kExactColumns = std::to_array<ColumnSpec<ExactRecord>>({
    {"intersect", &ExactRecord::intersect,
     "the convex hulls share at least one point (swept cases: the swept shapes, decided "
     "exactly)"},
    {"distance", &ExactRecord::distance,
     "world units: nearest double of the exact distance (0 when intersecting); swept cases: "
     "√(cores' squared distance) − radius_a − radius_b, correctly rounded from an MPFR "
     "evaluation"},
    {"distance2_num", &ExactRecord::distance2_num,
     "exact squared distance = `distance2_num / distance2_den`, decimal integers of any length; "
     "for sphere-swept cases the squared distance of the cores (the clouds' hulls), since the "
     "swept distance is irrational in general"},
    {"distance2_den", &ExactRecord::distance2_den, "(positive)"},
    {"depth", &ExactRecord::depth,
     "world units: penetration depth; NaN when not computed (separated pairs, or depth not "
     "asked for); swept cases: the swept shapes' depth, correctly rounded"},
    {"hull_vertices_a", &ExactRecord::hull_vertices_a,
     "vertices of the convex hull of A; −1 when not counted (`[oracle] hull_vertices = false`, "
     "the default)"},
    {"hull_vertices_b", &ExactRecord::hull_vertices_b,
     "vertices of the convex hull of B; −1 when not counted"},
    {"contact", &ExactRecord::contact,
     "separated, within the touching band (distance or depth ≤ `touching_band` · `size`), or "
     "intersecting"},
    {"method", &ExactRecord::method,
     "how the squared distance was obtained: `certified` (gjklab's GJK simplex verified "
     "exactly, see below) or `qp` (CGAL's `Polytope_distance_d`); both give the same rational"},
    {"depth_method", &ExactRecord::depth_method,
     "how the depth was obtained: `certified` (EPA's polytope verified exactly), `qp` (the "
     "exact hull of the Minkowski difference) or `none` (not computed)"},
});

inline constexpr auto kAlgorithmColumns = std::to_array<ColumnSpec<AlgorithmRecord>>({
    {"intersect", &AlgorithmRecord::intersect, "the algorithm's boolean answer"},
    {"distance", &AlgorithmRecord::distance, "world units; NaN for boolean-only algorithms"},
    {"abs_error", &AlgorithmRecord::abs_error,
     "world units: \\|distance − exact distance\\|; NaN when either is missing"},
    {"rel_error", &AlgorithmRecord::rel_error,
     "`abs_error / size`; NaN when either distance is missing"},
    {"boolean_correct", &AlgorithmRecord::boolean_correct,
     "`intersect` equals the exact one (always true inside the touching band, and when the "
     "oracle is off)"},
    {"iterations", &AlgorithmRecord::iterations, "iterations used"},
    {"support_calls", &AlgorithmRecord::support_calls, "support-function evaluations used"},
    {"termination", &AlgorithmRecord::termination, "why it stopped"},
    {"time_ns", &AlgorithmRecord::time_ns,
     "nanoseconds: median time per query; NaN when not timed"},
    {"failure", &AlgorithmRecord::failure,
     "why the query counts as failing (`none` when it does not)"},
    {"depth", &AlgorithmRecord::depth,
     "world units: the penetration depth a depth algorithm reported for an intersecting pair; "
     "NaN otherwise"},
    {"depth_abs_error", &AlgorithmRecord::depth_abs_error,
     "world units: \\|depth − exact depth\\| when both say intersecting and the exact depth was "
     "computed (always, when the experiment lists a depth algorithm); NaN otherwise"},
    {"depth_rel_error", &AlgorithmRecord::depth_rel_error, "`depth_abs_error / size`"},
    {"witness_a", &AlgorithmRecord::witness_a,
     "world frame: the point of A the algorithm reported (closest point of a separated answer, "
     "deepest point of a penetration answer); NaN rows when it reports none"},
    {"witness_b", &AlgorithmRecord::witness_b, "the same for B"},
    {"witness_error_a", &AlgorithmRecord::witness_error_a,
     "world units: the exact distance of `witness_a` from the hull of A (0 on or inside it), "
     "correctly rounded; NaN without witnesses or oracle, and for sphere-swept cases"},
    {"witness_error_b", &AlgorithmRecord::witness_error_b, "the same for `witness_b` and B"},
    {"witness_distance_error", &AlgorithmRecord::witness_distance_error,
     "world units: \\| ‖witness_a − witness_b‖ − exact distance \\|, correctly rounded (MPFR); "
     "NaN as above and for intersecting answers"},
    // Added with the precision option: older archives read NaN (the query ran in double).
    {"rounded_exact_distance", &AlgorithmRecord::rounded_exact_distance,
     "world units: for a GJK query run in float or long double (its `precision` option), the "
     "exact distance of the clouds and radii rounded to that precision (nearest double; 0 when "
     "they intersect), so input rounding (this against `exact/distance`) and the query's own "
     "error (its `distance` against this) can be told apart; NaN for queries in double and "
     "without the oracle. Archives from before the option lack the column (read as NaN)",
     Presence::optional},
    {"rounded_exact_depth", &AlgorithmRecord::rounded_exact_depth,
     "world units: the same for the penetration depth, where the rounded clouds intersect; NaN "
     "otherwise",
     Presence::optional},
    // Added with the proven stopping test: older archives read NaN.
    {"lower_bound", &AlgorithmRecord::lower_bound,
     "world units: the GJK distance query's proven lower bound of the exact distance (a support "
     "plane with its rounding accounted for); NaN for other algorithms and older archives",
     Presence::optional},
    {"upper_bound", &AlgorithmRecord::upper_bound,
     "world units: its proven upper bound (a point of the simplex with its rounding accounted "
     "for; infinite where none could be proven); `termination` is `converged` exactly when "
     "`upper_bound − lower_bound` is within the query's tolerance",
     Presence::optional},
});

inline constexpr auto kGeometryColumns = std::to_array<ColumnSpec<GeometryRow>>({
    {"case_id", &GeometryRow::case_id, "the case (a value of `/cases/case_id`)"},
    {"a_offset", &GeometryRow::a_offset, "first row of cloud A in `vertices_a`"},
    {"a_count", &GeometryRow::a_count, "its number of points"},
    {"b_offset", &GeometryRow::b_offset, "first row of cloud B in `vertices_b`"},
    {"b_count", &GeometryRow::b_count, "its number of points"},
});

inline constexpr auto kVerticesAColumns = std::to_array<ColumnSpec<VertexRow>>({
    {"vertices_a", &VertexRow::point, "x, y, z of the points of every kept cloud A (world units)"},
});
inline constexpr auto kVerticesBColumns = std::to_array<ColumnSpec<VertexRow>>({
    {"vertices_b", &VertexRow::point, "the same for the clouds B"},
});

inline constexpr auto kTraceColumns = std::to_array<ColumnSpec<TraceRow>>({
    {"case_id", &TraceRow::case_id, "the case"},
    {"iteration", &TraceRow::iteration, "1, 2, … within the query"},
    {"step", &TraceRow::step,
     "which branch fired: `continued`, `gap_converged`, `repeated_support`, `contact`, "
     "`separated`, `degenerate`, `no_progress`, `non_finite`, `step_limit`, "
     "`momentum_restart`, `stalled` (a step whose certified decrease of ‖v‖ rounding hid, "
     "taken anyway, at most 4 in a row), `cycled` (gjk-bool came back to an earlier state; the "
     "distance walk's rows follow)"},
    {"direction", &TraceRow::direction, "the search direction"},
    {"support", &TraceRow::support, "the support point w = a − b taken"},
    {"index_a", &TraceRow::index_a, "index of a in cloud A (−1 when unknown)"},
    {"index_b", &TraceRow::index_b, "index of b in cloud B (−1 when unknown)"},
    {"v_norm_squared", &TraceRow::v_norm_squared,
     "‖v‖² before the step (distance queries); ‖d‖² for gjk-bool's walk"},
    {"v_dot_w", &TraceRow::v_dot_w,
     "v·w; for gjk-bool's walk d·w, its separation test (separated when < 0)"},
    {"lower_bound", &TraceRow::lower_bound, "best lower bound of the distance so far"},
    {"simplex_size", &TraceRow::simplex_size, "points in the simplex after the step (0–4)"},
    {"simplex", &TraceRow::simplex, "the simplex points w (x, y, z each; unused slots 0)"},
    {"simplex_index_a", &TraceRow::simplex_index_a, "their indices in A (−1 unused)"},
    {"simplex_index_b", &TraceRow::simplex_index_b, "their indices in B (−1 unused)"},
    {"weights", &TraceRow::weights, "barycentric weights of the simplex points (distance queries)"},
});

// ---- /meshes: what non-convex pairs add (archives of nonconvex families only) ----

inline constexpr auto kMeshExactColumns = std::to_array<ColumnSpec<MeshExactRecord>>({
    {"contact", &MeshExactRecord::contact,
     "how the solids' truth was decided: `separated`, `triangles_meet`, `a_inside_b` or "
     "`b_inside_a` (one surface inside the other solid, no triangles meeting)"},
    {"face_a", &MeshExactRecord::face_a,
     "the triangle of A (index into its faces) that meets B's or attains the distance; −1 for "
     "a containment"},
    {"face_b", &MeshExactRecord::face_b, "the same for B"},
    {"exact_intersection_tests", &MeshExactRecord::exact_intersection_tests,
     "triangle pairs tested for intersection in exact arithmetic (the others were ruled out "
     "by their boxes)"},
    {"exact_distance_evaluations", &MeshExactRecord::exact_distance_evaluations,
     "triangle pairs whose squared distance was evaluated exactly (the others were ruled out "
     "by proven floating-point lower bounds)"},
});

inline constexpr auto kMeshAlgorithmColumns = std::to_array<ColumnSpec<MeshAlgorithmRecord>>({
    {"pieces_a", &MeshAlgorithmRecord::pieces_a,
     "convex pieces of A under the algorithm's decomposition; 0 for a mesh peer"},
    {"pieces_b", &MeshAlgorithmRecord::pieces_b, "the same for B"},
    {"piece_pairs", &MeshAlgorithmRecord::piece_pairs, "`pieces_a · pieces_b`"},
    {"piece_pairs_tested", &MeshAlgorithmRecord::piece_pairs_tested,
     "pairs of pieces the algorithm ran on (the others' boxes ruled them out)"},
    {"piece_a", &MeshAlgorithmRecord::piece_a,
     "the deciding piece of A (intersecting, or nearest of those run); −1 when none"},
    {"piece_b", &MeshAlgorithmRecord::piece_b, "the same for B"},
    {"face_a", &MeshAlgorithmRecord::face_a,
     "a mesh peer's deciding triangle of A; −1 when it reports none, and for pieces"},
    {"face_b", &MeshAlgorithmRecord::face_b, "the same for B"},
});

inline constexpr auto kMeshGeometryColumns = std::to_array<ColumnSpec<MeshGeometryRow>>({
    {"case_id", &MeshGeometryRow::case_id,
     "a kept case (its vertices are its clouds in `/geometry`)"},
    {"faces_a_offset", &MeshGeometryRow::faces_a_offset, "first row of mesh A in `faces_a`"},
    {"faces_a_count", &MeshGeometryRow::faces_a_count, "its number of triangles"},
    {"faces_b_offset", &MeshGeometryRow::faces_b_offset, "first row of mesh B in `faces_b`"},
    {"faces_b_count", &MeshGeometryRow::faces_b_count, "its number of triangles"},
    {"pieces_offset", &MeshGeometryRow::pieces_offset, "first row of its pieces in `pieces`"},
    {"pieces_count", &MeshGeometryRow::pieces_count,
     "its pieces, of every decomposition its algorithms ran on"},
});
inline constexpr auto kFacesAColumns = std::to_array<ColumnSpec<FaceRow>>({
    {"faces_a", &FaceRow::face,
     "triangles of every kept mesh A: indices into its vertices in `/geometry/vertices_a`, "
     "counter-clockwise seen from outside"},
});
inline constexpr auto kFacesBColumns = std::to_array<ColumnSpec<FaceRow>>({
    {"faces_b", &FaceRow::face, "the same for the meshes B"},
});
inline constexpr auto kPieceColumns = std::to_array<ColumnSpec<PieceRow>>({
    {"decomposition", &PieceRow::decomposition, "the decomposition the piece is of"},
    {"side", &PieceRow::side, "0: a piece of A, 1: of B"},
    {"corners_offset", &PieceRow::corners_offset,
     "first row of its corners in `piece_corners` (the piece is their convex hull)"},
    {"corners_count", &PieceRow::corners_count, "its number of corners"},
});
inline constexpr auto kPieceCornerColumns = std::to_array<ColumnSpec<VertexRow>>({
    {"piece_corners", &VertexRow::point, "x, y, z of the pieces' corners (world units)"},
});

// ---- root attributes ----

/// The prefix of the root attributes that hold a table's rows at the last checkpoint.
inline constexpr std::string_view kCheckpointPrefix = "checkpoint_";

/// The root attributes that count each table's rows at the last checkpoint (checkpoint_…).
namespace checkpoint {
inline constexpr std::string_view cases = "checkpoint_cases";
inline constexpr std::string_view geometry = "checkpoint_geometry";
inline constexpr std::string_view vertices_a = "checkpoint_vertices_a";
inline constexpr std::string_view vertices_b = "checkpoint_vertices_b";
inline constexpr std::string_view mesh_geometry = "checkpoint_mesh_geometry";
inline constexpr std::string_view mesh_faces_a = "checkpoint_mesh_faces_a";
inline constexpr std::string_view mesh_faces_b = "checkpoint_mesh_faces_b";
inline constexpr std::string_view mesh_pieces = "checkpoint_mesh_pieces";
inline constexpr std::string_view mesh_piece_corners = "checkpoint_mesh_piece_corners";
/// The traces of the header's algorithm number `algorithm`.
std::string traces(std::size_t algorithm);
}  // namespace checkpoint

/// The root attributes the writer writes itself, outside the header, as the run goes.
namespace attribute {
inline constexpr std::string_view schema_version = "schema_version";
inline constexpr std::string_view end_time = "end_time";
inline constexpr std::string_view complete = "complete";
}  // namespace attribute

/// The header member a root attribute stores; std::monostate for the attributes the writer
/// writes itself (the schema version first, checkpoints as they come, end time and flag last).
using HeaderField =
    std::variant<std::monostate, std::string ArchiveHeader::*, std::uint64_t ArchiveHeader::*,
                 bool ArchiveHeader::*, double ArchiveHeader::*,
                 std::vector<std::string> ArchiveHeader::*, TraceMode ArchiveHeader::*>;

/// One root attribute, as ColumnSpec is one column. `type` names the type of an attribute
/// without a header member; a header attribute's follows from its member. A name ending in
/// '*' stands for every attribute it begins.
struct RootAttributeSpec {
  std::string_view name;
  HeaderField field;
  std::string_view meaning;
  Presence presence = Presence::required;
  std::string_view type = {};
};

/// Every root attribute with a fixed meaning, in the order a run creates them (any other root
/// attribute is a provenance pair; the pairs follow schema_version).
inline constexpr auto kRootAttributes = std::to_array<RootAttributeSpec>({
    {.name = attribute::schema_version,
     .meaning = "2 for this layout (2 added `exact/method`, `exact/depth_method` and the "
                "algorithms' witness columns)",
     .type = "int32"},
    {.name = "experiment_name",
     .field = &ArchiveHeader::experiment_name,
     .meaning = "the experiment's name"},
    {.name = "experiment_text",
     .field = &ArchiveHeader::experiment_text,
     .meaning = "the experiment file, whole (TOML)"},
    {.name = "seed", .field = &ArchiveHeader::seed, .meaning = "the run's seed"},
    {.name = "cases_planned",
     .field = &ArchiveHeader::cases_planned,
     .meaning = "cases the run set out to do (N is less if it stopped)"},
    {.name = "start_time", .field = &ArchiveHeader::start_time, .meaning = "ISO 8601, UTC"},
    {.name = "oracle",
     .field = &ArchiveHeader::oracle,
     .meaning = "1: the exact oracle ran and `/exact` exists"},
    {.name = "touching_band",
     .field = &ArchiveHeader::touching_band,
     .meaning = "relative band of the `touching_band` contact class"},
    {.name = "family_names",
     .field = &ArchiveHeader::family_names,
     .meaning = "`/cases/family` indexes it"},
    {.name = "algorithm_names",
     .field = &ArchiveHeader::algorithm_names,
     .meaning = "the algorithms, in the experiment's order (= group names)"},
    // Added with traces: older archives read "none".
    {.name = "trace_mode",
     .field = &ArchiveHeader::trace_mode,
     .meaning = "`none`, `failing` or `all`: which queries have `/traces` rows",
     .presence = Presence::optional},
    {.name = "checkpoint_*",
     .meaning = "rows of each group at the last checkpoint (see above)",
     .type = "uint64 each"},
    {.name = attribute::end_time,
     .meaning = "ISO 8601, UTC; absent if the run never finished",
     .presence = Presence::optional,
     .type = "string"},
    {.name = attribute::complete,
     .meaning = "written last; see above",
     .presence = Presence::optional,
     .type = "uint8 (0/1)"},
});

// ---- how a member type is stored ----

/// The HDF5 types the archive creates (the fixed ones are HDF5's predefined types).
struct Types {
  h5::Handle boolean, string, shape, placement, contact, termination, failure, step, method;
  explicit Types(const h5::Context& cx);

  /// The enum type of E.
  template <class E>
  hid_t of() const;
};

/// How a member of type T is stored: the element type in memory (`Element`), values a row
/// (`width`), the HDF5 file and memory types, the type as results/README.md names it, and
/// how one value goes into a row buffer and back. Specialised below for every Field type.
template <class T>
struct Storage;

template <class T>
struct ScalarStorage {
  using Element = T;
  static constexpr std::size_t width = 1;
  static void put(const T& v, std::vector<Element>& out) { out.push_back(v); }
  static T get(const std::vector<Element>& in, std::size_t row) { return in[row]; }
};

template <>
struct Storage<std::uint64_t> : ScalarStorage<std::uint64_t> {
  static constexpr std::string_view name = "uint64";
  static hid_t file(const Types&) { return H5T_STD_U64LE; }
  static hid_t memory(const Types&) { return H5T_NATIVE_UINT64; }
};
template <>
struct Storage<std::uint32_t> : ScalarStorage<std::uint32_t> {
  static constexpr std::string_view name = "uint32";
  static hid_t file(const Types&) { return H5T_STD_U32LE; }
  static hid_t memory(const Types&) { return H5T_NATIVE_UINT32; }
};
template <>
struct Storage<std::int32_t> : ScalarStorage<std::int32_t> {
  static constexpr std::string_view name = "int32";
  static hid_t file(const Types&) { return H5T_STD_I32LE; }
  static hid_t memory(const Types&) { return H5T_NATIVE_INT32; }
};
template <>
struct Storage<double> : ScalarStorage<double> {
  static constexpr std::string_view name = "float64";
  static hid_t file(const Types&) { return H5T_IEEE_F64LE; }
  static hid_t memory(const Types&) { return H5T_NATIVE_DOUBLE; }
};

/// bool as the int8 enum {FALSE, TRUE} that h5py and numpy read as bool.
template <>
struct Storage<bool> {
  using Element = std::int8_t;
  static constexpr std::size_t width = 1;
  static constexpr std::string_view name = "bool";
  static hid_t file(const Types& t) { return t.boolean.get(); }
  static hid_t memory(const Types& t) { return t.boolean.get(); }
  static void put(bool v, std::vector<Element>& out) { out.push_back(v ? 1 : 0); }
  static bool get(const std::vector<Element>& in, std::size_t row) { return in[row] != 0; }
};

/// Strings are written as pointers into the records (alive for the write) and read back as
/// std::string (h5::read_string_column).
template <>
struct Storage<std::string> {
  using Element = const char*;
  static constexpr std::size_t width = 1;
  static constexpr std::string_view name = "string";
  static hid_t file(const Types& t) { return t.string.get(); }
  static hid_t memory(const Types& t) { return t.string.get(); }
  static void put(const std::string& v, std::vector<Element>& out) { out.push_back(v.c_str()); }
};

/// Fixed-width rows of doubles or int32s: a Vec3 or a std::array.
template <class Scalar, std::size_t N>
struct RowStorage {
  using Element = Scalar;
  static constexpr std::size_t width = N;
  static hid_t file(const Types& t) { return Storage<Scalar>::file(t); }
  static hid_t memory(const Types& t) { return Storage<Scalar>::memory(t); }
  template <class T>
  static void put(const T& v, std::vector<Element>& out) {
    for (std::size_t i = 0; i < N; ++i)
      out.push_back(v[i]);
  }
  template <class T>
  static void fill(const std::vector<Element>& in, std::size_t row, T& v) {
    for (std::size_t i = 0; i < N; ++i)
      v[i] = in[N * row + i];
  }
};

template <>
struct Storage<Vec3> : RowStorage<double, 3> {
  static Vec3 get(const std::vector<Element>& in, std::size_t row) {
    return Vec3(in[3 * row], in[3 * row + 1], in[3 * row + 2]);
  }
};
template <class Scalar, std::size_t N>
struct Storage<std::array<Scalar, N>> : RowStorage<Scalar, N> {
  static std::array<Scalar, N> get(const std::vector<Scalar>& in, std::size_t row) {
    std::array<Scalar, N> v{};
    RowStorage<Scalar, N>::fill(in, row, v);
    return v;
  }
};

/// Enums as HDF5 enum types over uint8 whose members are the enum's names.
template <class E>
requires std::is_enum_v<E>
struct Storage<E> : ScalarStorage<E> {
  static hid_t file(const Types& t) { return t.of<E>(); }
  static hid_t memory(const Types& t) { return t.of<E>(); }
};

/// Every enum type the archive stores, in the order results/README.md lists their values.
template <class... E>
struct EnumList {};
using ArchiveEnums = EnumList<ShapeKind, Placement, ContactClass, Termination, FailureClass,
                              GjkStep, exact::AnswerMethod>;

/// The name results/README.md gives an enum type.
template <class E>
constexpr std::string_view enum_type_name() {
  if constexpr (std::is_same_v<E, ShapeKind>) return "ShapeKind";
  if constexpr (std::is_same_v<E, Placement>) return "Placement";
  if constexpr (std::is_same_v<E, ContactClass>) return "ContactClass";
  if constexpr (std::is_same_v<E, Termination>) return "Termination";
  if constexpr (std::is_same_v<E, FailureClass>) return "FailureClass";
  if constexpr (std::is_same_v<E, GjkStep>) return "GjkStep";
  if constexpr (std::is_same_v<E, exact::AnswerMethod>) return "AnswerMethod";
}

template <class E>
hid_t Types::of() const {
  if constexpr (std::is_same_v<E, ShapeKind>) return shape.get();
  if constexpr (std::is_same_v<E, Placement>) return placement.get();
  if constexpr (std::is_same_v<E, ContactClass>) return contact.get();
  if constexpr (std::is_same_v<E, Termination>) return termination.get();
  if constexpr (std::is_same_v<E, FailureClass>) return failure.get();
  if constexpr (std::is_same_v<E, GjkStep>) return step.get();
  if constexpr (std::is_same_v<E, exact::AnswerMethod>) return method.get();
}

/// The member type a Field points to.
template <class M>
struct MemberType;
template <class R, class T>
struct MemberType<T R::*> {
  using type = T;
};

/// The column's type as results/README.md writes it: "float64", "enum `Termination`",
/// "float64 (rows × 3)".
template <class R>
std::string type_name(const ColumnSpec<R>& spec) {
  return std::visit(
      [](auto member) {
        using T = typename MemberType<decltype(member)>::type;
        using S = Storage<T>;
        std::string name;
        if constexpr (std::is_enum_v<T>)
          name = "enum `" + std::string(enum_type_name<T>()) + "`";
        else if constexpr (S::width == 1)
          name = S::name;
        else
          name = std::string(Storage<typename S::Element>::name) + " (rows × " +
                 std::to_string(S::width) + ")";
        return name;
      },
      spec.field);
}

/// The attribute's type as results/README.md writes it: "uint64", "string array", …
std::string_view type_name(const RootAttributeSpec& spec);

/// Writes the header's attributes, in the table's order.
void write_header_attributes(const h5::Context& cx, hid_t root, const ArchiveHeader& h);
/// Reads the header's attributes; an optional one the file lacks keeps h's value.
void read_header_attributes(const h5::Context& cx, hid_t root, ArchiveHeader& h);

}  // namespace gjklab::experiment::schema
