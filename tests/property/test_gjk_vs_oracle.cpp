// GJK against the exact oracle on seeded random pairs: booleans outside the touching band and
// distances within 1e-10 of the pair's size, for every gjklab algorithm (GJK, EPA, SAT, and
// gjk-bool under each of its starts). The peers' (libccd, FCL, Bullet) disagreements are
// counted and reported, not asserted.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "../support/random_pairs.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

using namespace gjklab;
using testing::CloudKind;
using testing::Rng;

namespace {

constexpr int kPairs = 2000;
constexpr double kBand = 1e-10;  // touching band and distance bound, relative to size

struct Tally {
  int wrong_outside_band = 0;
  int terminations_not_converged = 0;
  double worst_relative_error = 0;  // distance algorithms only
};

/// What each gjklab algorithm achieves on this sample, with a margin: the largest distance
/// error relative to size (measured worst, about 8× below the bound) and the most queries
/// that may stop other than converged (measured). A change that loses accuracy or converges
/// less often fails here, long before it reaches the touching band.
struct Accuracy {
  double relative_error;
  int not_converged;
};
const std::map<std::string, Accuracy> kAccuracy = {
    {"gjk-johnson", {1e-14, 2}},         // measured 1.2e-15, 1 no_progress
    {"gjk-johnson-backup", {1e-14, 2}},  // measured 1.2e-15, 1 no_progress
    {"gjk-voronoi", {1e-14, 1}},         // measured 1.1e-15
    {"epa", {1e-14, 4}},                 // its GJK phase is gjk-johnson-backup's
    {"gjk-sv", {1e-12, 0}},              // measured 1.1e-13
    {"gjk-nesterov", {3e-12, 1}},        // measured 3.3e-13
    {"gjk-polyak", {1e-12, 1}},          // measured 1.1e-13
    {"gjk-certified", {0, 0}},           // exact: the correctly rounded distance itself
    {"gjk-bool", {0, 0}},
    {"sat", {0, 0}},
};

}  // namespace

TEST_CASE("GJK agrees with the exact oracle on 2000 seeded random pairs", "[property]") {
  Rng rng(20261121);
  const auto algorithms = experiment::algorithms();
  std::map<std::string, Tally> tallies;
  int intersecting = 0, separated = 0, near_touching = 0;

  for (int i = 0; i < kPairs; ++i) {
    const CloudKind kind = (i % 2 == 0) ? CloudKind::sphere : CloudKind::cube;
    const int na = static_cast<int>(std::round(rng.log_uniform(4, 256)));
    const int nb = static_cast<int>(std::round(rng.log_uniform(4, 256)));
    // Half separated by 1e-6 … 10 sizes (log-uniform), a quarter overlapping by 1e-6 … 0.1
    // sizes (log-uniform), a quarter by 0.1 … 1 size (uniform): projections that overlap a
    // little often leave the hulls apart, so the deep quarter makes sure both answers occur.
    const double gap = (i % 4 < 2)    ? rng.log_uniform(1e-6, 10)
                       : (i % 4 == 2) ? -rng.log_uniform(1e-6, 0.1)
                                      : -rng.uniform(0.1, 1.0);
    const auto pair = testing::random_pair(rng, kind, na, nb, gap);
    const Polytope a(pair.a), b(pair.b);
    const double size = pair_size(pair.a, pair.b);

    const auto exact = exact::solve(a.vertices(), b.vertices());
    exact.intersect ? ++intersecting : ++separated;
    // Depth is computed only when a boolean disagrees, to know whether it is in the band.
    std::optional<double> depth;
    auto outside_band = [&] {
      if (!exact.intersect) return exact.distance > kBand * size;
      if (!depth) depth = exact::solve(a.vertices(), b.vertices(), {.depth = true}).depth.value();
      return *depth > kBand * size;
    };

    for (const auto& algorithm : algorithms) {
      if (algorithm.kind == experiment::AnswerKind::exact) continue;
      const auto o = experiment::run_algorithm(algorithm, a, b, {}, {});
      Tally& t = tallies[std::string(algorithm.name)];
      if (o.termination != Termination::converged) ++t.terminations_not_converged;
      if (o.intersect != exact.intersect && outside_band()) {
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
    }
    // gjk-bool's other starts (the registry runs the default one above).
    for (GjkBooleanStart start :
         {GjkBooleanStart::fixed_direction, GjkBooleanStart::centre_direction,
          GjkBooleanStart::centre_point}) {
      if (start == GjkBooleanDefaults::start) continue;
      GjkBooleanOptions options;
      options.start = start;
      const BooleanResult r = gjk_intersect(a, b, options);
      const std::string name = "gjk-bool start=" + std::string(to_string(start));
      Tally& t = tallies[name];
      if (r.termination != Termination::converged) ++t.terminations_not_converged;
      if (r.intersect != exact.intersect && outside_band()) {
        ++t.wrong_outside_band;
        FAIL_CHECK("pair " << i << ": " << name << " says intersect=" << r.intersect
                           << ", exact distance " << exact.distance << ", size " << size);
      }
    }
    if (!exact.intersect && exact.distance <= kBand * size) ++near_touching;
  }

  // The sample must exercise both answers.
  CHECK(intersecting > kPairs / 4);
  CHECK(separated > kPairs / 4);
  for (const auto& [name, accuracy] : kAccuracy) {
    INFO(name);
    REQUIRE(tallies.count(name));
    CHECK(tallies[name].worst_relative_error <= accuracy.relative_error);
    CHECK(tallies[name].terminations_not_converged <= accuracy.not_converged);
  }
  for (const auto& [name, t] : tallies) {
    WARN(name << ": wrong booleans outside the band " << t.wrong_outside_band << "/" << kPairs
              << ", terminations other than converged " << t.terminations_not_converged
              << ", worst distance error / size " << t.worst_relative_error);
  }
  WARN("sample: " << intersecting << " intersecting, " << separated << " separated ("
                  << near_touching << " within the band)");
}

TEST_CASE("gjk-johnson distances scale by exactly 2^k", "[property]") {
  Rng rng(7);
  int compared = 0;
  for (int i = 0; i < 200; ++i) {
    const auto pair =
        testing::random_pair(rng, i % 2 ? CloudKind::cube : CloudKind::sphere, rng.integer(4, 64),
                             rng.integer(4, 64), rng.log_uniform(1e-6, 10));
    const Polytope a(pair.a), b(pair.b);
    const auto base = gjk_distance(a, b);
    for (int k : {-40, -7, 3, 40}) {
      const double s = std::ldexp(1.0, k);
      const auto scaled = gjk_distance(a.scaled(s), b.scaled(s));
      INFO("pair " << i << " k " << k);
      CHECK(scaled.distance == base.distance * s);
      CHECK(scaled.iterations == base.iterations);
      CHECK(scaled.termination == base.termination);
      ++compared;
    }
  }
  WARN(compared << " scaled queries compared");
}
