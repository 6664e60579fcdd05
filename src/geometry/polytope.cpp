#include "gjklab/geometry/polytope.hpp"

#include <immintrin.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>

namespace gjklab {

std::string describe_invalid_cloud(std::span<const Vec3> cloud) {
  if (cloud.empty()) return "empty point cloud";
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud[i].allFinite()) {
      std::ostringstream out;
      out << "non-finite coordinate in point " << i;
      return out.str();
    }
  }
  return {};
}

namespace {

/// A cloud's mean and box, from the pass that also lays out its blocks.
struct CloudMeasures {
  Vec3 mean, lower, upper;
};

/// A point in two SSE2 registers: (x, y) and (z, 0). Every x86-64 processor has SSE2; its
/// lane arithmetic is IEEE double arithmetic, so each lane computes what the scalar code would.
struct Point2 {
  __m128d xy, z;
};

/// Point i of rows of any strides; the bytes are copied, so no alignment is assumed.
struct StridedRows {
  const char* data;
  std::ptrdiff_t row, column;  // bytes
  [[gnu::always_inline]] Point2 operator()(std::size_t i) const {
    const char* p = data + static_cast<std::ptrdiff_t>(i) * row;
    double x, y, z;
    std::memcpy(&x, p, sizeof x);
    std::memcpy(&y, p + column, sizeof y);
    std::memcpy(&z, p + 2 * column, sizeof z);
    return {_mm_set_pd(y, x), _mm_set_sd(z)};
  }
  static constexpr bool kContiguous = false;
};

/// Point i of contiguous rows (a C-contiguous n×3 array, or a std::vector<Vec3>'s storage).
struct ContiguousRows {
  const char* data;
  [[gnu::always_inline]] Point2 operator()(std::size_t i) const {
    const double* p = reinterpret_cast<const double*>(data + 3 * sizeof(double) * i);
    return {_mm_loadu_pd(p), _mm_load_sd(p + 2)};
  }
  static constexpr bool kContiguous = true;
};

/// The running measures of one pass, in registers. The sum's order fixes its bits: it is
/// taken from zero, point after point (as Vec3 += would). The box takes std::min / std::max
/// semantics (min_pd(v, m) is v < m ? v : m, as std::min(m, v)); its bounds' values do not
/// depend on the order, and fix_zero_signs settles the one thing that would. The z registers'
/// upper lanes are unused.
struct Running {
  __m128d sxy = _mm_setzero_pd(), sz = _mm_setzero_pd();
  __m128d lxy, lz, hxy, hz;
  explicit Running(const Point2& first) : lxy(first.xy), lz(first.z), hxy(lxy), hz(lz) {}
  [[gnu::always_inline]] void take(const Point2& v) {
    sxy = _mm_add_pd(sxy, v.xy);
    sz = _mm_add_sd(sz, v.z);
    lxy = _mm_min_pd(v.xy, lxy);
    lz = _mm_min_sd(v.z, lz);
    hxy = _mm_max_pd(v.xy, hxy);
    hz = _mm_max_sd(v.z, hz);
  }
  static Vec3 vec(__m128d xy, __m128d z) {
    return Vec3(_mm_cvtsd_f64(xy), _mm_cvtsd_f64(_mm_unpackhi_pd(xy, xy)), _mm_cvtsd_f64(z));
  }
};

/// Writes point v as lane l of block b.
[[gnu::always_inline]] inline void to_block(const Point2& v, Polytope::Block& b, int l) {
  _mm_storel_pd(&b.x[l], v.xy);
  _mm_storeh_pd(&b.y[l], v.xy);
  _mm_store_sd(&b.z[l], v.z);
}

/// Writes point v to *out.
[[gnu::always_inline]] inline void to_vertex(const Point2& v, Vec3* out) {
  _mm_storeu_pd(out->data(), v.xy);
  _mm_store_sd(out->data() + 2, v.z);
}

/// The box's bounds as point-after-point std::min / std::max give them. Two doubles that
/// compare equal are the same double, except +0 and −0; so a bound found in another order has
/// the right value, and only a zero bound may have the wrong sign. Point after point, the bound
/// is the coordinate of the first point that attains it (before it every value is strictly
/// beyond it, after it none is): for a zero bound, that point is looked up.
template <class Rows>
void fix_zero_signs(const Rows& rows, std::size_t n, CloudMeasures& m) {
  for (Vec3* bound : {&m.lower, &m.upper}) {
    for (int c = 0; c < 3; ++c) {
      if ((*bound)[c] != 0) continue;
      for (std::size_t i = 0; i < n; ++i) {
        const Point2 v = rows(i);
        if (const double x = Running::vec(v.xy, v.z)[c]; x == 0) {
          (*bound)[c] = x;
          break;
        }
      }
    }
  }
}

/// The pass from block `first_block` on, continuing `r` (the blocks before it done by the
/// AVX2 kernel below): copies the points to `out` (kCopy; else the points are already there),
/// fills the scan's blocks (the last padded with the last point) and measures the cloud.
/// Finiteness costs nothing per point: a NaN or infinite coordinate makes its sum NaN or
/// infinite for good, so only a cloud whose sum is not finite (that, or an overflow) is
/// searched for the point to name. `out` must not overlap the points.
template <bool kCopy, class Rows>
[[gnu::always_inline]] inline CloudMeasures fill(const Rows& rows, std::size_t n, Vec3* out,
                                                 Polytope::Block* blocks, std::size_t first_block,
                                                 Running r) {
  constexpr int kB = Polytope::kBlock;
  const std::size_t full = n / kB;
  for (std::size_t k = first_block; k < full; ++k) {
    Polytope::Block& b = blocks[k];
    const std::size_t i = k * kB;
    for (int l = 0; l < kB; ++l) {
      const Point2 v = rows(i + static_cast<std::size_t>(l));
      to_block(v, b, l);
      if constexpr (kCopy && !Rows::kContiguous) to_vertex(v, out + i + l);
      r.take(v);
    }
    // Contiguous rows are Vec3's layout: the block's points are copied whole.
    if constexpr (kCopy && Rows::kContiguous)
      std::memcpy(static_cast<void*>(out + i), rows.data + 3 * sizeof(double) * i,
                  kB * sizeof(Vec3));
  }
  if (full * kB < n) {  // the last block, padded with copies of the last point
    Polytope::Block& b = blocks[full];
    for (int l = 0; l < kB; ++l) {
      const std::size_t i = full * kB + static_cast<std::size_t>(l);
      const Point2 v = rows(std::min(i, n - 1));
      to_block(v, b, l);
      if (i < n) {
        if constexpr (kCopy) to_vertex(v, out + i);
        r.take(v);
      }
    }
  }
  const Vec3 sum = Running::vec(r.sxy, r.sz);
  if (!is_finite(sum)) {
    for (std::size_t i = 0; i < n; ++i) {
      const Point2 v = rows(i);
      if (!Running::vec(v.xy, v.z).allFinite())
        throw InvalidGeometry("non-finite coordinate in point " + std::to_string(i));
    }
  }
  // The mean divided by n, not multiplied by 1/n: as Vec3 / double.
  CloudMeasures m{sum / static_cast<double>(n), Running::vec(r.lxy, r.lz),
                  Running::vec(r.hxy, r.hz)};
  fix_zero_signs(rows, n, m);
  return m;
}

/// The blocks' rows of four contiguous points m0 = (x0 y0 z0 x1), m1 = (y1 z1 x2 y2),
/// m2 = (z2 x3 y3 z3): two blends and one permutation per row. The box takes the rows before
/// their permutation (lane order does not matter to its values; see `fix_zero_signs`).
[[gnu::target("avx2"), gnu::always_inline]] inline void transpose4(__m256d m0, __m256d m1,
                                                                   __m256d m2, double* x, double* y,
                                                                   double* z, __m256d lo[3],
                                                                   __m256d hi[3]) {
  // (x0 x3 x2 x1), (y1 y0 y3 y2), (z2 z1 z0 z3), then into order.
  const __m256d rows[3] = {_mm256_blend_pd(_mm256_blend_pd(m0, m1, 0b0100), m2, 0b0010),
                           _mm256_blend_pd(_mm256_blend_pd(m0, m1, 0b1001), m2, 0b0100),
                           _mm256_blend_pd(_mm256_blend_pd(m0, m1, 0b0010), m2, 0b1001)};
  for (int c = 0; c < 3; ++c) {
    lo[c] = _mm256_min_pd(rows[c], lo[c]);
    hi[c] = _mm256_max_pd(rows[c], hi[c]);
  }
  _mm256_store_pd(x, _mm256_permute4x64_pd(rows[0], 0b01101100));  // lanes 0 3 2 1
  _mm256_store_pd(y, _mm256_permute4x64_pd(rows[1], 0b10110001));  // lanes 1 0 3 2
  _mm256_store_pd(z, _mm256_permute4x64_pd(rows[2], 0b11000110));  // lanes 2 1 0 3
}

/// The smallest / largest of four lanes (as values: a zero's sign is fixed later).
[[gnu::target("avx2"), gnu::always_inline]] inline double lanes_min(__m256d v) {
  const __m128d h = _mm_min_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_min_sd(h, _mm_unpackhi_pd(h, h)));
}
[[gnu::target("avx2"), gnu::always_inline]] inline double lanes_max(__m256d v) {
  const __m128d h = _mm_max_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_max_sd(h, _mm_unpackhi_pd(h, h)));
}

