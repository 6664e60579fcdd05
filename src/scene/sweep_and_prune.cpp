// Sweep and prune in bands (see scene/broadphase.hpp for the method).
//
// Costs per call on n boxes that moved a little: O(n) to find the bands and to repair the
// order, O(listings) to fill the bands, O(tests) for the sweep, O(pairs + n) for the output
// order. Measured on the demo scene (1000 bodies, `gjklab simulate` between calls, so the
// caches are cold): a data-dependent branch per listing or per test, and writes that go to
// many places at once, cost more than the tests themselves; the loops below avoid both.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "gjklab/scene/broadphase.hpp"
#include "pair_order.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace gjklab::scene {

namespace {

/// Band side over the median box's width across the sweep axis. 1 to 1.5 measure the same on
/// the demo scene within noise: narrower bands list a box more often, wider ones test more.
constexpr double kBandFactor = 1.25;
/// Boxes wider than this many bands go aside (tested against every box).
constexpr double kAsideBands = 4;
/// Tests per step of the sweep's inner loop: a box meets about two later ones in its band,
/// and a loop whose exit depends on the data mispredicts about once per box.
constexpr std::uint32_t kUnroll = 4;

/// Finite and not inverted: the boxes the bands can hold.
bool regular(const Aabb& b) {
  return b.lower.allFinite() && b.upper.allFinite() && (b.lower.array() <= b.upper.array()).all();
}

}  // namespace

void SweepAndPrune::find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  out.clear();
  if (boxes.size() >= (std::size_t{1} << 30))
    throw std::length_error("sweep and prune: more than 2^30 - 1 boxes");
  const auto n = static_cast<std::uint32_t>(boxes.size());
  if (n == 0) return;
  const int previous_axis = axis_;
  choose_axis(boxes);
  assign_bands(boxes);
  sort_order(order_.size() != n || axis_ != previous_axis);
  fill_bands(list_boxes());
  const std::size_t found = sweep_bands();
  out.assign(found_.begin(), found_.begin() + static_cast<std::ptrdiff_t>(found));
  aside_pairs(boxes, out);
  detail::sort_pairs(out, n, sort_tmp_, sort_count_);
}

void SweepAndPrune::choose_axis(std::span<const Aabb> boxes) {
  // Spread of the centres per axis (m² × count) over a sample of about 64 boxes: enough to
  // tell the axes apart, and the choice only affects the speed.
  const std::size_t stride = std::max<std::size_t>(1, boxes.size() / 64);
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  std::uint32_t m = 0;
  for (std::size_t i = 0; i < boxes.size(); i += stride) {
    const Aabb& b = boxes[i];
    if (!regular(b)) continue;
    for (int a = 0; a < 3; ++a) {
      const double c = 0.5 * (b.lower[a] + b.upper[a]);
      sum[a] += c;
      sum2[a] += c * c;
    }
    ++m;
  }
  double spread[3];
  for (int a = 0; a < 3; ++a)
    spread[a] = sum2[a] - sum[a] * sum[a] / std::max<double>(m, 1);
  const int best = static_cast<int>(std::max_element(spread, spread + 3) - spread);
  // A new axis costs a full sort: only for a clearly better one (scenes often spread about
  // equally along two axes, and the choice must not flip between frames).
  if (axis_ < 0 || spread[best] > 1.5 * spread[axis_]) axis_ = best;
}

