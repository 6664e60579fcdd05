#include "result_codec.hpp"

#include "experiment/archive/archive_schema.hpp"

namespace gjklab::experiment::codec {

namespace {

template <class T>
void put_value(ByteWriter& out, const T& v) {
  if constexpr (std::is_same_v<T, std::string>) {
    out.put_string(v);
  } else if constexpr (std::is_same_v<T, Vec3>) {
    for (int k = 0; k < 3; ++k)
      out.put(v[k]);
  } else {
    out.put(v);
  }
}

template <class T>
void get_value(ByteReader& in, T& v) {
  if constexpr (std::is_same_v<T, std::string>) {
    v = in.get_string();
  } else if constexpr (std::is_same_v<T, Vec3>) {
    for (int k = 0; k < 3; ++k)
      v[k] = in.get<double>();
  } else {
    v = in.get<T>();
  }
}

/// Every column of one schema table: the record goes over the wire exactly as the archive
/// stores it.
template <class R, std::size_t N>
void put_record(ByteWriter& out, const R& r, const std::array<schema::ColumnSpec<R>, N>& specs) {
  for (const auto& spec : specs)
    std::visit([&](auto member) { put_value(out, r.*member); }, spec.field);
}

template <class R, std::size_t N>
R get_record(ByteReader& in, const std::array<schema::ColumnSpec<R>, N>& specs) {
  R r;
  for (const auto& spec : specs)
    std::visit([&](auto member) { get_value(in, r.*member); }, spec.field);
  return r;
}

void put_points(ByteWriter& out, const std::vector<Vec3>& points) {
  out.put<std::uint64_t>(points.size());
  for (const Vec3& p : points)
    put_value(out, p);
}

std::vector<Vec3> get_points(ByteReader& in) {
  const auto n = in.get<std::uint64_t>();
  std::vector<Vec3> points;
  // Each point takes 24 bytes, so a corrupt count fails in get() before a huge allocation.
  for (std::uint64_t i = 0; i < n; ++i)
    get_value(in, points.emplace_back());
  return points;
}

void put_faces(ByteWriter& out, const std::vector<std::array<std::uint32_t, 3>>& faces) {
  out.put<std::uint64_t>(faces.size());
  for (const auto& f : faces)
    for (std::uint32_t i : f)
      out.put(i);
}

std::vector<std::array<std::uint32_t, 3>> get_faces(ByteReader& in) {
  const auto n = in.get<std::uint64_t>();
  std::vector<std::array<std::uint32_t, 3>> faces;
  // Each face takes 12 bytes, so a corrupt count fails in get() before a huge allocation.
  for (std::uint64_t k = 0; k < n; ++k)
    for (std::uint32_t& i : faces.emplace_back())
      i = in.get<std::uint32_t>();
  return faces;
}

/// A non-convex pair's records, and the faces and pieces of its kept geometry.
void put_mesh(ByteWriter& out, const CaseResult& r) {
  out.put<std::uint8_t>(r.mesh.has_value());
  if (!r.mesh) return;
  out.put<std::uint8_t>(r.mesh->exact.has_value());
  if (r.mesh->exact) put_record(out, *r.mesh->exact, schema::kMeshExactColumns);
  out.put<std::uint64_t>(r.mesh->algorithms.size());
  for (const MeshAlgorithmRecord& a : r.mesh->algorithms)
    put_record(out, a, schema::kMeshAlgorithmColumns);
  if (!r.geometry) return;
  put_faces(out, r.geometry->faces_a);
  put_faces(out, r.geometry->faces_b);
  out.put<std::uint64_t>(r.geometry->pieces.size());
  for (const KeptPiece& p : r.geometry->pieces) {
    out.put_string(p.decomposition);
    out.put(p.side);
    put_points(out, p.corners);
  }
}

void get_mesh(ByteReader& in, CaseResult& r) {
  if (!in.get<std::uint8_t>()) return;
  MeshCaseResult& mesh = r.mesh.emplace();
  if (in.get<std::uint8_t>()) mesh.exact = get_record(in, schema::kMeshExactColumns);
  const auto algorithms = in.get<std::uint64_t>();
  for (std::uint64_t i = 0; i < algorithms; ++i)
    mesh.algorithms.push_back(get_record(in, schema::kMeshAlgorithmColumns));
  if (!r.geometry) return;
  r.geometry->faces_a = get_faces(in);
  r.geometry->faces_b = get_faces(in);
  const auto pieces = in.get<std::uint64_t>();
  for (std::uint64_t i = 0; i < pieces; ++i) {
    KeptPiece& p = r.geometry->pieces.emplace_back();
    p.decomposition = in.get_string();
    p.side = in.get<std::int32_t>();
    p.corners = get_points(in);
  }
}

void put_result(ByteWriter& out, const CaseResult& r) {
  put_record(out, r.record, schema::kCaseColumns);
  out.put<std::uint8_t>(r.exact.has_value());
  if (r.exact) put_record(out, *r.exact, schema::kExactColumns);
  out.put<std::uint64_t>(r.algorithms.size());
  for (const AlgorithmRecord& a : r.algorithms)
    put_record(out, a, schema::kAlgorithmColumns);
  out.put<std::uint8_t>(r.geometry.has_value());
  if (r.geometry) {
    put_points(out, r.geometry->a);
    put_points(out, r.geometry->b);
  }
  // Traces as the archive's rows: what the writer stores is flatten() of each iteration.
  out.put<std::uint64_t>(r.traces.size());
  for (const auto& trace : r.traces) {
    out.put<std::uint64_t>(trace.size());
    for (const GjkIterationTrace& t : trace)
      put_record(out, schema::flatten(r.record.case_id, t), schema::kTraceColumns);
  }
  put_mesh(out, r);
}

CaseResult get_result(ByteReader& in) {
  CaseResult r;
  r.record = get_record(in, schema::kCaseColumns);
  if (in.get<std::uint8_t>()) r.exact = get_record(in, schema::kExactColumns);
  const auto algorithms = in.get<std::uint64_t>();
  for (std::uint64_t i = 0; i < algorithms; ++i)
    r.algorithms.push_back(get_record(in, schema::kAlgorithmColumns));
  if (in.get<std::uint8_t>()) {
    std::vector<Vec3> a = get_points(in);
    r.geometry.emplace();
    r.geometry->a = std::move(a);
    r.geometry->b = get_points(in);
  }
  const auto traces = in.get<std::uint64_t>();
  for (std::uint64_t i = 0; i < traces; ++i) {
    const auto iterations = in.get<std::uint64_t>();
    auto& trace = r.traces.emplace_back();
    for (std::uint64_t k = 0; k < iterations; ++k) {
      const schema::TraceRow row = get_record(in, schema::kTraceColumns);
      if (row.simplex_size < 0 || row.simplex_size > 4)
        throw std::runtime_error("malformed result message: simplex of size " +
                                 std::to_string(row.simplex_size));
      trace.push_back(schema::unflatten(row));
    }
  }
  get_mesh(in, r);
  return r;
}

}  // namespace

void encode_results(ByteWriter& out, std::span<const CaseResult> results) {
  out.put<std::uint64_t>(results.size());
  for (const CaseResult& r : results)
    put_result(out, r);
}

std::vector<CaseResult> decode_results(ByteReader& in) {
  const auto n = in.get<std::uint64_t>();
  std::vector<CaseResult> results;
  for (std::uint64_t i = 0; i < n; ++i)
    results.push_back(get_result(in));
  return results;
}

}  // namespace gjklab::experiment::codec
