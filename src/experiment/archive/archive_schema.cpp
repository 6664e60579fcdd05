// The parts of the archive schema the writer and the reader share: the HDF5 types, the trace
// rows, the root attributes, and the tables results/README.md documents.

#include "archive_schema.hpp"

#include <algorithm>

namespace gjklab::experiment {

namespace schema {

Types::Types(const h5::Context& cx)
    : boolean(h5::bool_type(cx)),
      string(h5::string_type(cx)),
      shape(h5::enum_type<ShapeKind>(cx)),
      placement(h5::enum_type<Placement>(cx)),
      contact(h5::enum_type<ContactClass>(cx)),
      termination(h5::enum_type<Termination>(cx)),
      failure(h5::enum_type<FailureClass>(cx)),
      step(h5::enum_type<GjkStep>(cx)),
      method(h5::enum_type<exact::AnswerMethod>(cx)) {}

TraceRow flatten(std::uint64_t case_id, const GjkIterationTrace& t) {
  TraceRow row;
  row.case_id = case_id;
  row.iteration = t.iteration;
  row.step = t.step;
  row.direction = t.direction;
  row.support = t.support.w;
  row.index_a = t.support.index_a;
  row.index_b = t.support.index_b;
  row.v_norm_squared = t.v_norm_squared;
  row.v_dot_w = t.v_dot_w;
  row.lower_bound = t.lower_bound;
  row.simplex_size = t.simplex.size();
  for (int i = 0; i < 4; ++i) {
    const bool in = i < t.simplex.size();
    const Vec3 p = in ? t.simplex[i].w : Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      row.simplex[3 * i + k] = p[k];
    row.simplex_index_a[i] = in ? t.simplex[i].index_a : -1;
    row.simplex_index_b[i] = in ? t.simplex[i].index_b : -1;
    row.weights[i] = in ? t.weights[i] : 0.0;
  }
  return row;
}

GjkIterationTrace unflatten(const TraceRow& row) {
  GjkIterationTrace t;
  t.iteration = row.iteration;
  t.step = row.step;
  t.direction = row.direction;
  t.support.w = row.support;
  t.support.index_a = row.index_a;
  t.support.index_b = row.index_b;
  t.v_norm_squared = row.v_norm_squared;
  t.v_dot_w = row.v_dot_w;
  t.lower_bound = row.lower_bound;
  for (int i = 0; i < row.simplex_size; ++i) {
    SimplexVertex v;
    v.w = Vec3(row.simplex[3 * i], row.simplex[3 * i + 1], row.simplex[3 * i + 2]);
    v.index_a = row.simplex_index_a[i];
    v.index_b = row.simplex_index_b[i];
    t.simplex.push(v);
    t.weights[i] = row.weights[i];
  }
  return t;
}

std::string checkpoint::traces(std::size_t algorithm) {
  return std::string(kCheckpointPrefix) + "traces_" + std::to_string(algorithm);
}

namespace {

/// How a header member of type T is stored as a root attribute, and its type's name there.
template <class T>
struct AttributeStorage;

template <>
struct AttributeStorage<std::string> {
  static constexpr std::string_view name = "string";
  static void write(const h5::Context& cx, hid_t root, const std::string& key,
                    const std::string& v) {
    h5::write_attr_string(cx, root, "/", key, v);
  }
  static std::string read(const h5::Context& cx, hid_t root, const std::string& key) {
    return h5::read_attr_string(cx, root, "/", key);
  }
};
template <>
struct AttributeStorage<std::uint64_t> {
  static constexpr std::string_view name = "uint64";
  static void write(const h5::Context& cx, hid_t root, const std::string& key, std::uint64_t v) {
    h5::write_attr_u64(cx, root, "/", key, v);
  }
  static std::uint64_t read(const h5::Context& cx, hid_t root, const std::string& key) {
    return h5::read_attr_u64(cx, root, "/", key);
  }
};
/// bool as uint8 0 or 1.
template <>
struct AttributeStorage<bool> {
  static constexpr std::string_view name = "uint8 (0/1)";
  static void write(const h5::Context& cx, hid_t root, const std::string& key, bool v) {
    h5::write_attr_u8(cx, root, "/", key, v ? 1 : 0);
  }
  static bool read(const h5::Context& cx, hid_t root, const std::string& key) {
    return h5::read_attr_u8(cx, root, "/", key) != 0;
  }
};
template <>
struct AttributeStorage<double> {
  static constexpr std::string_view name = "float64";
  static void write(const h5::Context& cx, hid_t root, const std::string& key, double v) {
    h5::write_attr_f64(cx, root, "/", key, v);
  }
  static double read(const h5::Context& cx, hid_t root, const std::string& key) {
    return h5::read_attr_f64(cx, root, "/", key);
  }
};
template <>
struct AttributeStorage<std::vector<std::string>> {
  static constexpr std::string_view name = "string array";
  static void write(const h5::Context& cx, hid_t root, const std::string& key,
                    const std::vector<std::string>& v) {
    h5::write_attr_strings(cx, root, "/", key, v);
  }
  static std::vector<std::string> read(const h5::Context& cx, hid_t root, const std::string& key) {
    return h5::read_attr_strings(cx, root, "/", key);
  }
};

/// TraceMode by its name; a name the table lacks is an error naming the attribute.
template <>
struct AttributeStorage<TraceMode> {
  static constexpr std::string_view name = "string";
  static void write(const h5::Context& cx, hid_t root, const std::string& key, TraceMode v) {
    h5::write_attr_string(cx, root, "/", key, std::string(to_string(v)));
  }
  static TraceMode read(const h5::Context& cx, hid_t root, const std::string& key) {
    const std::string text = h5::read_attr_string(cx, root, "/", key);
    const auto mode = trace_mode_from_string(text);
    if (!mode)
      cx.error("attribute '" + key + "' of / is '" + text + "', not one of " +
               names_list(kTraceModeNames));
    return *mode;
  }
};

}  // namespace

std::string_view type_name(const RootAttributeSpec& spec) {
  return std::visit(
      [&spec](auto member) -> std::string_view {
        if constexpr (std::is_same_v<decltype(member), std::monostate>)
          return spec.type;
        else
          return AttributeStorage<typename MemberType<decltype(member)>::type>::name;
      },
      spec.field);
}

void write_header_attributes(const h5::Context& cx, hid_t root, const ArchiveHeader& h) {
  for (const RootAttributeSpec& spec : kRootAttributes)
    std::visit(
        [&](auto member) {
          if constexpr (!std::is_same_v<decltype(member), std::monostate>) {
            using S = AttributeStorage<typename MemberType<decltype(member)>::type>;
            S::write(cx, root, std::string(spec.name), h.*member);
          }
        },
        spec.field);
}

void read_header_attributes(const h5::Context& cx, hid_t root, ArchiveHeader& h) {
  for (const RootAttributeSpec& spec : kRootAttributes) {
    const std::string name(spec.name);
    if (spec.presence == Presence::optional && !h5::has_attr(cx, root, "/", name)) continue;
    std::visit(
        [&](auto member) {
          if constexpr (!std::is_same_v<decltype(member), std::monostate>) {
            using S = AttributeStorage<typename MemberType<decltype(member)>::type>;
            h.*member = S::read(cx, root, name);
          }
        },
        spec.field);
  }
}

}  // namespace schema

namespace {

template <class R, std::size_t N>
void describe(const std::array<schema::ColumnSpec<R>, N>& specs, std::vector<ArchiveColumn>& out) {
  for (const auto& spec : specs)
    out.push_back({std::string(spec.name), schema::type_name(spec), std::string(spec.meaning)});
}

}  // namespace

// The checkpoint attributes are root attributes by the table's pattern row.
static_assert(std::ranges::any_of(schema::kRootAttributes, [](const auto& spec) {
  return spec.name.ends_with('*') &&
         spec.name.substr(0, spec.name.size() - 1) == schema::kCheckpointPrefix;
}));

bool is_root_attribute(std::string_view name) {
  for (const schema::RootAttributeSpec& spec : schema::kRootAttributes) {
    const bool pattern = spec.name.ends_with('*');
    if (pattern ? name.starts_with(spec.name.substr(0, spec.name.size() - 1)) : name == spec.name)
      return true;
  }
  return false;
}

std::vector<ArchiveColumn> archive_root_attributes() {
  std::vector<ArchiveColumn> out;
  for (const schema::RootAttributeSpec& spec : schema::kRootAttributes)
    out.push_back(
        {std::string(spec.name), std::string(schema::type_name(spec)), std::string(spec.meaning)});
  return out;
}

std::vector<ArchiveColumn> archive_columns(std::string_view group) {
  std::vector<ArchiveColumn> out;
  if (group == "cases") describe(schema::kCaseColumns, out);
  if (group == "exact") describe(schema::kExactColumns, out);
  if (group == "algorithms") describe(schema::kAlgorithmColumns, out);
  if (group == "traces") describe(schema::kTraceColumns, out);
  if (group == "geometry") {
    describe(schema::kGeometryColumns, out);
    describe(schema::kVerticesAColumns, out);
    describe(schema::kVerticesBColumns, out);
  }
  if (group == "meshes/exact") describe(schema::kMeshExactColumns, out);
  if (group == "meshes/algorithms") describe(schema::kMeshAlgorithmColumns, out);
  if (group == "meshes/geometry") {
    describe(schema::kMeshGeometryColumns, out);
    describe(schema::kFacesAColumns, out);
    describe(schema::kFacesBColumns, out);
    describe(schema::kPieceColumns, out);
    describe(schema::kPieceCornerColumns, out);
  }
  return out;
}

}  // namespace gjklab::experiment