std::size_t SweepAndPrune::assign_bands(std::span<const Aabb> boxes) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  const int ax = axis_, u = (ax + 1) % 3, v = (ax + 2) % 3;
  // The median width of a sample of at most about 64 boxes (length units): exact enough for
  // a band side, and no sort of all n.
  sample_.clear();
  for (std::uint32_t i = 0; i < n; i += std::max<std::uint32_t>(1, n / 64))
    if (regular(boxes[i]))
      sample_.push_back(
          std::max(boxes[i].upper[u] - boxes[i].lower[u], boxes[i].upper[v] - boxes[i].lower[v]));
  double side = 1;
  if (!sample_.empty()) {
    std::nth_element(sample_.begin(), sample_.begin() + sample_.size() / 2, sample_.end());
    if (const double median = sample_[sample_.size() / 2]; median > 0) side = kBandFactor * median;
  }
  key_.resize(n + 1);
  upper_.resize(n + 1);
  across_.resize(n + 1);
  key_[n] = INFINITY;  // the sentinel: past the end of every band's list
  upper_[n] = -INFINITY;
  across_[n] = {0, 0, 0, 0};
  range_.resize(n);
  is_aside_.resize(n);
  aside_.clear();
  double lo_u = INFINITY, hi_u = -INFINITY, lo_v = INFINITY, hi_v = -INFINITY;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Aabb& b = boxes[i];
    const bool banded = regular(b) && b.upper[u] - b.lower[u] <= kAsideBands * side &&
                        b.upper[v] - b.lower[v] <= kAsideBands * side;
    // Boxes aside sort first (they are not swept); a key is never NaN, so the order is total.
    key_[i] = banded ? b.lower[ax] : -INFINITY;
    upper_[i] = b.upper[ax];
    across_[i] = {b.lower[u], b.lower[v], -b.upper[u], -b.upper[v]};
    is_aside_[i] = banded ? 0 : 1;
    if (!banded) {
      aside_.push_back(i);
      continue;
    }
    lo_u = std::min(lo_u, b.lower[u]);
    hi_u = std::max(hi_u, b.upper[u]);
    lo_v = std::min(lo_v, b.lower[v]);
    hi_v = std::max(hi_v, b.upper[v]);
  }
  band_start_.assign(2, 0);
  columns_ = 1;
  if (aside_.size() == n) return 1;
  // Scattered boxes: wider bands, at most about four per box.
  double su = side, sv = side;
  const double bands = ((hi_u - lo_u) / su + 1) * ((hi_v - lo_v) / sv + 1), cap = 4.0 * n + 64;
  if (!(bands <= cap)) {
    su *= std::sqrt(bands / cap);
    sv *= std::sqrt(bands / cap);
  }
  // One band along an axis whose extent overflows (bands of infinite side).
  const double iu = std::isfinite(su) ? 1 / su : 0, iv = std::isfinite(sv) ? 1 / sv : 0;
  const std::int32_t nu = iu > 0 ? static_cast<std::int32_t>((hi_u - lo_u) * iu) + 1 : 1;
  const std::int32_t nv = iv > 0 ? static_cast<std::int32_t>((hi_v - lo_v) * iv) + 1 : 1;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (is_aside_[i]) continue;
    const Aabb& b = boxes[i];
    // Offsets from the lowest bound are ≥ 0, so truncation is the floor; monotone in the
    // coordinate, so overlapping boxes share a band.
    auto band = [](double offset, double inverse, std::int32_t count) {
      return inverse > 0 ? std::min(static_cast<std::int32_t>(offset * inverse), count - 1) : 0;
    };
    range_[i] = {{band(b.lower[u] - lo_u, iu, nu), band(b.lower[v] - lo_v, iv, nv)},
                 {band(b.upper[u] - lo_u, iu, nu), band(b.upper[v] - lo_v, iv, nv)}};
  }
  columns_ = static_cast<std::uint32_t>(nu);
  band_start_.assign(static_cast<std::size_t>(nu) * nv + 1, 0);
  return band_start_.size() - 1;
}

void SweepAndPrune::sort_order(bool from_scratch) {
  const auto n = static_cast<std::uint32_t>(key_.size() - 1);  // without the sentinel
  if (from_scratch) {
    order_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i)
      order_[i] = i;
    std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) {
      return key_[a] < key_[b] || (key_[a] == key_[b] && a < b);
    });
    return;
  }
  // Insertion sort from the last call's order: nearly sorted, about n comparisons.
  for (std::uint32_t k = 1; k < n; ++k) {
    const std::uint32_t body = order_[k];
    const double key = key_[body];
    std::uint32_t m = k;
    for (; m > 0 && key_[order_[m - 1]] > key; --m)
      order_[m] = order_[m - 1];
    order_[m] = body;
  }
}

std::size_t SweepAndPrune::list_boxes() {
  // Listings in sweep order, written one after the other. Most boxes are narrower than a band
  // and touch one, two or four: those are listed without a loop, an absent neighbour (du or dv
  // 0) being written and then overwritten (the cursor does not advance).
  const std::uint32_t nu = columns_;
  listings_.resize(std::max<std::size_t>(listings_.size(), 4 * order_.size() + 4));
  std::size_t count = 0;
  for (std::uint32_t i : order_) {
    if (is_aside_[i]) continue;
    const Range& r = range_[i];
    const std::uint32_t du = r.hi[0] - r.lo[0], dv = r.hi[1] - r.lo[1];
    const std::uint32_t c = static_cast<std::uint32_t>(r.lo[1]) * nu + r.lo[0];
    if (listings_.size() < count + 4) listings_.resize(2 * (count + 4));
    if ((du | dv) <= 1) {
      listings_[count] = {c, i << 2 | 3u};
      count += 1;
      listings_[count] = {c + 1, i << 2 | 2u};
      count += du;
      listings_[count] = {c + nu, i << 2 | 1u};
      count += dv;
      listings_[count] = {c + nu + 1, i << 2};
      count += du & dv;
      continue;
    }
    for (std::int32_t y = r.lo[1]; y <= r.hi[1]; ++y)
      for (std::int32_t x = r.lo[0]; x <= r.hi[0]; ++x) {
        if (listings_.size() < count + 1) listings_.resize(2 * (count + 1));
        const auto first = static_cast<std::uint32_t>((r.lo[0] == x) | ((r.lo[1] == y) << 1));
        listings_[count++] = {static_cast<std::uint32_t>(y) * nu + x, i << 2 | first};
      }
  }
  return count;
}