/// AVX2 (no FMA: nothing here multiplies) for blocks [0, count) of contiguous points, where
/// the point after the last of them exists: each point is read as four doubles (x y z and the
/// next x, which the sum ignores), so its sum is one instruction in vertex order; a block is
/// transposed in registers, and the box taken on its rows, lane by lane. Continues and returns
/// r. The sum's additions depend each on the last (about 0.45 ns per point, the floor of this
/// pass); the loads, shuffles, box and stores run beside them.
template <bool kCopy>
[[gnu::target("avx2")]] Running fill_blocks_avx2(const double* p, std::size_t count, Vec3* out,
                                                 Polytope::Block* blocks, Running r) {
  __m256d sum = _mm256_set_m128d(r.sz, r.sxy);
  const Vec3 l = Running::vec(r.lxy, r.lz), h = Running::vec(r.hxy, r.hz);
  __m256d lo[3], hi[3];
  for (int c = 0; c < 3; ++c) {
    lo[c] = _mm256_set1_pd(l[c]);
    hi[c] = _mm256_set1_pd(h[c]);
  }
  for (std::size_t k = 0; k < count; ++k, p += 3 * Polytope::kBlock) {
    for (int j = 0; j < Polytope::kBlock; ++j)
      sum = _mm256_add_pd(sum, _mm256_loadu_pd(p + 3 * j));
    const __m256d m[6] = {_mm256_loadu_pd(p),      _mm256_loadu_pd(p + 4),
                          _mm256_loadu_pd(p + 8),  _mm256_loadu_pd(p + 12),
                          _mm256_loadu_pd(p + 16), _mm256_loadu_pd(p + 20)};
    Polytope::Block& b = blocks[k];
    transpose4(m[0], m[1], m[2], b.x, b.y, b.z, lo, hi);
    transpose4(m[3], m[4], m[5], b.x + 4, b.y + 4, b.z + 4, lo, hi);
    if constexpr (kCopy) {
      double* o = (out + k * Polytope::kBlock)->data();
      for (int j = 0; j < 6; ++j)
        _mm256_storeu_pd(o + 4 * j, m[j]);
    }
  }
  r.sxy = _mm256_castpd256_pd128(sum);
  r.sz = _mm256_extractf128_pd(sum, 1);
  r.lxy = _mm_set_pd(lanes_min(lo[1]), lanes_min(lo[0]));
  r.lz = _mm_set_sd(lanes_min(lo[2]));
  r.hxy = _mm_set_pd(lanes_max(hi[1]), lanes_max(hi[0]));
  r.hz = _mm_set_sd(lanes_max(hi[2]));
  return r;
}

