#include "gjklab/experiment/families.hpp"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/shapes.hpp"

namespace gjklab::experiment {

namespace {

// ---- seeding ----
//
// GSL's generators take 32-bit seeds (gsl_rng_mt19937 keeps the low 32 bits of its seed). A
// 64-bit hash of (seed, case id) truncated to 32 bits would give two cases of one experiment
// the same stream with probability ~n²/2³³ (even odds at 77 000 cases). Instead the
// experiment seed is mixed into a 64-bit key with splitmix64, and the case id goes through a
// bijection of 32-bit integers keyed by it: within an experiment, case ids below 2³² get
// pairwise different generator seeds, and the seeds of consecutive ids look unrelated.

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// MurmurHash3's finaliser: a bijection of 32-bit integers with full avalanche.
std::uint32_t fmix32(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bU;
  h ^= h >> 13;
  h *= 0xc2b2ae35U;
  h ^= h >> 16;
  return h;
}

}  // namespace

std::uint32_t case_stream_seed(std::uint64_t seed, std::uint64_t case_id) {
  const std::uint64_t key = splitmix64(seed);
  const auto lo = static_cast<std::uint32_t>(key);
  const auto hi = static_cast<std::uint32_t>(key >> 32);
  return fmix32(fmix32(static_cast<std::uint32_t>(case_id) + lo) ^ hi);
}

namespace {

struct RngDeleter {
  void operator()(gsl_rng* r) const { gsl_rng_free(r); }
};
using RngPtr = std::unique_ptr<gsl_rng, RngDeleter>;

RngPtr make_case_rng(std::uint64_t seed, std::uint64_t case_id) {
  RngPtr rng(gsl_rng_alloc(gsl_rng_mt19937));
  if (!rng) throw std::bad_alloc();
  gsl_rng_set(rng.get(), case_stream_seed(seed, case_id));
  return rng;
}

/// Uniform in [0, 1).
double uniform(gsl_rng* r) { return gsl_rng_uniform(r); }

/// Log-uniform in [lo, hi] (0 < lo <= hi).
double log_uniform(gsl_rng* r, const Interval& range) {
  const double u = uniform(r);
  if (range.lo == range.hi) return range.lo;
  return std::clamp(range.lo * std::pow(range.hi / range.lo, u), range.lo, range.hi);
}

/// Integer with P(n) ∝ log((n + 1) / n) on [lo, hi]: the floor of a log-uniform variate on
/// [lo, hi + 1), so every scale of vertex counts gets an equal share.
int log_uniform_count(gsl_rng* r, const Interval& range) {
  const double u = uniform(r);
  const double lo = range.lo;
  const double hi = range.hi;
  if (lo == hi) return static_cast<int>(lo);
  const double x = std::floor(lo * std::pow((hi + 1) / lo, u));
  return static_cast<int>(std::clamp(x, lo, hi));
}

Vec3 unit_vector(gsl_rng* r) {
  double x = 0, y = 0, z = 0;
  gsl_ran_dir_3d(r, &x, &y, &z);
  return {x, y, z};
}

/// A rotation uniform on SO(3): a normalised quaternion of four independent Gaussians.
Mat3 random_rotation(gsl_rng* r) {
  for (;;) {
    const double w = gsl_ran_gaussian(r, 1.0);
    const double x = gsl_ran_gaussian(r, 1.0);
    const double y = gsl_ran_gaussian(r, 1.0);
    const double z = gsl_ran_gaussian(r, 1.0);
    const Quat q(w, x, y, z);
    if (q.norm() > 1e-6) return q.normalized().toRotationMatrix();
  }
}

std::size_t draw_family(gsl_rng* r, const std::vector<FamilySpec>& families) {
  double total = 0;
  for (const FamilySpec& f : families) total += f.weight;
  const double target = uniform(r) * total;
  double cumulative = 0;
  for (std::size_t i = 0; i < families.size(); ++i) {
    cumulative += families[i].weight;
    if (target < cumulative) return i;
  }
  return families.size() - 1;
}

Vec3 vertex_mean(const std::vector<Vec3>& cloud) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : cloud) sum += p;
  return sum / static_cast<double>(cloud.size());
}

/// Generates one shape and moves it to the origin (vertex mean), rotates it there when asked,
/// and scales it.
std::vector<Vec3> make_shape(gsl_rng* r, ShapeKind kind, int n, const FamilySpec& family) {
  std::vector<Vec3> cloud = generate_shape(kind, n, r);
  const Vec3 mean = vertex_mean(cloud);
  for (Vec3& p : cloud) p -= mean;
  if (family.rotate) {
    const Mat3 rotation = random_rotation(r);
    for (Vec3& p : cloud) p = rotation * p;
  }
  for (Vec3& p : cloud) p *= family.scale;
  return cloud;
}

double max_projection(const std::vector<Vec3>& cloud, const Vec3& u) {
  double m = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : cloud) m = std::max(m, p.dot(u));
  return m;
}

double min_projection(const std::vector<Vec3>& cloud, const Vec3& u) {
  double m = std::numeric_limits<double>::infinity();
  for (const Vec3& p : cloud) m = std::min(m, p.dot(u));
  return m;
}