void SweepAndPrune::fill_bands(std::size_t listings) {
  // A counting sort of the listings by band: stable, so each band's list stays in sweep order.
  for (std::size_t k = 0; k < listings; ++k)
    ++band_start_[listings_[k].band + 1];
  for (std::size_t c = 1; c < band_start_.size(); ++c)
    band_start_[c] += band_start_[c - 1];
  band_fill_.assign(band_start_.begin(), band_start_.end() - 1);
  // Padding after the last band, read (never counted) by the unrolled sweep: the sentinel.
  const auto sentinel = static_cast<std::uint32_t>(key_.size() - 1) << 2;
  entries_.resize(band_start_.back() + kUnroll);
  for (std::uint32_t k = 0; k < kUnroll; ++k)
    entries_[band_start_.back() + k] = sentinel;
  for (std::size_t k = 0; k < listings; ++k)
    entries_[band_fill_[listings_[k].band]++] = listings_[k].code;
}

std::size_t SweepAndPrune::sweep_bands() {
  std::size_t count = 0;
  for (std::size_t c = 0; c + 1 < band_start_.size(); ++c) {
    const std::uint32_t begin = band_start_[c], end = band_start_[c + 1];
    // Room for every test's write (a miss writes too, and is not counted); found_ only grows.
    const std::size_t room = count + std::size_t{end - begin} * (end - begin + kUnroll);
    if (found_.size() < room) found_.resize(2 * room);
    for (std::uint32_t p = begin; p < end; ++p) {
      const std::uint32_t a = entries_[p] >> 2, a_first = entries_[p] & 3u;
      const double a_upper = upper_[a];
#if defined(__SSE2__)
      const __m128d upper = _mm_setr_pd(-across_[a].neg_hi_u, -across_[a].neg_hi_v);
      const __m128d neg_lower = _mm_setr_pd(-across_[a].lo_u, -across_[a].lo_v);
#endif
      for (std::uint32_t q = p + 1;; q += kUnroll) {
        for (std::uint32_t k = 0; k < kUnroll; ++k) {
          const std::uint32_t b = entries_[q + k] >> 2, b_first = entries_[q + k] & 3u;
          const Across& x = across_[b];
#if defined(__SSE2__)
          const __m128d le = _mm_and_pd(_mm_cmple_pd(_mm_load_pd(&x.lo_u), upper),
                                        _mm_cmple_pd(_mm_load_pd(&x.neg_hi_u), neg_lower));
          const bool across = _mm_movemask_pd(le) == 3;
#else
          const Across& y = across_[a];
          const bool across = (x.lo_u <= -y.neg_hi_u) & (x.lo_v <= -y.neg_hi_v) &
                              (x.neg_hi_u <= -y.lo_u) & (x.neg_hi_v <= -y.lo_v);
#endif
          // Along the sweep axis b starts at or after a (sorted), so key ≤ a's upper bound is
          // the whole test there. The band reports the pair only if it holds the lower corner
          // of the two boxes' band ranges, i.e. one of them starts here along each axis.
          const bool own = (a_first | b_first) == 3u;
          found_[count] = detail::ordered(a, b);
          count += (q + k < end) & (key_[b] <= a_upper) & across & own;
        }
        if (q + kUnroll >= end || key_[entries_[q + kUnroll] >> 2] > a_upper) break;
      }
    }
  }
  return count;
}

void SweepAndPrune::aside_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) const {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t big : aside_)
    for (std::uint32_t j = 0; j < n; ++j)
      // Two boxes aside meet twice: reported when `big` is the smaller index.
      if (j != big && !(is_aside_[j] && j < big) && boxes[big].overlaps(boxes[j]))
        out.push_back(detail::ordered(big, j));
}

}  // namespace gjklab::scene
