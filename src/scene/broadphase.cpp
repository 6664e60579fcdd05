#include "gjklab/scene/broadphase.hpp"

#include <algorithm>
#include <cmath>

#include "pair_order.hpp"

namespace gjklab::scene {

using detail::ordered;

void all_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  out.clear();
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j)
      if (boxes[i].overlaps(boxes[j])) out.emplace_back(i, j);
}

namespace {

/// 21 bits per axis, offset so that negative cells hash too; cells beyond ±2^20 wrap (pairs
/// stay exact: every reported pair is checked with overlaps()).
std::uint64_t cell_key(std::int64_t x, std::int64_t y, std::int64_t z) {
  constexpr std::int64_t kOffset = std::int64_t{1} << 20;
  constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
  return ((static_cast<std::uint64_t>(x + kOffset) & kMask) << 42) |
         ((static_cast<std::uint64_t>(y + kOffset) & kMask) << 21) |
         (static_cast<std::uint64_t>(z + kOffset) & kMask);
}

struct CellRange {
  std::int64_t lo[3], hi[3];
  /// In double: the clamped ranges below would overflow a 64-bit product.
  double count() const {
    return double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
  }
};

/// floor(x) as an integer, for x clamped to ±10¹⁵ (a NaN goes to cell 0: such a box overlaps
/// nothing). Truncation and one comparison: std::floor is a library call on baseline x86-64,
/// and this runs six times per box per frame.
std::int64_t cell_of(double x) {
  if (!(x == x)) return 0;
  x = std::clamp(x, -1e15, 1e15);
  const auto t = static_cast<std::int64_t>(x);
  return static_cast<double>(t) > x ? t - 1 : t;
}

CellRange cell_range(const Aabb& b, double inv_cell) {
  CellRange r;
  for (int a = 0; a < 3; ++a) {
    // Clamped so that absurd coordinates cannot overflow the conversion; such boxes then
    // count as large (many cells) and are tested against every box.
    r.lo[a] = cell_of(b.lower[a] * inv_cell);
    r.hi[a] = cell_of(b.upper[a] * inv_cell);
  }
  return r;
}

double auto_cell_size(std::span<const Aabb> boxes) {
  std::vector<double> sides;
  sides.reserve(boxes.size());
  for (const Aabb& b : boxes)
    sides.push_back((b.upper - b.lower).maxCoeff());
  std::nth_element(sides.begin(), sides.begin() + sides.size() / 2, sides.end());
  const double median = sides[sides.size() / 2];
  // About the median box's side: most boxes then touch 1 to 8 cells and a cell holds few
  // boxes (measured on the demo scene: 1.1 × the median side is near the fastest).
  return median > 0 && std::isfinite(median) ? 1.1 * median : 1.0;
}

}  // namespace

void UniformGrid::find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  out.clear();
  large_.clear();
  if (boxes.empty()) return;
  used_cell_size_ = cell_size_ > 0 ? cell_size_ : auto_cell_size(boxes);
  const double inv = 1.0 / used_cell_size_;
  const auto n = static_cast<std::uint32_t>(boxes.size());
  ranges_.resize(n);
  small_.clear();
  std::int64_t lo[3] = {INT64_MAX, INT64_MAX, INT64_MAX}, hi[3] = {INT64_MIN, INT64_MIN, INT64_MIN};
  for (std::uint32_t i = 0; i < n; ++i) {
    const CellRange r = cell_range(boxes[i], inv);
    // An inverted box (lower above upper) spans no cell range, yet all_pairs' test can still
    // accept it: it is tested against every box, like a large one. (A NaN box is in cell 0
    // and overlaps nothing.)
    const bool inverted = r.hi[0] < r.lo[0] || r.hi[1] < r.lo[1] || r.hi[2] < r.lo[2];
    if (inverted || !(r.count() <= double(kMaxCellsPerBox))) {
      large_.push_back(i);
      continue;
    }
    ranges_[i] = {r.lo[0], r.lo[1], r.lo[2], r.hi[0], r.hi[1], r.hi[2]};
    small_.push_back(i);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], r.lo[a]);
      hi[a] = std::max(hi[a], r.hi[a]);
    }
  }
  if (!small_.empty()) {
    const double cells =
        double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
    // A dense array of cells when the occupied region is not much larger than the bodies
    // need (the usual case); hashed cells, sorted, for scattered worlds.
    if (cells <= 8.0 * double(small_.size()) + 4096)
      dense_pairs(boxes, lo, hi, out);
    else
      hashed_pairs(boxes, out);
  }
  for (std::uint32_t big : large_)
    for (std::uint32_t j = 0; j < n; ++j)
      if (j != big && boxes[big].overlaps(boxes[j])) {
        // Two large boxes meet twice: report from the smaller index only.
        const bool other_large = std::binary_search(large_.begin(), large_.end(), j);
        if (other_large && j < big) continue;
        out.push_back(ordered(big, j));
      }
  detail::sort_pairs(out, n, sort_tmp_, sort_count_);
}