bool has_avx2() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2");
}

/// The pass over contiguous points: the AVX2 kernel where the processor has it, for the blocks
/// whose points it may read four doubles at a time, then the SSE2 pass for the rest.
template <bool kCopy>
CloudMeasures fill_contiguous(const char* data, std::size_t n, Vec3* out, Polytope::Block* blocks) {
  static const bool avx2 = has_avx2();  // local: polytopes may be built during static init
  const ContiguousRows rows{data};
  Running r(rows(0));
  // Blocks [0, m) hold points up to 8m − 1, and point 8m must exist: m = (n − 1) / 8.
  const std::size_t m = avx2 ? (n - 1) / Polytope::kBlock : 0;
  if (m > 0) r = fill_blocks_avx2<kCopy>(reinterpret_cast<const double*>(data), m, out, blocks, r);
  return fill<kCopy>(rows, n, out, blocks, m, r);
}

CloudMeasures fill_strided(const CoordinateRows& rows, Vec3* out, Polytope::Block* blocks) {
  const StridedRows points{static_cast<const char*>(rows.data), rows.row_stride,
                           rows.column_stride};
  return fill<true>(points, rows.count, out, blocks, 0, Running(points(0)));
}

/// Fills `vertices` and `blocks` (resized, their capacity reused) from rows, and measures.
CloudMeasures fill_from(const CoordinateRows& rows, std::vector<Vec3>& vertices,
                        std::vector<Polytope::Block>& blocks) {
  if (rows.count == 0) throw InvalidGeometry(describe_invalid_cloud({}));
  vertices.resize(rows.count);
  blocks.resize((rows.count + Polytope::kBlock - 1) / Polytope::kBlock);
  // The fast path reads doubles in place, so it also needs them aligned (NumPy's may not be).
  const bool contiguous = rows.row_stride == static_cast<std::ptrdiff_t>(3 * sizeof(double)) &&
                          rows.column_stride == static_cast<std::ptrdiff_t>(sizeof(double)) &&
                          reinterpret_cast<std::uintptr_t>(rows.data) % alignof(double) == 0;
  return contiguous ? fill_contiguous<true>(static_cast<const char*>(rows.data), rows.count,
                                            vertices.data(), blocks.data())
                    : fill_strided(rows, vertices.data(), blocks.data());
}

