// A convex polytope given by its vertices: the convex hull of a finite point cloud.
//
// The cloud need not be in convex position, and may be flat, collinear or a single point:
// every point is a candidate support point. Vertices are stored contiguously.
//
// Support. The default support is a full scan over every vertex, returning the first vertex
// that maximises d·x. The scan reads a second copy of the vertices laid out in blocks of eight
// (x[8], y[8], z[8]: structure of arrays within a block), which the compiler turns into packed
// SIMD arithmetic; each dot product is evaluated as (x·dx + y·dy) + z·dz, exactly as Eigen's
// Vec3::dot does, so the scan returns the same index as the textbook loop, bit for bit, ties
// included.
//
// Hill climbing (opt-in). With hull adjacency attached (enable_hill_climbing), support walks
// the hull's vertex graph from the previous support vertex (the hint) or from a precomputed
// start vertex for d's cell of a cube map of directions, whichever is better in d, to a vertex
// no neighbour of which is strictly better. On a convex polytope that vertex maximises d·x. It need
// not be the *first* maximising vertex of the cloud: on ties (d normal to a face or edge) it may
// return another maximiser, and it never returns a point that is not a hull vertex. The adjacency
// is computed from the exact hull by exact::hull_vertex_adjacency. Because of that, and because the
// hint is state, hill climbing is off by default: experiments compare the scan's answers bit for
// bit.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// Thrown for clouds that cannot define a polytope (empty, or with a non-finite coordinate).
class InvalidGeometry : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// n points stored as rows of three doubles, as in a NumPy n×3 float64 array of any strides:
/// coordinate k of point i is the double at byte offset i·row_stride + k·column_stride from
/// `data` (no alignment assumed). The default strides are those of a C-contiguous array, which
/// is also the layout of a std::vector<Vec3>.
struct CoordinateRows {
  const void* data = nullptr;
  std::size_t count = 0;
  std::ptrdiff_t row_stride = 3 * sizeof(double);  ///< bytes
  std::ptrdiff_t column_stride = sizeof(double);   ///< bytes
};

/// Vertex counts from which hill climbing beats the blocked scan on the machines measured
/// (see bench/ and `gjklab bench --suite random`); callers decide, this is a suggestion.
inline constexpr std::size_t kHillClimbingMinVertices = 128;

class Polytope {
 public:
  /// Throws InvalidGeometry if the cloud is empty or has a NaN or infinite coordinate.
  explicit Polytope(std::vector<Vec3> vertices);
  /// The polytope of the points in `rows`, read in one pass that copies them, lays out the
  /// scan's blocks and takes the measures: bit for bit the polytope that the constructor above
  /// builds from the same points, with the same InvalidGeometry.
  explicit Polytope(const CoordinateRows& rows);
  /// *this = Polytope(rows), in this polytope's own storage: no allocation when it already held
  /// at least as many points (for callers that build many short-lived polytopes, such as a query
  /// on arrays). The result has a new id() and uses the full scan. If it throws InvalidGeometry,
  /// the polytope is left as the single point at the origin (valid, with a new id()).
  void assign(const CoordinateRows& rows);

  std::span<const Vec3> vertices() const { return vertices_; }
  std::size_t size() const { return vertices_.size(); }

  /// Index of a vertex maximising d·x. With the default full scan: the first such vertex on
  /// ties. With hill climbing enabled: some maximising hull vertex (see the file comment).
  std::size_t support_index(const Vec3& d) const {
    return graph_ ? climb_support_index(d) : scan_support_index(d);
  }
  Vec3 support(const Vec3& d) const { return vertices_[support_index(d)]; }

  /// The full scan, whatever the mode: the first vertex maximising d·x. For a NaN d (or any d
  /// for which vertex 0's dot product is NaN) the answer is 0, as for the textbook loop.
  std::size_t scan_support_index(const Vec3& d) const;

  /// The full scans of a in d and of b in −d, in one call (see scan_support_pair).
  friend std::pair<std::size_t, std::size_t> scan_support_pair(const Polytope& a, const Vec3& d,
                                                               const Polytope& b);

  /// Attaches hull adjacency and switches support to hill climbing. adjacency[i] lists the
  /// neighbours of point i on the hull's boundary graph (empty for points that are not hull
  /// vertices, and for repeated copies of a point). Throws std::invalid_argument if it has the
  /// wrong size, an index out of range, or no vertex with neighbours while size() > 1.
  void enable_hill_climbing(const std::vector<std::vector<int>>& adjacency);
  /// Back to the full scan (drops the adjacency).
  void disable_hill_climbing();
  bool uses_hill_climbing() const { return graph_ != nullptr; }

