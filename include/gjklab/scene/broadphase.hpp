// 3D broad phases over axis-aligned bounding boxes (world frame, length units).
//
// Every broad phase answers the same question: the set of pairs (i, j), i < j, whose closed
// boxes overlap (touching counts), returned sorted, so that the three are interchangeable and
// the tests compare them with ==. Pairs of two static bodies are the caller's to drop.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "gjklab/geometry/enum_names.hpp"
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

inline constexpr auto kBroadPhaseKindNames = std::to_array<EnumName<BroadPhaseKind>>({
    {BroadPhaseKind::all_pairs, "all-pairs"},
    {BroadPhaseKind::grid, "grid"},
    {BroadPhaseKind::sweep_and_prune, "sap"},
});
static_assert(in_value_order(kBroadPhaseKindNames) &&
              ends_at(kBroadPhaseKindNames, BroadPhaseKind::sweep_and_prune));

constexpr std::string_view to_string(BroadPhaseKind k) {
  return name_of(kBroadPhaseKindNames, k);
}
inline std::optional<BroadPhaseKind> broad_phase_from_string(std::string_view name) {
  return value_named(kBroadPhaseKindNames, name);
}

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
  /// At most 2³⁰ − 1 boxes (a listing packs the index with two flags in 32 bits).
  void find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out);
  int axis() const { return axis_; }
  std::size_t bands() const { return band_start_.empty() ? 0 : band_start_.size() - 1; }

 private:
  /// A box's bands, inclusive on both ends (column u, row v).
  struct Range {
    std::int32_t lo[2], hi[2];
  };
  /// A box's bounds across the sweep axis, laid out for two-lane compares: b overlaps a there
  /// when (b.lo_u, b.lo_v) ≤ (a.hi_u, a.hi_v) and (−b.hi_u, −b.hi_v) ≤ (−a.lo_u, −a.lo_v), lane
  /// by lane (negation is exact).
  struct alignas(16) Across {
    double lo_u, lo_v, neg_hi_u, neg_hi_v;
  };
  /// A box listed in a band: code = index << 2 | first, where first's bit 0 says the band is
  /// the box's lowest along u, bit 1 along v. The bands' lists hold only codes (4 bytes each):
  /// writing them is the cost that grows when the caches are cold, as in a simulation step.
  struct Listing {
    std::uint32_t band, code;
  };
  void choose_axis(std::span<const Aabb> boxes);
  std::size_t assign_bands(std::span<const Aabb> boxes);
  void sort_order(bool from_scratch);
  std::size_t list_boxes();
  void fill_bands(std::size_t listings);
  std::size_t sweep_bands();
  void aside_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) const;

  int axis_ = -1;
  std::uint32_t columns_ = 1;         ///< bands along u
  std::vector<std::uint32_t> order_;  ///< boxes by lower bound on the axis, kept between calls
  /// Per box, plus a last entry (key +∞) read by the sweep past the end of the lists.
  std::vector<double> key_, upper_;
  std::vector<Across> across_;
  std::vector<double> sample_;
  std::vector<std::uint8_t> is_aside_;
  std::vector<std::uint32_t> aside_, band_start_, band_fill_, entries_;
  std::vector<Range> range_;
  std::vector<Listing> listings_;
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
