// Bullet's HACD behind gjklab's mesh and options (see peers/hacd.hpp).
#include "gjklab/peers/hacd.hpp"

#include <HACD/hacdHACD.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>

static_assert(std::is_same_v<HACD::Real, double>, "HACD must compute in double");

namespace gjklab::peers {

namespace {

using HacdPoint = HACD::Vec3<HACD::Real>;
using HacdTriangle = HACD::Vec3<long>;

void require(bool ok, const char* option, const char* range) {
  if (!ok) throw std::invalid_argument(std::string("hacd: ") + option + " must be " + range);
}

bool finite_at_least(double value, double low) {
  return std::isfinite(value) && value >= low;
}

[[noreturn]] void fail(const std::string& why) {
  throw std::runtime_error("hacd_decomposition: " + why);
}

/// HACD's copies of the mesh: Compute scales and shifts the points in place (and back, up to
/// rounding), so it never sees the caller's.
struct HacdInput {
  std::vector<HacdPoint> points;
  std::vector<HacdTriangle> triangles;
};

HacdInput hacd_input(const TriangleMesh& mesh) {
  if (mesh.faces.empty()) fail("the mesh has no face");
  HacdInput in;
  in.points.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) {
    if (!is_finite(v)) fail("the mesh has a non-finite vertex");
    in.points.emplace_back(v.x(), v.y(), v.z());
  }
  in.triangles.reserve(mesh.faces.size());
  for (const MeshFace& f : mesh.faces) {
    for (std::uint32_t i : f)
      if (i >= mesh.vertices.size()) fail("a face has a vertex index out of range");
    in.triangles.emplace_back(long{f[0]}, long{f[1]}, long{f[2]});
  }
  return in;
}

void configure(HACD::HACD& hacd, HacdInput& in, const HacdOptions& o) {
  hacd.SetPoints(in.points.data());
  hacd.SetNPoints(in.points.size());
  hacd.SetTriangles(in.triangles.data());
  hacd.SetNTriangles(in.triangles.size());
  hacd.SetCallBack(nullptr);  // HACD reports progress only through it: silent
  hacd.SetNClusters(static_cast<std::size_t>(o.min_clusters));
  hacd.SetConcavity(o.concavity);
  hacd.SetAddExtraDistPoints(o.add_extra_distance_points);
  hacd.SetAddNeighboursDistPoints(o.add_neighbours_distance_points);
  hacd.SetAddFacesPoints(o.add_faces_points);
  hacd.SetCompacityWeight(o.compacity_weight);
  hacd.SetVolumeWeight(o.volume_weight);
  hacd.SetNVerticesPerCH(static_cast<std::size_t>(o.max_hull_vertices));
  hacd.SetConnectDist(o.connect_distance);
  hacd.SetScaleFactor(o.scale);
}

/// For each cluster, the mesh vertices of its triangles (sorted, once each): HACD builds the
/// cluster's hull from these points only.
std::vector<std::vector<std::uint32_t>> cluster_vertices(const HACD::HACD& hacd,
                                                         const TriangleMesh& mesh) {
  const long* partition = hacd.GetPartition();
  if (partition == nullptr) fail("HACD returned no partition of the triangles");
  std::vector<std::vector<std::uint32_t>> out(hacd.GetNClusters());
  for (std::size_t t = 0; t < mesh.faces.size(); ++t) {
    const long c = partition[t];
    if (c < 0 || static_cast<std::size_t>(c) >= out.size())
      fail("HACD put a triangle in no cluster");
    out[c].insert(out[c].end(), mesh.faces[t].begin(), mesh.faces[t].end());
  }
  for (std::vector<std::uint32_t>& v : out) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  return out;
}

/// The mesh vertex among `candidates` (its cluster's) that HACD's point p is a copy of: the
/// nearest one, which must be within rounding of p (HACD's round trip through its normalised
/// frame moves a point by a few ulps of the mesh's extent; `tolerance` is far above that).
Vec3 mesh_vertex(const HacdPoint& p, const std::vector<std::uint32_t>& candidates,
                 const TriangleMesh& mesh, double tolerance) {
  const Vec3 q(p.X(), p.Y(), p.Z());
  double best = std::numeric_limits<double>::infinity();
  std::uint32_t nearest = 0;
  for (std::uint32_t i : candidates) {
    const double d = (mesh.vertices[i] - q).squaredNorm();
    if (d < best) best = d, nearest = i;
  }
  if (!(std::sqrt(best) <= tolerance))
    fail("HACD returned a point that is no vertex of its cluster");
  return mesh.vertices[nearest];
}

/// The tolerance of mesh_vertex: 1e-9 of the mesh's extent (its bounding box's diagonal plus
/// the distance of the box from the origin, which the round trip's rounding also scales with).
double round_trip_tolerance(const TriangleMesh& mesh) {
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices)
    lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return 1e-9 * ((hi - lo).norm() + lo.cwiseAbs().cwiseMax(hi.cwiseAbs()).norm());
}