  /// The same cloud with every vertex moved by the pose. Hill climbing, if enabled, stays
  /// enabled with the same adjacency: a rigid motion preserves the hull's combinatorics (up
  /// to rounding of nearly flat configurations).
  Polytope transformed(const Pose& pose) const;
  /// The same cloud with every coordinate multiplied by factor (adjacency kept, as above).
  Polytope scaled(double factor) const;

  /// The same cloud with every vertex moved by t (adjacency kept). Exact where every sum
  /// x + t_i is representable, as for the exact re-centring (recentring.hpp).
  Polytope translated(const Vec3& t) const;

  /// Length of the diagonal of the axis-aligned bounding box (length units).
  double bounding_box_diagonal() const;
  /// Corners of the axis-aligned bounding box; computed once, at construction.
  const Vec3& box_lower() const { return box_lower_; }
  const Vec3& box_upper() const { return box_upper_; }
  /// The box's largest side and the cloud's largest |coordinate| (length units): the scales
  /// that decide, in two comparisons, whether a pair is far from the origin (recentring.hpp).
  double box_extent() const { return box_extent_; }
  double max_magnitude() const { return max_magnitude_; }
  /// Mean of the vertices (not the volume centroid); computed once, at construction.
  Vec3 vertex_mean() const { return mean_; }
  /// Identity of the vertex list, for caches of data derived from it (hull features, a peer
  /// library's shape object): every polytope built from a cloud gets a new id, and copies
  /// share it (the vertices never change after construction).
  std::uint64_t id() const { return id_; }

  Polytope(const Polytope& other) = default;
  Polytope& operator=(const Polytope& other) = default;
  Polytope(Polytope&& other) noexcept = default;
  Polytope& operator=(Polytope&& other) noexcept = default;
  ~Polytope();

  /// Vertices per block of the scan's layout.
  static constexpr int kBlock = 8;
  /// One block of the scan's layout; the last block is padded with copies of the last vertex
  /// (which can never win: the real last vertex has a smaller index and the same dot product).
  struct alignas(64) Block {
    double x[kBlock], y[kBlock], z[kBlock];
  };

  /// Hull graph for hill climbing, in compressed rows.
  struct HullGraph {
    std::vector<std::uint32_t> offsets;  ///< neighbours of i: [offsets[i], offsets[i+1])
    std::vector<std::uint32_t> neighbours;
  };

 private:
  std::size_t climb_support_index(const Vec3& d) const;
  void build_start_table();
  /// The measures (mean, box, extent, magnitude) from a pass's results, and a new id.
  void take_measures(const Vec3& mean, const Vec3& lower, const Vec3& upper);

  std::vector<Vec3> vertices_;
  std::vector<Block> blocks_;
  Vec3 mean_ = Vec3::Zero();
  Vec3 box_lower_ = Vec3::Zero();
  Vec3 box_upper_ = Vec3::Zero();
  double box_extent_ = 0;
  double max_magnitude_ = 0;
  std::uint64_t id_ = 0;
  std::shared_ptr<const HullGraph> graph_;
  /// Start vertices of hill climbing: for each cell of a cube map of directions (6 faces of
  /// table_resolution_² cells), the graph vertex extreme along the cell's central direction.
  std::vector<std::uint32_t> start_table_;
  int table_resolution_ = 1;
  /// A vertex index that concurrent queries on one polytope may read and write: a relaxed
  /// atomic (each query then starts from some recent vertex, which is still correct) that
  /// copies and moves as its current value, so that Polytope's own copies are the defaults.
  class SharedHint {
   public:
    SharedHint() = default;
    SharedHint(const SharedHint& other) noexcept : value_(other.load()) {}
    SharedHint& operator=(const SharedHint& other) noexcept {
      store(other.load());
      return *this;
    }
    std::uint32_t load() const { return value_.load(std::memory_order_relaxed); }
    void store(std::uint32_t v) const { value_.store(v, std::memory_order_relaxed); }

   private:
    mutable std::atomic<std::uint32_t> value_{0};
  };
  /// Last support vertex of hill climbing.
  SharedHint hint_;
};

/// {a.scan_support_index(d), b.scan_support_index(−d)}, the same answers, from one call that
/// lets the processor overlap the two searches (a GJK iteration needs both before it goes on).
std::pair<std::size_t, std::size_t> scan_support_pair(const Polytope& a, const Vec3& d,
                                                      const Polytope& b);

/// Returns an empty string if the cloud is valid, else what is wrong with it (for messages).
std::string describe_invalid_cloud(std::span<const Vec3> cloud);

/// The larger bounding-box diagonal of two clouds: the size that relative errors refer to.
double pair_size(std::span<const Vec3> a, std::span<const Vec3> b);
/// The same for the clouds swept by balls of the given radii (length units): each bounding box
/// grows by its radius on every side. Equal to pair_size(a, b) for zero radii.
double pair_size(std::span<const Vec3> a, std::span<const Vec3> b, double radius_a,
                 double radius_b);

}  // namespace gjklab