// ---- the blocked scan --------------------------------------------------------------------
//
// Each lane l of the eight keeps the largest dot product it has seen (strictly greater wins,
// so it keeps its first maximiser) and the block where it saw it. The answer is, among the
// lanes holding the overall maximum, the smallest vertex index block·8 + l: the first vertex
// of the cloud attaining the maximum. NaN dot products never compare greater, so they are
// skipped, as in the textbook loop once its running maximum is a number.

using V4d = double __attribute__((vector_size(32)));
using V4i = std::int64_t __attribute__((vector_size(32)));
static_assert(Polytope::kBlock == 8, "the scan handles a block as two groups of four lanes");

/// Reads four doubles of a block (blocks are 64-byte aligned, so every group of four is
/// 32-byte aligned); may_alias makes reading doubles through the vector type legal.
using V4dLoad = double __attribute__((vector_size(32), may_alias));
#define GJKLAB_LOAD4(p) (*reinterpret_cast<const V4dLoad*>(p))

/// The direction d in every lane.
struct Direction4 {
  V4d x, y, z;
  Direction4(double dx, double dy, double dz)
      : x{dx, dx, dx, dx}, y{dy, dy, dy, dy}, z{dz, dz, dz, dz} {}
};

/// The running maxima of the eight lanes over some of the blocks, with the block where each
/// lane saw its maximum.
struct LaneMaxima {
  V4d m0, m1;
  V4i i0, i1;