std::vector<Vec3> piece(HACD::HACD& hacd, std::size_t cluster,
                        const std::vector<std::uint32_t>& candidates, const TriangleMesh& mesh,
                        double tolerance) {
  const std::size_t n_points = hacd.GetNPointsCH(cluster);
  if (n_points == 0) fail("HACD returned an empty piece");
  // GetCH also writes the hull's triangles, which a piece does not keep (it is its points'
  // hull); one spare element keeps the array non-null when a hull has none.
  std::vector<HacdPoint> points(n_points);
  std::vector<HacdTriangle> triangles(hacd.GetNTrianglesCH(cluster) + 1);
  if (!hacd.GetCH(cluster, points.data(), triangles.data())) fail("HACD lost a piece");
  std::vector<Vec3> out;
  out.reserve(n_points);
  for (const HacdPoint& p : points)
    out.push_back(mesh_vertex(p, candidates, mesh, tolerance));
  return out;
}

/// HACD's run, under the lock (see the header), and its pieces.
std::vector<std::vector<Vec3>> run(const TriangleMesh& mesh, const HacdOptions& options) {
  static std::mutex lock;
  const std::lock_guard<std::mutex> guard(lock);
  HacdInput in = hacd_input(mesh);
  HACD::HACD hacd;
  configure(hacd, in, options);
  bool computed = false;
  try {
    computed = hacd.Compute(options.full_hulls, /*exportDistPoints=*/false);
  } catch (const std::exception& e) {
    fail(std::string("HACD failed: ") + e.what());
  }
  if (!computed || hacd.GetNClusters() == 0) fail("HACD computed no decomposition");
  const std::vector<std::vector<std::uint32_t>> clusters = cluster_vertices(hacd, mesh);
  const double tolerance = round_trip_tolerance(mesh);
  std::vector<std::vector<Vec3>> pieces;
  pieces.reserve(clusters.size());
  for (std::size_t c = 0; c < clusters.size(); ++c)
    pieces.push_back(piece(hacd, c, clusters[c], mesh, tolerance));
  return pieces;
}

}  // namespace

void validate(const HacdOptions& o) {
  require(o.min_clusters >= 1, "min_clusters", "an integer >= 1");
  require(finite_at_least(o.concavity, 0.0), "concavity", "finite and >= 0");
  require(finite_at_least(o.compacity_weight, 0.0), "compacity_weight", "finite and >= 0");
  require(finite_at_least(o.volume_weight, 0.0), "volume_weight", "finite and >= 0");
  require(o.max_hull_vertices >= 4, "max_hull_vertices", "an integer >= 4");
  require(std::isfinite(o.connect_distance), "connect_distance",
          "finite (a negative value links no components)");
  require(std::isfinite(o.scale) && o.scale > 0, "scale", "finite and > 0");
}

std::vector<std::vector<Vec3>> hacd_decomposition(const TriangleMesh& mesh,
                                                  const HacdOptions& options) {
  validate(options);
  return run(mesh, options);
}

}  // namespace gjklab::peers
