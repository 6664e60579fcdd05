// The parts of the archive schema the writer and the reader share: the HDF5 types, the trace
// rows, the root attributes, and the column list results/README.md documents.

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

}  // namespace schema

namespace {

// Root attributes with a fixed meaning; every other root attribute is a provenance pair.
constexpr std::array<std::string_view, 17> kRootAttributes = {"schema_version",
                                                              "experiment_name",
                                                              "experiment_text",
                                                              "seed",
                                                              "cases_planned",
                                                              "start_time",
                                                              "end_time",
                                                              "oracle",
                                                              "touching_band",
                                                              "family_names",
                                                              "algorithm_names",
                                                              "complete",
                                                              "checkpoint_cases",
                                                              "checkpoint_geometry",
                                                              "checkpoint_vertices_a",
                                                              "checkpoint_vertices_b",
                                                              "trace_mode"};

template <class R, std::size_t N>
void describe(const std::array<schema::ColumnSpec<R>, N>& specs, std::vector<ArchiveColumn>& out) {
  for (const auto& spec : specs)
    out.push_back({std::string(spec.name), schema::type_name(spec)});
}

}  // namespace

bool is_root_attribute(std::string_view name) {
  return name.starts_with("checkpoint_") ||
         std::find(kRootAttributes.begin(), kRootAttributes.end(), name) != kRootAttributes.end();
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
  return out;
}

}  // namespace gjklab::experiment