  static LaneMaxima empty() {
    constexpr double lowest = -std::numeric_limits<double>::infinity();
    const V4d m = {lowest, lowest, lowest, lowest};
    const V4i i = {0, 0, 0, 0};
    return {m, m, i, i};
  }

  /// Takes block `blk` (number b in every lane) into the maxima.
  [[gnu::always_inline]] void absorb(const Polytope::Block& blk, V4i b, const Direction4& d) {
    // The same operations in the same order as Eigen's Vec3::dot: (x·dx + y·dy) + z·dz.
    const V4d d0 =
        (GJKLAB_LOAD4(blk.x) * d.x + GJKLAB_LOAD4(blk.y) * d.y) + GJKLAB_LOAD4(blk.z) * d.z;
    const V4d d1 = (GJKLAB_LOAD4(blk.x + 4) * d.x + GJKLAB_LOAD4(blk.y + 4) * d.y) +
                   GJKLAB_LOAD4(blk.z + 4) * d.z;
    const V4i g0 = d0 > m0, g1 = d1 > m1;
    m0 = g0 ? d0 : m0;
    m1 = g1 ? d1 : m1;
    i0 = g0 ? b : i0;
    i1 = g1 ? b : i1;
  }

  /// Largest value held (never NaN: lanes start at −∞ and only take d > m).
  double top() const {
    const V4d m = m0 > m1 ? m0 : m1;
    return std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
  }

  /// Smallest vertex index block·8 + lane among the lanes holding `top` (none if no lane does).
  std::int64_t first_index_of(double top) const {
    constexpr std::int64_t none = std::numeric_limits<std::int64_t>::max();
    const V4d top4 = {top, top, top, top};
    const V4i none4 = {none, none, none, none};
    const V4i lane0 = {0, 1, 2, 3}, lane1 = {4, 5, 6, 7};
    const V4i c0 = m0 == top4 ? i0 * Polytope::kBlock + lane0 : none4;
    const V4i c1 = m1 == top4 ? i1 * Polytope::kBlock + lane1 : none4;
    const V4i c = c0 < c1 ? c0 : c1;
    return std::min(std::min(c[0], c[1]), std::min(c[2], c[3]));
  }
};

/// The first vertex of the lanes' maxima. Branch-free: which lane wins is data-dependent, so
/// compare-and-branch code mispredicts on nearly every call.
[[gnu::always_inline]] inline std::size_t winner(const LaneMaxima& lanes) {
  return static_cast<std::size_t>(lanes.first_index_of(lanes.top()));
}

[[gnu::always_inline]] inline std::size_t scan_blocks(const Polytope::Block* blocks,
                                                      std::size_t count, double dx, double dy,
                                                      double dz) {
  const Direction4 d(dx, dy, dz);
  LaneMaxima lanes = LaneMaxima::empty();
  V4i b = {0, 0, 0, 0};
  const V4i one = {1, 1, 1, 1};
  // (Splitting even and odd blocks into two sets of lanes, to shorten the compare-and-select
  // chain, measured slower.)
  for (std::size_t k = 0; k < count; ++k, b += one)
    lanes.absorb(blocks[k], b, d);
  return winner(lanes);
}

std::size_t scan_default(const Polytope::Block* blocks, std::size_t count, double dx, double dy,
                         double dz) {
  return scan_blocks(blocks, count, dx, dy, dz);
}

// The same code for AVX2 (four doubles per instruction). Only "avx2" is enabled, not "fma":
// products and sums stay separately rounded, so the answers are those of the default build.
[[gnu::target("avx2")]] std::size_t scan_avx2(const Polytope::Block* blocks, std::size_t count,
                                              double dx, double dy, double dz) {
  return scan_blocks(blocks, count, dx, dy, dz);
}

