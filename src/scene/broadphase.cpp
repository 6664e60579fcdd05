#include "gjklab/scene/broadphase.hpp"

#include <algorithm>
#include <cmath>

namespace gjklab::scene {

std::optional<BroadPhaseKind> broad_phase_from_string(std::string_view name) {
  for (BroadPhaseKind k :
       {BroadPhaseKind::all_pairs, BroadPhaseKind::grid, BroadPhaseKind::sweep_and_prune})
    if (to_string(k) == name) return k;
  return std::nullopt;
}

void all_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  out.clear();
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j)
      if (boxes[i].overlaps(boxes[j])) out.emplace_back(i, j);
}

namespace {

BodyPair ordered(std::uint32_t a, std::uint32_t b) {
  return a < b ? BodyPair{a, b} : BodyPair{b, a};
}

}  // namespace

void SweepAndPrune::find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  out.clear();
  const auto n = static_cast<std::uint32_t>(boxes.size());
  if (order_.size() != n) {
    order_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) order_[i] = i;
  }
  // Insertion sort on lower x from last frame's order (nearly sorted: about n steps).
  for (std::uint32_t k = 1; k < n; ++k) {
    const std::uint32_t body = order_[k];
    const double key = boxes[body].lower.x();
    std::uint32_t m = k;
    while (m > 0 && boxes[order_[m - 1]].lower.x() > key) {
      order_[m] = order_[m - 1];
      --m;
    }
    order_[m] = body;
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const Aabb& a = boxes[order_[k]];
    for (std::uint32_t m = k + 1; m < n; ++m) {
      const Aabb& b = boxes[order_[m]];
      if (b.lower.x() > a.upper.x()) break;  // every later box starts further right
      if (a.overlaps(b)) out.push_back(ordered(order_[k], order_[m]));
    }
  }
  std::sort(out.begin(), out.end());
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

CellRange cell_range(const Aabb& b, double inv_cell) {
  CellRange r;
  for (int a = 0; a < 3; ++a) {
    // Clamped so that absurd coordinates cannot overflow the conversion; such boxes then
    // count as large (many cells) and are tested against every box.
    // A NaN bound (a box that overlaps nothing) goes to cell 0.
    const double l = std::floor(b.lower[a] * inv_cell), h = std::floor(b.upper[a] * inv_cell);
    const double lo = std::isnan(l) ? 0.0 : std::clamp(l, -1e15, 1e15);
    const double hi = std::isnan(h) ? 0.0 : std::clamp(h, -1e15, 1e15);
    r.lo[a] = static_cast<std::int64_t>(lo);
    r.hi[a] = static_cast<std::int64_t>(hi);
  }
  return r;
}

double auto_cell_size(std::span<const Aabb> boxes) {
  std::vector<double> sides;
  sides.reserve(boxes.size());
  for (const Aabb& b : boxes) sides.push_back((b.upper - b.lower).maxCoeff());
  std::nth_element(sides.begin(), sides.begin() + sides.size() / 2, sides.end());
  const double median = sides[sides.size() / 2];
  return median > 0 && std::isfinite(median) ? 2 * median : 1.0;
}

}  // namespace

void UniformGrid::find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  out.clear();
  entries_.clear();
  large_.clear();
  if (boxes.empty()) return;
  used_cell_size_ = cell_size_ > 0 ? cell_size_ : auto_cell_size(boxes);
  const double inv = 1.0 / used_cell_size_;
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    const CellRange r = cell_range(boxes[i], inv);
    if (!(r.count() <= double(kMaxCellsPerBox))) {
      large_.push_back(i);
      continue;
    }
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
    while (e < entries_.size() && entries_[e].key == entries_[s].key) ++e;
    for (std::size_t p = s; p < e; ++p) {
      for (std::size_t q = p + 1; q < e; ++q) {
        const std::uint32_t i = entries_[p].body, j = entries_[q].body;
        const Aabb& a = boxes[i];
        const Aabb& b = boxes[j];
        if (!a.overlaps(b)) continue;
        // Report only from the cell holding the lower corner of the shared cell range.
        const CellRange ra = cell_range(a, inv), rb = cell_range(b, inv);
        const std::uint64_t owner =
            cell_key(std::max(ra.lo[0], rb.lo[0]), std::max(ra.lo[1], rb.lo[1]),
                     std::max(ra.lo[2], rb.lo[2]));
        if (owner == entries_[s].key) out.push_back(ordered(i, j));
      }
    }
    s = e;
  }
  for (std::uint32_t big : large_)
    for (std::uint32_t j = 0; j < n; ++j)
      if (j != big && boxes[big].overlaps(boxes[j])) {
        // Two large boxes meet twice: report from the smaller index only.
        const bool other_large = std::binary_search(large_.begin(), large_.end(), j);
        if (other_large && j < big) continue;
        out.push_back(ordered(big, j));
      }
  std::sort(out.begin(), out.end());
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
