// Sphere-swept shapes against the exact oracle on seeded random pairs: rounded point clouds,
// capsules and spheres with random radii, placed by the swept shapes' extents. Every gjklab
// algorithm that handles them must get the boolean right outside the touching band and the
// distance within 1e-10 of the pair's size (EPA: the depth too); libccd's answers are counted
// and reported, not asserted.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "../support/random_pairs.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

using namespace gjklab;
using testing::CloudKind;
using testing::Rng;

namespace {

constexpr int kPairs = 1000;
constexpr double kBand = 1e-10;  // touching band and error bound, relative to size

/// A cloud of 1 (sphere), 2 (capsule) or 4 … 64 points (rounded polytope), by the pair index.
std::vector<Vec3> core_cloud(Rng& rng, int i) {
  switch (i % 3) {
    case 0:
      return {rng.unit_vector()};
    case 1:
      return {rng.unit_vector(), rng.unit_vector()};
    default:
      return testing::random_cloud(rng, i % 2 ? CloudKind::cube : CloudKind::sphere,
                                   rng.integer(4, 64));
  }
}

Vec3 mean_of(const std::vector<Vec3>& cloud) {
  Vec3 m = Vec3::Zero();
  for (const Vec3& v : cloud)
    m += v;
  return m / static_cast<double>(cloud.size());
}

double extent(const std::vector<Vec3>& cloud, const Vec3& u, bool max) {
  double e = max ? -INFINITY : INFINITY;
  for (const Vec3& v : cloud)
    e = max ? std::max(e, v.dot(u)) : std::min(e, v.dot(u));
  return e;
}

struct Tally {
  int wrong_outside_band = 0;
  int not_converged = 0;
  double worst_relative_error = 0;
};

}  // namespace

TEST_CASE("sphere-swept shapes agree with the exact oracle on 1000 seeded random pairs",
          "[property][swept]") {
  Rng rng(20261122);
  std::map<std::string, Tally> tallies;
  int intersecting = 0, separated = 0, cores_intersecting = 0;
  for (int i = 0; i < kPairs; ++i) {
    std::vector<Vec3> a = core_cloud(rng, i), b = core_cloud(rng, i / 3);
    const SweptRadii radii{rng.log_uniform(1e-3, 1), rng.log_uniform(1e-3, 1)};
    // B's vertex mean goes to A's, then B moves along u so that the swept extents are `gap`
    // sizes apart (overlap when < 0).
    const Vec3 to_a = mean_of(a) - mean_of(b);
    for (Vec3& v : b)
      v += to_a;
    const double size = pair_size(a, b, radii.a, radii.b);
    const double gap = (i % 2 == 0) ? rng.log_uniform(1e-6, 1) : -rng.uniform(0.05, 1);
    const Vec3 u = rng.unit_vector();
    const double shift =
        (extent(a, u, true) + radii.a) + gap * size - (extent(b, u, false) - radii.b);
    for (Vec3& v : b)
      v += shift * u;
    const Polytope pa(a), pb(b);

    const auto exact = exact::solve_swept(a, b, radii.a, radii.b, {.depth = true});
    exact.intersect ? ++intersecting : ++separated;
    cores_intersecting += exact.distance_squared.is_zero();
    const bool in_band =
        exact.intersect ? *exact.depth <= kBand * size : exact.distance <= kBand * size;

    for (const auto& algorithm : experiment::algorithms()) {
      if (!algorithm.can.swept || algorithm.kind == experiment::AnswerKind::exact) continue;
      const auto o = experiment::run_algorithm(algorithm, pa, pb, radii, {});
      Tally& t = tallies[std::string(algorithm.name)];
      if (o.termination != Termination::converged) ++t.not_converged;
      if (o.intersect != exact.intersect && !in_band) {
        ++t.wrong_outside_band;
        if (!algorithm.peer)
          FAIL_CHECK("pair " << i << ": " << algorithm.name << " says intersect=" << o.intersect
                             << ", exact distance " << exact.distance << ", size " << size);
      }
      if (o.distance) {
        const double relative = std::abs(*o.distance - exact.distance) / size;
        t.worst_relative_error = std::max(t.worst_relative_error, relative);
        if (relative > kBand && !algorithm.peer)
          FAIL_CHECK("pair " << i << ": " << algorithm.name << " distance " << *o.distance
                             << " vs exact " << exact.distance << " (size " << size << ")");
      }
      if (algorithm.name == "epa" && o.intersect && exact.intersect && o.depth) {
        const double relative = std::abs(*o.depth - *exact.depth) / size;
        if (relative > kBand)
          FAIL_CHECK("pair " << i << ": epa depth " << *o.depth << " vs exact " << *exact.depth
                             << " (size " << size << ")");
      }
    }
  }
  // Both answers, and overlaps from the radii alone as well as from intersecting cores.
  CHECK(intersecting > kPairs / 4);
  CHECK(separated > kPairs / 4);
  CHECK(cores_intersecting > 10);
  CHECK(intersecting - cores_intersecting > 10);
  CHECK(tallies.size() == 13);
  for (const auto& [name, t] : tallies)
    WARN(name << ": wrong booleans outside the band " << t.wrong_outside_band << "/" << kPairs
              << ", not converged " << t.not_converged << ", worst distance error / size "
              << t.worst_relative_error);
  WARN("sample: " << intersecting << " intersecting (" << cores_intersecting
                  << " with intersecting cores), " << separated << " separated");
}