/// Two scans in one call: the support of one shape in d and of another in −d. Both loops sit
/// in one function body, so the processor overlaps the two independent searches instead of
/// finishing the first before it starts the second.
struct ScanPairAnswer {
  std::size_t a, b;
};

[[gnu::always_inline]] inline ScanPairAnswer scan_pair_blocks(const Polytope::Block* a,
                                                              std::size_t a_count,
                                                              const Polytope::Block* b,
                                                              std::size_t b_count, double dx,
                                                              double dy, double dz) {
  const Direction4 da(dx, dy, dz), db(-dx, -dy, -dz);
  LaneMaxima la = LaneMaxima::empty(), lb = LaneMaxima::empty();
  V4i blk = {0, 0, 0, 0};
  const V4i one = {1, 1, 1, 1};
  // Block k of both shapes in one step: the compiler keeps two searches in flight (written as
  // two loops, it finishes the first, reduction included, before it starts the second).
  const std::size_t common = std::min(a_count, b_count);
  std::size_t k = 0;
  for (; k < common; ++k, blk += one) {
    la.absorb(a[k], blk, da);
    lb.absorb(b[k], blk, db);
  }
  // The longer shape's remaining blocks (at most one of these two loops runs).
  for (V4i rest = blk; k < a_count; ++k, rest += one)
    la.absorb(a[k], rest, da);
  for (k = common; k < b_count; ++k, blk += one)
    lb.absorb(b[k], blk, db);
  return {winner(la), winner(lb)};
}

ScanPairAnswer scan_pair_default(const Polytope::Block* a, std::size_t a_count,
                                 const Polytope::Block* b, std::size_t b_count, double dx,
                                 double dy, double dz) {
  return scan_pair_blocks(a, a_count, b, b_count, dx, dy, dz);
}

[[gnu::target("avx2")]] ScanPairAnswer scan_pair_avx2(const Polytope::Block* a, std::size_t a_count,
                                                      const Polytope::Block* b, std::size_t b_count,
                                                      double dx, double dy, double dz) {
  return scan_pair_blocks(a, a_count, b, b_count, dx, dy, dz);
}

using ScanFunction = std::size_t (*)(const Polytope::Block*, std::size_t, double, double, double);
using ScanPairFunction = ScanPairAnswer (*)(const Polytope::Block*, std::size_t,
                                            const Polytope::Block*, std::size_t, double, double,
                                            double);

const ScanFunction scan = has_avx2() ? scan_avx2 : scan_default;
const ScanPairFunction scan_pair = has_avx2() ? scan_pair_avx2 : scan_pair_default;

#undef GJKLAB_LOAD4

}  // namespace

namespace {
/// Source of Polytope ids (0 is never handed out).
std::atomic<std::uint64_t> next_polytope_id{1};
}  // namespace

Polytope::Polytope(std::vector<Vec3> vertices) : vertices_(std::move(vertices)) {
  if (vertices_.empty()) throw InvalidGeometry(describe_invalid_cloud(vertices_));
  blocks_.resize((vertices_.size() + kBlock - 1) / kBlock);
  // The points are read where they are: nothing to copy.
  const CloudMeasures m = fill_contiguous<false>(reinterpret_cast<const char*>(vertices_.data()),
                                                 vertices_.size(), nullptr, blocks_.data());
  take_measures(m.mean, m.lower, m.upper);
}

Polytope::Polytope(const CoordinateRows& rows) {
  const CloudMeasures m = fill_from(rows, vertices_, blocks_);
  take_measures(m.mean, m.lower, m.upper);
}

void Polytope::assign(const CoordinateRows& rows) {
  graph_.reset();
  start_table_.clear();
  table_resolution_ = 1;
  hint_.store(0);
  try {
    const CloudMeasures m = fill_from(rows, vertices_, blocks_);
    take_measures(m.mean, m.lower, m.upper);
  } catch (const InvalidGeometry&) {
    // Left valid: the point at the origin (no allocation: one point fits what was there).
    const Vec3 origin = Vec3::Zero();
    const CloudMeasures m = fill_from(CoordinateRows{origin.data(), 1}, vertices_, blocks_);
    take_measures(m.mean, m.lower, m.upper);
    throw;
  }
}

