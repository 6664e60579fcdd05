#include "gjklab/experiment/cases/scene_stream.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/archive/scene_archive.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"

namespace gjklab::experiment {

namespace {

constexpr const char* kNoQueries =
    "holds no recorded queries (write it with gjklab simulate and [scene] queries_every = k, "
    "k at most the frames run)";

/// Every problem of the archive is an InputError naming the file.
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
  throw InputError(path.string(), 0, problem);
}

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
  SceneArchive scene;
  try {
    scene = read_scene_archive(archive.string());
  } catch (const ArchiveError& e) {
    fail(archive, e.what());
  }
  const SceneQueryRows& q = scene.queries;
  const SceneShapeRows& shapes = scene.shapes;
  const std::size_t n = q.frame.size();
  if (scene.header.queries_every == 0 || n == 0) fail(archive, kNoQueries);
  const std::vector<std::int64_t>& offset = shapes.offset;
  // Swept radius per shape (archives before sphere-swept bodies have none: all polytopes).
  const std::vector<double> radius =
      !shapes.radius.empty() ? shapes.radius
                             : std::vector<double>(offset.empty() ? 0 : offset.size() - 1, 0.0);
  if (radius.size() + 1 != offset.size()) fail(archive, "shapes/radius and shapes/offset disagree");
  // The cloud of body i at a pose, exactly as the scene's world hull: rotation·v + translation.
  auto cloud = [&](std::uint32_t body, const Pose& pose) {
    if (body >= shapes.body_shape.size() || shapes.body_shape[body] + 1 >= offset.size())
      fail(archive, "a query names body " + std::to_string(body) + ", which shapes/ does not hold");
    const auto first = offset[shapes.body_shape[body]], last = offset[shapes.body_shape[body] + 1];
    if (first < 0 || last < first || static_cast<std::size_t>(3 * last) > shapes.vertices.size())
      fail(archive, "shapes/offset is out of range");
    std::vector<Vec3> out;
    for (auto k = first; k < last; ++k) {
      const double* v = shapes.vertices.data() + 3 * k;
      out.push_back(pose.apply(Vec3(v[0], v[1], v[2])));
    }
    return out;
  };
  std::vector<StoredPair> pairs;
  pairs.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    StoredPair p;
    p.id.append("f").append(std::to_string(q.frame[k])).append(":");
    p.id.append(std::to_string(q.a[k])).append("-").append(std::to_string(q.b[k]));
    p.a = cloud(q.a[k], pose_at(q.pose_a, k));
    p.b = cloud(q.b[k], pose_at(q.pose_b, k));
    p.radius_a = radius[shapes.body_shape[q.a[k]]];
    p.radius_b = radius[shapes.body_shape[q.b[k]]];
    p.warm = warm_start(q.warm_size[k], &q.warm_index_a[4 * k], &q.warm_index_b[4 * k], p.a, p.b);
    if (p.warm.size() != q.warm_size[k])
      fail(archive, "query " + std::to_string(k) + "'s warm start names a vertex its bodies lack");
    pairs.push_back(std::move(p));
  }
  return pairs;
}

}  // namespace gjklab::experiment
