// 3D broad phases over axis-aligned bounding boxes (world frame, length units).
//
// Every broad phase answers the same question: the set of pairs (i, j), i < j, whose closed
// boxes overlap (touching counts), returned sorted, so that the three are interchangeable and
// the tests compare them with ==. Pairs of two static bodies are the caller's to drop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::scene {

struct Aabb {
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();
  bool overlaps(const Aabb& o) const {
    return lower.x() <= o.upper.x() && o.lower.x() <= upper.x() && lower.y() <= o.upper.y() &&
           o.lower.y() <= upper.y() && lower.z() <= o.upper.z() && o.lower.z() <= upper.z();
  }
};

using BodyPair = std::pair<std::uint32_t, std::uint32_t>;

enum class BroadPhaseKind : std::uint8_t {
  all_pairs,        ///< every pair tested: the reference, O(n²)
  grid,             ///< uniform 3D grid of hashed cells
  sweep_and_prune,  ///< sort along one axis, sweep within bands across the other two
};

constexpr std::string_view to_string(BroadPhaseKind k) {
  switch (k) {
    case BroadPhaseKind::all_pairs:
      return "all-pairs";
    case BroadPhaseKind::grid:
      return "grid";
    case BroadPhaseKind::sweep_and_prune:
      return "sap";
  }
  return "unknown";
}
std::optional<BroadPhaseKind> broad_phase_from_string(std::string_view name);

/// The reference: every pair tested.
void all_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out);

/// Sweep and prune in bands. The boxes are sorted on their lower bound along the axis on which
/// the centres spread most; the order is kept between calls and repaired by insertion sort (in
/// a simulation it changes little from frame to frame: about n comparisons). The sweep runs
/// within the bands of a coarse 2D grid across the other two axes (side 1.25 × the median box's
/// width), as in multi-box pruning: a box is listed in every band it touches (one to four for
/// most boxes), each band's list is in sweep order, and a pair is reported by the one band that
/// holds the lower corner of the two boxes' band ranges. A single band is the classic sweep.
/// Boxes wider than four bands (grounds, containers) and boxes that are not finite or are
/// inverted are kept aside and tested against every box.
class SweepAndPrune {
 public:
  void find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out);
  int axis() const { return axis_; }
  std::size_t bands() const { return band_start_.empty() ? 0 : band_start_.size() - 1; }

 private:
  /// A box's bands, inclusive on both ends (column u, row v).
  struct Range {
    std::int32_t lo[2], hi[2];
  };
  /// A box as listed in one band, laid out for a two-lane compare: the lower bounds and the
  /// negated upper bounds across the sweep axis (b overlaps a there when all of b's lower
  /// bounds are ≤ a's upper ones and −b.upper ≤ −a.lower; negation is exact).
  struct alignas(16) Entry {
    double lo_x, lo_u, lo_v, neg_hi_u, neg_hi_v;
    std::uint32_t body;
    std::uint32_t first;  ///< bit 0: the box's lowest band in u; bit 1: in v
  };
  void choose_axis(std::span<const Aabb> boxes);
  std::size_t assign_bands(std::span<const Aabb> boxes);
  void sort_order(bool from_scratch);
  void fill_bands(std::span<const Aabb> boxes);
  std::size_t sweep_bands();
  void aside_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) const;

  int axis_ = -1;
  std::int32_t columns_ = 1;          ///< bands along u
  std::vector<std::uint32_t> order_;  ///< bodies by lower bound on the axis, kept between calls
  std::vector<double> key_, upper_, sample_;
  std::vector<std::uint8_t> is_aside_;
  std::vector<std::uint32_t> aside_, band_start_, band_fill_;
  std::vector<Range> range_;
  std::vector<Entry> entries_;
  std::vector<BodyPair> found_, sort_tmp_;  ///< found_: scratch of the sweep, only grows
  std::vector<std::uint32_t> sort_count_;
};

/// Uniform grid of cubic cells of side `cell_size` (length units): a dense array over the
/// occupied region (counting sort, linear time), or hashed cells when the bodies are scattered
/// over a region much larger than they fill. A box goes into every cell it touches; a pair is
/// reported by the one cell that holds the lower corner of the intersection of the two boxes' cell
/// ranges, so each pair once without a set. Boxes that would touch more than kMaxCellsPerBox cells
/// (a ground plane) are kept aside and tested against every box instead.
class UniformGrid {
 public:
  static constexpr std::int64_t kMaxCellsPerBox = 64;
  /// cell_size ≤ 0: chosen at each call as 1.1 × the median box's largest side.
  explicit UniformGrid(double cell_size = 0) : cell_size_(cell_size) {}
  void find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out);
  double last_cell_size() const { return used_cell_size_; }

 private:
  /// A box's cells, inclusive on both ends.
  struct Range {
    std::int64_t lo[3], hi[3];
  };
  static bool owns(const Range& a, const Range& b, std::int64_t x, std::int64_t y, std::int64_t z);
  void dense_pairs(std::span<const Aabb> boxes, const std::int64_t lo[3], const std::int64_t hi[3],
                   std::vector<BodyPair>& out);
  void hashed_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out);

  double cell_size_;
  double used_cell_size_ = 0;
  struct Entry {
    std::uint64_t key;
    std::uint32_t body;
  };
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> large_, small_;
  std::vector<Range> ranges_;
  std::vector<std::uint32_t> start_, fill_, members_;
  std::vector<BodyPair> sort_tmp_;
  std::vector<std::uint32_t> sort_count_;
};

/// One broad phase selected by kind, with the state its kind keeps between frames.
class BroadPhase {
 public:
  explicit BroadPhase(BroadPhaseKind kind, double grid_cell_size = 0)
      : kind_(kind), grid_(grid_cell_size) {}
  BroadPhaseKind kind() const { return kind_; }
  /// The sorted overlapping pairs (i < j) of the boxes.
  void find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out);

 private:
  BroadPhaseKind kind_;
  SweepAndPrune sap_;
  UniformGrid grid_;
};

}  // namespace gjklab::scene
