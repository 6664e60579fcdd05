#include "gjklab/experiment/cases/scene_stream.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "gjklab/experiment/cases/cloud_io.hpp"

namespace gjklab::experiment {

namespace {

constexpr const char* kNoQueries =
    "holds no recorded queries (write it with gjklab simulate and [scene] queries_every = k, "
    "k at most the frames run)";

/// Reads whole datasets of one scene archive; every failure is an InputError naming the file.
class Reader {
 public:
  explicit Reader(const std::filesystem::path& path) : path_(path.string()) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    file_ = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_ < 0) fail("cannot open it as HDF5");
  }
  ~Reader() {
    if (file_ >= 0) H5Fclose(file_);
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(path_, 0, problem); }
  bool has(const char* name) const { return H5Lexists(file_, name, H5P_DEFAULT) > 0; }

  template <class T>
  std::vector<T> column(const char* name, hid_t type) const {
    const hid_t ds = has(name) ? H5Dopen2(file_, name, H5P_DEFAULT) : -1;
    if (ds < 0) fail(std::string("no dataset ") + name);
    const hid_t space = H5Dget_space(ds);
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    std::vector<T> out(n > 0 ? static_cast<std::size_t>(n) : 0);
    const bool ok = n >= 0 && (out.empty() ||
                               H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0);
    H5Sclose(space);
    H5Dclose(ds);
    if (!ok) fail(std::string("cannot read ") + name);
    return out;
  }

 private:
  std::string path_;
  hid_t file_ = -1;
};

Pose pose_at(const std::vector<double>& poses, std::size_t row) {
  const double* p = poses.data() + 12 * row;
  Pose out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out.rotation(r, c) = p[3 * r + c];
  out.translation = Vec3(p[9], p[10], p[11]);
  return out;
}

/// The simplex a query was warm-started from: `size` (at most 4) vertex index pairs into the
/// world-frame clouds, with the points they name; shorter when an index is out of range.
std::vector<SimplexVertex> warm_start(std::uint8_t size, const std::int32_t* index_a,
                                      const std::int32_t* index_b, const std::vector<Vec3>& a,
                                      const std::vector<Vec3>& b) {
  std::vector<SimplexVertex> out;
  for (int k = 0; k < std::min<int>(size, 4); ++k) {
    const std::int32_t ia = index_a[k], ib = index_b[k];
    if (ia < 0 || ib < 0 || static_cast<std::size_t>(ia) >= a.size() ||
        static_cast<std::size_t>(ib) >= b.size())
      break;
    SimplexVertex v;
    v.a = a[ia];
    v.b = b[ib];
    v.w = v.a - v.b;
    v.index_a = ia;
    v.index_b = ib;
    out.push_back(v);
  }
  return out;
}

}  // namespace

std::vector<StoredPair> read_scene_stream(const std::filesystem::path& archive) {
  const Reader in(archive);
  if (!in.has("queries") || !in.has("shapes")) in.fail(kNoQueries);
  const auto frame = in.column<std::int64_t>("queries/frame", H5T_NATIVE_INT64);
  const auto body_a = in.column<std::uint32_t>("queries/body_a", H5T_NATIVE_UINT32);
  const auto body_b = in.column<std::uint32_t>("queries/body_b", H5T_NATIVE_UINT32);
  const auto pose_a = in.column<double>("queries/pose_a", H5T_NATIVE_DOUBLE);
  const auto pose_b = in.column<double>("queries/pose_b", H5T_NATIVE_DOUBLE);
  const auto vertices = in.column<double>("shapes/vertices", H5T_NATIVE_DOUBLE);
  const auto offset = in.column<std::int64_t>("shapes/offset", H5T_NATIVE_INT64);
  const auto body_shape = in.column<std::uint32_t>("shapes/body_shape", H5T_NATIVE_UINT32);
  // Swept radius per shape (archives before sphere-swept bodies have none: all polytopes).
  const auto radius = in.has("shapes/radius")
                          ? in.column<double>("shapes/radius", H5T_NATIVE_DOUBLE)
                          : std::vector<double>(offset.empty() ? 0 : offset.size() - 1, 0.0);
  if (radius.size() + 1 != offset.size()) in.fail("shapes/radius and shapes/offset disagree");
  const std::size_t n = frame.size();
  if (body_a.size() != n || body_b.size() != n || pose_a.size() != 12 * n ||
      pose_b.size() != 12 * n)
    in.fail("queries/ columns of different lengths");
  if (n == 0) in.fail(kNoQueries);
  // The cloud of body i at a pose, exactly as the scene's world hull: rotation·v + translation.
  auto cloud = [&](std::uint32_t body, const Pose& pose) {
    if (body >= body_shape.size() || body_shape[body] + 1 >= offset.size())
      in.fail("a query names body " + std::to_string(body) + ", which shapes/ does not hold");
    const auto first = offset[body_shape[body]], last = offset[body_shape[body] + 1];
    if (first < 0 || last < first || static_cast<std::size_t>(3 * last) > vertices.size())
      in.fail("shapes/offset is out of range");
    std::vector<Vec3> out;
    for (auto k = first; k < last; ++k) {
      const std::size_t at = static_cast<std::size_t>(3 * k);
      out.push_back(pose.apply(Vec3(vertices[at], vertices[at + 1], vertices[at + 2])));
    }
    return out;
  };
  const auto warm_size = in.column<std::uint8_t>("queries/warm_size", H5T_NATIVE_UINT8);
  const auto warm_a = in.column<std::int32_t>("queries/warm_index_a", H5T_NATIVE_INT32);
  const auto warm_b = in.column<std::int32_t>("queries/warm_index_b", H5T_NATIVE_INT32);
  if (warm_size.size() != n || warm_a.size() != 4 * n || warm_b.size() != 4 * n)
    in.fail("queries/warm_* columns of different lengths");
  std::vector<StoredPair> pairs;
  pairs.reserve(n);
  for (std::size_t q = 0; q < n; ++q) {
    StoredPair p;
    p.id.append("f").append(std::to_string(frame[q])).append(":");
    p.id.append(std::to_string(body_a[q])).append("-").append(std::to_string(body_b[q]));
    p.a = cloud(body_a[q], pose_at(pose_a, q));
    p.b = cloud(body_b[q], pose_at(pose_b, q));
    p.radius_a = radius[body_shape[body_a[q]]];
    p.radius_b = radius[body_shape[body_b[q]]];
    p.warm = warm_start(warm_size[q], &warm_a[4 * q], &warm_b[4 * q], p.a, p.b);
    if (p.warm.size() != warm_size[q])
      in.fail("query " + std::to_string(q) + "'s warm start names a vertex its bodies lack");
    pairs.push_back(std::move(p));
  }
  return pairs;
}

}  // namespace gjklab::experiment