void Polytope::take_measures(const Vec3& mean, const Vec3& lower, const Vec3& upper) {
  mean_ = mean;
  box_lower_ = lower;
  box_upper_ = upper;
  box_extent_ = (box_upper_ - box_lower_).maxCoeff();
  max_magnitude_ = std::max(box_lower_.cwiseAbs().maxCoeff(), box_upper_.cwiseAbs().maxCoeff());
  id_ = next_polytope_id.fetch_add(1, std::memory_order_relaxed);
}

Polytope::~Polytope() = default;

std::size_t Polytope::scan_support_index(const Vec3& d) const {
  // The textbook loop starts from vertex 0's dot product; if that is NaN nothing compares
  // greater and it returns 0. The blocked scan skips NaNs instead, so that case is decided here.
  if (std::isnan(vertices_[0].dot(d))) return 0;
  return scan(blocks_.data(), blocks_.size(), d.x(), d.y(), d.z());
}

std::pair<std::size_t, std::size_t> scan_support_pair(const Polytope& a, const Vec3& d,
                                                      const Polytope& b) {
  // As scan_support_index: a NaN first dot product answers vertex 0 (−d's is NaN with d's).
  if (std::isnan(a.vertices_[0].dot(d)) || std::isnan(b.vertices_[0].dot(d)))
    return {a.scan_support_index(d), b.scan_support_index(-d)};
  const ScanPairAnswer r = scan_pair(a.blocks_.data(), a.blocks_.size(), b.blocks_.data(),
                                     b.blocks_.size(), d.x(), d.y(), d.z());
  return {r.a, r.b};
}

// ---- transforms and measures ----------------------------------------------------------------

Polytope Polytope::transformed(const Pose& pose) const {
  std::vector<Vec3> moved;
  moved.reserve(vertices_.size());
  for (const Vec3& v : vertices_)
    moved.push_back(pose.apply(v));
  Polytope out(std::move(moved));
  out.graph_ = graph_;
  if (graph_) out.build_start_table();
  return out;
}

Polytope Polytope::translated(const Vec3& t) const {
  std::vector<Vec3> moved;
  moved.reserve(vertices_.size());
  for (const Vec3& v : vertices_)
    moved.push_back(v + t);
  Polytope out(std::move(moved));
  out.graph_ = graph_;
  if (graph_) out.build_start_table();
  return out;
}

Polytope Polytope::scaled(double factor) const {
  std::vector<Vec3> scaled_vertices;
  scaled_vertices.reserve(vertices_.size());
  for (const Vec3& v : vertices_)
    scaled_vertices.push_back(factor * v);
  Polytope out(std::move(scaled_vertices));
  out.graph_ = graph_;
  if (graph_) out.build_start_table();
  return out;
}

/// Diagonal of the cloud's bounding box grown by `radius` on every side.
static double cloud_diagonal(std::span<const Vec3> cloud, double radius = 0) {
  if (cloud.empty()) return 0;
  Vec3 lo = cloud[0], hi = cloud[0];
  for (const Vec3& v : cloud) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  if (radius == 0) return (hi - lo).norm();
  return (hi - lo + Vec3::Constant(2 * radius)).norm();
}

double Polytope::bounding_box_diagonal() const {
  return cloud_diagonal(vertices_);
}

double pair_size(std::span<const Vec3> a, std::span<const Vec3> b) {
  return std::max(cloud_diagonal(a), cloud_diagonal(b));
}

double pair_size(std::span<const Vec3> a, std::span<const Vec3> b, double radius_a,
                 double radius_b) {
  return std::max(cloud_diagonal(a, radius_a), cloud_diagonal(b, radius_b));
}

}  // namespace gjklab