bool UniformGrid::owns(const Range& a, const Range& b, std::int64_t x, std::int64_t y,
                       std::int64_t z) {
  // The one cell that reports a pair: the lower corner of the two ranges' intersection.
  return x == std::max(a.lo[0], b.lo[0]) && y == std::max(a.lo[1], b.lo[1]) &&
         z == std::max(a.lo[2], b.lo[2]);
}

void UniformGrid::dense_pairs(std::span<const Aabb> boxes, const std::int64_t lo[3],
                              const std::int64_t hi[3], std::vector<BodyPair>& out) {
  const std::int64_t nx = hi[0] - lo[0] + 1, ny = hi[1] - lo[1] + 1, nz = hi[2] - lo[2] + 1;
  auto cell_index = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::size_t>(((z - lo[2]) * ny + (y - lo[1])) * nx + (x - lo[0]));
  };
  // Counting sort of (cell, body): counts, prefix sums, then the bodies in index order.
  start_.assign(static_cast<std::size_t>(nx * ny * nz) + 1, 0);
  auto for_cells = [&](const Range& r, auto&& f) {
    for (std::int64_t z = r.lo[2]; z <= r.hi[2]; ++z)
      for (std::int64_t y = r.lo[1]; y <= r.hi[1]; ++y)
        for (std::int64_t x = r.lo[0]; x <= r.hi[0]; ++x)
          f(x, y, z);
  };
  for (std::uint32_t i : small_)
    for_cells(ranges_[i], [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      ++start_[cell_index(x, y, z) + 1];
    });
  for (std::size_t c = 1; c < start_.size(); ++c)
    start_[c] += start_[c - 1];
  members_.resize(start_.back());
  fill_ = start_;
  for (std::uint32_t i : small_)
    for_cells(ranges_[i], [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      members_[fill_[cell_index(x, y, z)]++] = i;
    });
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
        const std::size_t c = cell_index(x, y, z);
        for (std::uint32_t p = start_[c]; p < start_[c + 1]; ++p)
          for (std::uint32_t q = p + 1; q < start_[c + 1]; ++q) {
            const std::uint32_t i = members_[p], j = members_[q];
            if (owns(ranges_[i], ranges_[j], x, y, z) && boxes[i].overlaps(boxes[j]))
              out.push_back(ordered(i, j));
          }
      }
}

void UniformGrid::hashed_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  entries_.clear();
  for (std::uint32_t i : small_) {
    const Range& r = ranges_[i];
    for (std::int64_t x = r.lo[0]; x <= r.hi[0]; ++x)
      for (std::int64_t y = r.lo[1]; y <= r.hi[1]; ++y)
        for (std::int64_t z = r.lo[2]; z <= r.hi[2]; ++z)
          entries_.push_back({cell_key(x, y, z), i});
  }
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    return a.key != b.key ? a.key < b.key : a.body < b.body;
  });
  for (std::size_t s = 0; s < entries_.size();) {
    std::size_t e = s;
    while (e < entries_.size() && entries_[e].key == entries_[s].key)
      ++e;
    for (std::size_t p = s; p < e; ++p) {
      for (std::size_t q = p + 1; q < e; ++q) {
        const std::uint32_t i = entries_[p].body, j = entries_[q].body;
        if (!boxes[i].overlaps(boxes[j])) continue;
        const Range& ra = ranges_[i];
        const Range& rb = ranges_[j];
        const std::uint64_t owner =
            cell_key(std::max(ra.lo[0], rb.lo[0]), std::max(ra.lo[1], rb.lo[1]),
                     std::max(ra.lo[2], rb.lo[2]));
        if (owner == entries_[s].key) out.push_back(ordered(i, j));
      }
    }
    s = e;
  }
}

void BroadPhase::find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  switch (kind_) {
    case BroadPhaseKind::all_pairs:
      all_pairs(boxes, out);
      return;
    case BroadPhaseKind::grid:
      grid_.find_pairs(boxes, out);
      return;
    case BroadPhaseKind::sweep_and_prune:
      sap_.find_pairs(boxes, out);
      return;
  }
}

}  // namespace gjklab::scene
