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
#include <variant>
#include <vector>

#include "gjklab/experiment/records.hpp"
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

/// The record's member a column stores; its type decides the HDF5 type and the row width.
template <class R>
using Field = std::variant<std::uint64_t R::*, std::uint32_t R::*, std::int32_t R::*, double R::*,
                           bool R::*, std::string R::*, Vec3 R::*, std::array<double, 4> R::*,
                           std::array<double, 12> R::*, std::array<std::int32_t, 4> R::*,
                           ShapeKind R::*, Placement R::*, ContactClass R::*, Termination R::*,
                           FailureClass R::*, GjkStep R::*, exact::AnswerMethod R::*>;

/// Whether archives of this schema version may lack a column.
enum class Presence : std::uint8_t {
  required,
  /// Added after the first archives of the schema version: an archive without the column reads
  /// the record's default value for it.
  optional,
};

template <class R>
struct ColumnSpec {
  std::string_view name;
  Field<R> field;
  Presence presence = Presence::required;
};

inline constexpr auto kCaseColumns = std::to_array<ColumnSpec<CaseRecord>>({
    {"case_id", &CaseRecord::case_id},
    {"family", &CaseRecord::family},
    {"shape_a", &CaseRecord::shape_a},
    {"shape_b", &CaseRecord::shape_b},
    {"placement", &CaseRecord::placement},
    {"vertices_a", &CaseRecord::vertices_a},
    {"vertices_b", &CaseRecord::vertices_b},
    {"scale", &CaseRecord::scale},
    {"size", &CaseRecord::size},
    {"intended_gap", &CaseRecord::intended_gap},
    // Added with sphere-swept shapes: older archives read radius 0, a plain polytope.
    {"radius_a", &CaseRecord::radius_a, Presence::optional},
    {"radius_b", &CaseRecord::radius_b, Presence::optional},
});

inline constexpr auto kExactColumns = std::to_array<ColumnSpec<ExactRecord>>({
    {"intersect", &ExactRecord::intersect},
    {"distance", &ExactRecord::distance},
    {"distance2_num", &ExactRecord::distance2_num},
    {"distance2_den", &ExactRecord::distance2_den},
    {"depth", &ExactRecord::depth},
    {"hull_vertices_a", &ExactRecord::hull_vertices_a},
    {"hull_vertices_b", &ExactRecord::hull_vertices_b},
    {"contact", &ExactRecord::contact},
    {"method", &ExactRecord::method},
    {"depth_method", &ExactRecord::depth_method},
});

inline constexpr auto kAlgorithmColumns = std::to_array<ColumnSpec<AlgorithmRecord>>({
    {"intersect", &AlgorithmRecord::intersect},
    {"distance", &AlgorithmRecord::distance},
    {"abs_error", &AlgorithmRecord::abs_error},
    {"rel_error", &AlgorithmRecord::rel_error},
    {"boolean_correct", &AlgorithmRecord::boolean_correct},
    {"iterations", &AlgorithmRecord::iterations},
    {"support_calls", &AlgorithmRecord::support_calls},
    {"termination", &AlgorithmRecord::termination},
    {"time_ns", &AlgorithmRecord::time_ns},
    {"failure", &AlgorithmRecord::failure},
    {"depth", &AlgorithmRecord::depth},
    {"depth_abs_error", &AlgorithmRecord::depth_abs_error},
    {"depth_rel_error", &AlgorithmRecord::depth_rel_error},
    {"witness_a", &AlgorithmRecord::witness_a},
    {"witness_b", &AlgorithmRecord::witness_b},
    {"witness_error_a", &AlgorithmRecord::witness_error_a},
    {"witness_error_b", &AlgorithmRecord::witness_error_b},
    {"witness_distance_error", &AlgorithmRecord::witness_distance_error},
    // Added with the precision option: older archives read NaN (the query ran in double).
    {"rounded_exact_distance", &AlgorithmRecord::rounded_exact_distance, Presence::optional},
    {"rounded_exact_depth", &AlgorithmRecord::rounded_exact_depth, Presence::optional},
});

inline constexpr auto kGeometryColumns = std::to_array<ColumnSpec<GeometryRow>>({
    {"case_id", &GeometryRow::case_id},
    {"a_offset", &GeometryRow::a_offset},
    {"a_count", &GeometryRow::a_count},
    {"b_offset", &GeometryRow::b_offset},
    {"b_count", &GeometryRow::b_count},
});

inline constexpr auto kVerticesAColumns = std::to_array<ColumnSpec<VertexRow>>({
    {"vertices_a", &VertexRow::point},
});
inline constexpr auto kVerticesBColumns = std::to_array<ColumnSpec<VertexRow>>({
    {"vertices_b", &VertexRow::point},
});

inline constexpr auto kTraceColumns = std::to_array<ColumnSpec<TraceRow>>({
    {"case_id", &TraceRow::case_id},
    {"iteration", &TraceRow::iteration},
    {"step", &TraceRow::step},
    {"direction", &TraceRow::direction},
    {"support", &TraceRow::support},
    {"index_a", &TraceRow::index_a},
    {"index_b", &TraceRow::index_b},
    {"v_norm_squared", &TraceRow::v_norm_squared},
    {"v_dot_w", &TraceRow::v_dot_w},
    {"lower_bound", &TraceRow::lower_bound},
    {"simplex_size", &TraceRow::simplex_size},
    {"simplex", &TraceRow::simplex},
    {"simplex_index_a", &TraceRow::simplex_index_a},
    {"simplex_index_b", &TraceRow::simplex_index_b},
    {"weights", &TraceRow::weights},
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

}  // namespace gjklab::experiment::schema
