// Sweep and prune in bands (see scene/broadphase.hpp for the method).
//
// Costs per call on n boxes that moved a little: O(n) to find the axis, the bands and the
// repaired order, O(listings) to fill the bands, O(tests) for the sweep, O(pairs + n) for the
// output order. The inner loops are free of data-dependent branches: on the dense demo scene
// (1000 bodies) a mispredicted branch per listing or per test costs more than the tests.
#include <algorithm>
#include <cmath>
#include <limits>

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
  const auto n = static_cast<std::uint32_t>(boxes.size());
  if (n == 0) return;
  const int previous_axis = axis_;
  choose_axis(boxes);
  assign_bands(boxes);
  sort_order(order_.size() != n || axis_ != previous_axis);
  fill_bands(boxes);
  const std::size_t found = sweep_bands();
  out.assign(found_.begin(), found_.begin() + static_cast<std::ptrdiff_t>(found));
  aside_pairs(boxes, out);
  detail::sort_pairs(out, n, sort_tmp_, sort_count_);
}

void SweepAndPrune::choose_axis(std::span<const Aabb> boxes) {
  // Spread of the centres per axis (n × variance, m²).
  // Irregular boxes are marked aside here; assign_bands adds the wide ones.
  const auto n = static_cast<std::uint32_t>(boxes.size());
  is_aside_.resize(n);
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  std::uint32_t m = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Aabb& b = boxes[i];
    is_aside_[i] = !regular(b);
    if (is_aside_[i]) continue;
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
    if (!is_aside_[i])
      sample_.push_back(
          std::max(boxes[i].upper[u] - boxes[i].lower[u], boxes[i].upper[v] - boxes[i].lower[v]));
  double side = 1;
  if (!sample_.empty()) {
    std::nth_element(sample_.begin(), sample_.begin() + sample_.size() / 2, sample_.end());
    if (const double median = sample_[sample_.size() / 2]; median > 0) side = kBandFactor * median;
  }
  key_.resize(n);
  upper_.resize(n);
  range_.resize(n);
  aside_.clear();
  double lo_u = INFINITY, hi_u = -INFINITY, lo_v = INFINITY, hi_v = -INFINITY;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Aabb& b = boxes[i];
    const bool banded = !is_aside_[i] && b.upper[u] - b.lower[u] <= kAsideBands * side &&
                        b.upper[v] - b.lower[v] <= kAsideBands * side;
    // Boxes aside sort first (they are not swept); a key is never NaN, so the order is total.
    key_[i] = banded ? b.lower[ax] : -INFINITY;
    upper_[i] = b.upper[ax];
    if (!banded) {
      is_aside_[i] = 1;
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
  const auto nu = iu > 0 ? static_cast<std::int32_t>((hi_u - lo_u) * iu) + 1 : 1;
  const auto nv = iv > 0 ? static_cast<std::int32_t>((hi_v - lo_v) * iv) + 1 : 1;
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
  columns_ = nu;
  band_start_.assign(static_cast<std::size_t>(nu) * nv + 1, 0);
  return band_start_.size() - 1;
}

void SweepAndPrune::sort_order(bool from_scratch) {
  const auto n = static_cast<std::uint32_t>(key_.size());
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

void SweepAndPrune::fill_bands(std::span<const Aabb> boxes) {
  const int ax = axis_, u = (ax + 1) % 3, v = (ax + 2) % 3;
  const auto n = static_cast<std::uint32_t>(boxes.size());
  const std::size_t nu = static_cast<std::size_t>(columns_);
  // Most boxes are narrower than a band and touch one, two or four: those are counted and
  // listed without a loop. An absent neighbour (du or dv 0) aliases the box's own band and
  // adds nothing.
  for (std::uint32_t i = 0; i < n; ++i) {
    if (is_aside_[i]) continue;
    const Range& r = range_[i];
    const std::uint32_t du = r.hi[0] - r.lo[0], dv = r.hi[1] - r.lo[1];
    const std::size_t c = r.lo[1] * nu + r.lo[0] + 1;
    if ((du | dv) <= 1) {
      band_start_[c] += 1;
      band_start_[c + (du ? 1 : 0)] += du;
      band_start_[c + (dv ? nu : 0)] += dv;
      band_start_[c + (du ? 1 : 0) + (dv ? nu : 0)] += du & dv;
      continue;
    }
    for (std::int32_t y = r.lo[1]; y <= r.hi[1]; ++y)
      for (std::int32_t x = r.lo[0]; x <= r.hi[0]; ++x)
        ++band_start_[y * nu + x + 1];
  }
  for (std::size_t c = 1; c < band_start_.size(); ++c)
    band_start_[c] += band_start_[c - 1];
  // Padding after the last band, read (never counted) by the unrolled sweep.
  entries_.resize(band_start_.back() + kUnroll);
  for (std::uint32_t k = 0; k < kUnroll; ++k)
    entries_[band_start_.back() + k] = {INFINITY, 0, 0, 0, 0, 0, 0};
  band_fill_.assign(band_start_.begin(), band_start_.end() - 1);
  // Listed in sweep order, so that every band's list comes out sorted.
  for (std::uint32_t i : order_) {
    if (is_aside_[i]) continue;
    const Range& r = range_[i];
    const Aabb& b = boxes[i];
    Entry e{b.lower[ax], b.lower[u], b.lower[v], -b.upper[u], -b.upper[v], i, 3};
    const std::uint32_t du = r.hi[0] - r.lo[0], dv = r.hi[1] - r.lo[1];
    const std::size_t c = r.lo[1] * nu + r.lo[0];
    if ((du | dv) <= 1) {
      // An absent neighbour's write lands in a band written for real afterwards, and does
      // not advance it.
      const std::size_t c01 = c + (du ? 1 : 0), c10 = c + (dv ? nu : 0), c11 = c01 + (dv ? nu : 0);
      e.first = 0;
      entries_[band_fill_[c11]] = e;
      band_fill_[c11] += du & dv;
      e.first = 1;
      entries_[band_fill_[c10]] = e;
      band_fill_[c10] += dv;
      e.first = 2;
      entries_[band_fill_[c01]] = e;
      band_fill_[c01] += du;
      e.first = 3;
      entries_[band_fill_[c]++] = e;
      continue;
    }
    for (std::int32_t y = r.lo[1]; y <= r.hi[1]; ++y)
      for (std::int32_t x = r.lo[0]; x <= r.hi[0]; ++x) {
        e.first = static_cast<std::uint32_t>((r.lo[0] == x) | ((r.lo[1] == y) << 1));
        entries_[band_fill_[y * nu + x]++] = e;
      }
  }
}

std::size_t SweepAndPrune::sweep_bands() {
  std::size_t count = 0;
  for (std::size_t c = 0; c + 1 < band_start_.size(); ++c) {
    const std::uint32_t begin = band_start_[c], end = band_start_[c + 1];
    // Room for every test's write (a miss writes too, and is not counted); found_ only grows.
    const std::size_t room = count + std::size_t{end - begin} * (end - begin + kUnroll);
    if (found_.size() < room) found_.resize(2 * room);
    for (std::uint32_t p = begin; p < end; ++p) {
      const Entry& a = entries_[p];
      const double a_hi_x = upper_[a.body];
#if defined(__SSE2__)
      // b meets a when (b.lo_x, b.lo_u | b.lo_v, −b.hi_u | −b.hi_v) ≤ these, lane by lane.
      const __m128d h0 = _mm_setr_pd(a_hi_x, -a.neg_hi_u);
      const __m128d h1 = _mm_setr_pd(-a.neg_hi_v, -a.lo_u);
      const __m128d h2 = _mm_setr_pd(-a.lo_v, INFINITY);
#endif
      for (std::uint32_t q = p + 1;; q += kUnroll) {
        for (std::uint32_t k = 0; k < kUnroll; ++k) {
          const Entry& b = entries_[q + k];
#if defined(__SSE2__)
          const __m128d le = _mm_and_pd(_mm_and_pd(_mm_cmple_pd(_mm_load_pd(&b.lo_x), h0),
                                                   _mm_cmple_pd(_mm_load_pd(&b.lo_v), h1)),
                                        _mm_cmple_pd(_mm_load_sd(&b.neg_hi_v), h2));
          const bool meet = _mm_movemask_pd(le) == 3;
#else
          const bool meet = (b.lo_x <= a_hi_x) & (b.lo_u <= -a.neg_hi_u) & (b.lo_v <= -a.neg_hi_v) &
                            (b.neg_hi_u <= -a.lo_u) & (b.neg_hi_v <= -a.lo_v);
#endif
          // Along the sweep axis b starts at or after a (sorted), so b.lo_x ≤ a.hi_x is the
          // whole test there. The band reports the pair only if it holds the lower corner of
          // the two boxes' band ranges, i.e. one of them starts here along each axis.
          const bool own = ((a.first | b.first) & 3u) == 3u;
          found_[count] = detail::ordered(a.body, b.body);
          count += (q + k < end) & meet & own;
        }
        if (q + kUnroll >= end || entries_[q + kUnroll].lo_x > a_hi_x) break;
      }
    }
  }
  return count;
}

void SweepAndPrune::aside_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) const {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t big : aside_)
    for (std::uint32_t j = 0; j < n; ++j)
      // Two boxes aside meet twice: reported from the larger index only.
      if (j != big && !(is_aside_[j] && j < big) && boxes[big].overlaps(boxes[j]))
        out.push_back(detail::ordered(big, j));
}

}  // namespace gjklab::scene
