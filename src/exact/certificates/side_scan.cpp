#include "exact/certificates/side_scan.hpp"

#include <immintrin.h>

#include <algorithm>
#include <cmath>

namespace gjklab::exact::detail {

namespace {

/// The scan's per-point test, with everything fixed for one cloud: the signed direction, its
/// error weights and the reference point.
struct SideTest {
  double d0, d1, d2, w0, w1, w2;
  Vec3 ref;
  static constexpr double kUnderflow = 0x1p-1070;
  static constexpr double kBoundSafety = 1 + 0x1p-40;
};

/// Decides one point: 1 clearly on the plane's right side, −1 clearly on the wrong side, 0 too
/// close to call (|computed value| within the bound; NaN from an overflowing x − x_r too).
int side_of(const SideTest& t, const Vec3& p) {
  const double x = p.x() - t.ref.x(), y = p.y() - t.ref.y(), z = p.z() - t.ref.z();
  const double value = (t.d0 * x + t.d1 * y) + t.d2 * z;
  const double bound =
      ((t.w0 * std::abs(x) + t.w1 * std::abs(y)) + t.w2 * std::abs(z) + SideTest::kUnderflow) *
      SideTest::kBoundSafety;
  if (value > bound) return 1;
  if (-value > bound) return -1;
  return 0;
}

/// side_of for the points [begin, end) not clearly right: false when one is clearly wrong, else
/// the ties (points too close to call, other than the feature's own) go to `ties`.
bool classify(std::span<const Vec3> cloud, std::size_t begin, std::size_t end, const SideTest& t,
              std::span<const std::int32_t> skip, Ties& ties) {
  for (std::size_t i = begin; i < end; ++i) {
    const int side = side_of(t, cloud[i]);
    if (side > 0) continue;
    if (side < 0) return false;
    if (std::find(skip.begin(), skip.end(), static_cast<std::int32_t>(i)) == skip.end())
      ties.push_back(i);
  }
  return true;
}

bool has_avx2() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2");
}

/// The same test four points at a time: the first index of each block of four whose points are
/// not all clearly right is handed to `classify` (the same arithmetic per point, so the same
/// decisions: the bound holds for any order of the sums, and there is no FMA in this target).
/// Returns the number of points covered (a multiple of four).
[[gnu::target("avx2")]] std::size_t scan_blocks_avx2(std::span<const Vec3> cloud, const SideTest& t,
                                                     std::span<const std::int32_t> skip, Ties& ties,
                                                     bool& wrong) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "points packed as x, y, z");
  const std::size_t blocks = cloud.size() / 4;
  const double* data = cloud.data()->data();
  const __m256d d0 = _mm256_set1_pd(t.d0), d1 = _mm256_set1_pd(t.d1), d2 = _mm256_set1_pd(t.d2);
  const __m256d w0 = _mm256_set1_pd(t.w0), w1 = _mm256_set1_pd(t.w1), w2 = _mm256_set1_pd(t.w2);
  const __m256d rx = _mm256_set1_pd(t.ref.x()), ry = _mm256_set1_pd(t.ref.y()),
                rz = _mm256_set1_pd(t.ref.z());
  const __m256d sign_bit = _mm256_set1_pd(-0.0);
  const __m256d underflow = _mm256_set1_pd(SideTest::kUnderflow);
  const __m256d safety = _mm256_set1_pd(SideTest::kBoundSafety);
  for (std::size_t k = 0; k < blocks; ++k) {
    // Points 4k … 4k+3 as three loads, a = (x0 y0 z0 x1), b = (y1 z1 x2 y2), c = (z2 x3 y3 z3),
    // regrouped into x, y, z by blends and lane permutations (gathers cost more here).
    const double* p = data + 12 * k;
    const __m256d a = _mm256_loadu_pd(p), b = _mm256_loadu_pd(p + 4), c = _mm256_loadu_pd(p + 8);
    const __m256d xs = _mm256_permute4x64_pd(
        _mm256_blend_pd(_mm256_blend_pd(a, b, 0b0100), c, 0b0010), 0x6C);  // (x0 x3 x2 x1)
    const __m256d ys = _mm256_permute4x64_pd(
        _mm256_blend_pd(_mm256_blend_pd(a, b, 0b1001), c, 0b0100), 0xB1);  // (y1 y0 y3 y2)
    const __m256d zs = _mm256_permute4x64_pd(
        _mm256_blend_pd(_mm256_blend_pd(a, b, 0b0010), c, 0b1001), 0xC6);  // (z2 z1 z0 z3)
    const __m256d x = _mm256_sub_pd(xs, rx), y = _mm256_sub_pd(ys, ry), z = _mm256_sub_pd(zs, rz);
    const __m256d value = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(d0, x), _mm256_mul_pd(d1, y)),
                                        _mm256_mul_pd(d2, z));
    const __m256d ax = _mm256_andnot_pd(sign_bit, x), ay = _mm256_andnot_pd(sign_bit, y),
                  az = _mm256_andnot_pd(sign_bit, z);
    const __m256d sum =
        _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(w0, ax), _mm256_mul_pd(w1, ay)),
                                    _mm256_mul_pd(w2, az)),
                      underflow);
    const __m256d bound = _mm256_mul_pd(sum, safety);
    if (_mm256_movemask_pd(_mm256_cmp_pd(value, bound, _CMP_GT_OQ)) == 0xF) continue;
    if (!classify(cloud, 4 * k, 4 * k + 4, t, skip, ties)) {
      wrong = true;
      return 4 * k;
    }
  }
  return 4 * blocks;
}

}  // namespace

/// Scans a cloud: every x must satisfy sign·d·(x − x_r) ≥ 0. False when a point is decided on
/// the wrong side; points too close to call go to `ties` (those in `skip`, the feature's own
/// points, lie on the plane exactly and need no test).
bool scan_side(std::span<const Vec3> cloud, const Vec3& ref, const ScanDirection& s, double sign,
               std::span<const std::int32_t> skip, Ties& ties) {
  static const bool avx2 = has_avx2();
  const SideTest t{sign * s.d[0], sign * s.d[1], sign * s.d[2], s.w[0], s.w[1], s.w[2], ref};
  std::size_t done = 0;
  if (avx2) {
    bool wrong = false;
    done = scan_blocks_avx2(cloud, t, skip, ties, wrong);
    if (wrong) return false;
  }
  return classify(cloud, done, cloud.size(), t, skip, ties);
}

}  // namespace gjklab::exact::detail