std::vector<Vec3> points_of(const Polytope& p) {
  return {p.vertices().begin(), p.vertices().end()};
}

}  // namespace

std::vector<Vec3> generate_shape(ShapeKind kind, int n, void* gsl_rng_handle) {
  if (n < 1) throw std::invalid_argument("generate_shape: vertex count must be at least 1");
  auto* r = static_cast<gsl_rng*>(gsl_rng_handle);
  std::vector<Vec3> cloud;
  switch (kind) {
    case ShapeKind::sphere_points:
      cloud.reserve(n);
      for (int i = 0; i < n; ++i) cloud.push_back(unit_vector(r));
      break;
    case ShapeKind::ball_points:
      // Rejection from the cube [-1, 1)^3 (accepts π/6 ≈ 52%); the test is the same squared
      // norm Eigen computes, so every accepted point has norm ≤ 1 as Eigen reports it.
      cloud.reserve(n);
      while (static_cast<int>(cloud.size()) < n) {
        const Vec3 p(2 * uniform(r) - 1, 2 * uniform(r) - 1, 2 * uniform(r) - 1);
        if (p.squaredNorm() <= 1) cloud.push_back(p);
      }
      break;
    case ShapeKind::cube_points:
      cloud.reserve(n);
      for (int i = 0; i < n; ++i)
        cloud.emplace_back(2 * uniform(r) - 1, 2 * uniform(r) - 1, 2 * uniform(r) - 1);
      break;
    case ShapeKind::gaussian:
      cloud.reserve(n);
      for (int i = 0; i < n; ++i) {
        const double x = gsl_ran_gaussian(r, 1.0);
        const double y = gsl_ran_gaussian(r, 1.0);
        const double z = gsl_ran_gaussian(r, 1.0);
        cloud.emplace_back(x, y, z);
      }
      break;
    case ShapeKind::box:
      cloud = points_of(shapes::box());
      break;
    case ShapeKind::cone:
      cloud = points_of(shapes::cone(std::max(n, 4)));
      break;
    case ShapeKind::cylinder:
      cloud = points_of(shapes::cylinder(std::max(n + (n & 1), 6)));
      break;
    case ShapeKind::uv_sphere:
      cloud = points_of(shapes::uv_sphere(std::max(n, 6)));
      break;
  }
  if (cloud.empty()) throw std::invalid_argument("generate_shape: unknown shape kind");
  return cloud;
}

GeneratedCase generate_case(const ExperimentConfig& config, std::uint64_t case_id) {
  if (config.families.empty())
    throw std::invalid_argument("generate_case: the experiment has no families");
  const RngPtr rng = make_case_rng(config.seed, case_id);
  gsl_rng* r = rng.get();

  GeneratedCase out;
  CaseRecord& rec = out.record;
  rec.case_id = case_id;
  const std::size_t family_index = draw_family(r, config.families);
  const FamilySpec& family = config.families[family_index];
  rec.family = static_cast<std::uint32_t>(family_index);
  rec.shape_a = family.shape_a;
  rec.shape_b = family.shape_b;
  rec.scale = family.scale;

  const int n_a = log_uniform_count(r, family.vertices_a);
  const int n_b = log_uniform_count(r, family.vertices_b);
  out.a = make_shape(r, family.shape_a, n_a, family);
  out.b = make_shape(r, family.shape_b, n_b, family);

  // Both vertex means are at the origin now; B moves along a random axis u.
  const PlacementSpec& placement = family.placement;
  const double size = pair_size(out.a, out.b);
  Vec3 translation = Vec3::Zero();
  Placement mode = Placement::random;
  if (placement.mode == "separated") {
    mode = Placement::separated;
  } else if (placement.mode == "overlapping") {
    mode = Placement::overlapping;
  } else if (placement.mode == "mixed") {
    mode = uniform(r) < placement.overlapping_fraction ? Placement::overlapping
                                                       : Placement::separated;
  } else if (placement.mode != "random") {
    throw std::invalid_argument("generate_case: unknown placement mode '" + placement.mode + "'");
  }

  if (mode == Placement::random) {
    const double half_width = placement.spread * size;
    for (int k = 0; k < 3; ++k) translation[k] = (2 * uniform(r) - 1) * half_width;
    rec.intended_gap = 0;
  } else {
    const Vec3 u = unit_vector(r);
    // gap > 0: B's extent along u starts gap·size after A's; gap < 0: they overlap by −gap·size.
    const double gap = mode == Placement::separated ? log_uniform(r, placement.gap)
                                                    : -log_uniform(r, placement.depth);
    const double shift = max_projection(out.a, u) + gap * size - min_projection(out.b, u);
    translation = shift * u;
    rec.intended_gap = gap;
    out.direction = u;
  }
  for (Vec3& p : out.b) p += translation;
  rec.placement = mode;

  rec.vertices_a = static_cast<std::int32_t>(out.a.size());
  rec.vertices_b = static_cast<std::int32_t>(out.b.size());
  rec.size = pair_size(out.a, out.b);
  for (const auto* cloud : {&out.a, &out.b})
    if (const std::string problem = describe_invalid_cloud(*cloud); !problem.empty())
      throw std::runtime_error("generate_case " + std::to_string(case_id) + ": " + problem);
  return out;
}

}  // namespace gjklab::experiment
