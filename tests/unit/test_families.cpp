// Seeded case generators: determinism independent of order, the distributions of each shape
// kind, the placements, the family weights and the scale.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "../../src/experiment/cases/random_stream.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/geometry/polytope.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

namespace {

FamilySpec family(ShapeKind shape, double vertices_lo, double vertices_hi) {
  FamilySpec f;
  f.name = std::string(to_string(shape));
  f.shape_a = f.shape_b = shape;
  f.vertices_a = f.vertices_b = Interval{vertices_lo, vertices_hi};
  return f;
}

ExperimentConfig config_with(std::vector<FamilySpec> families, std::uint64_t seed = 42) {
  ExperimentConfig c;
  c.name = "test";
  c.seed = seed;
  c.cases = 1000;
  c.families = std::move(families);
  return c;
}

/// Several families and every placement mode, for the determinism tests.
ExperimentConfig varied_config() {
  std::vector<FamilySpec> families;
  const ShapeKind kinds[] = {ShapeKind::sphere_points, ShapeKind::ball_points,
                             ShapeKind::cube_points,   ShapeKind::gaussian,
                             ShapeKind::box,           ShapeKind::cone,
                             ShapeKind::cylinder,      ShapeKind::uv_sphere};
  const PlacementMode modes[] = {PlacementMode::separated, PlacementMode::overlapping,
                                 PlacementMode::mixed, PlacementMode::random};
  int i = 0;
  for (ShapeKind k : kinds) {
    FamilySpec f = family(k, 4, 200);
    f.placement.mode = modes[i % 4];
    f.weight = 1 + i;
    f.rotation = i % 3 != 0 ? Rotation::random : Rotation::none;
    f.scale = i % 2 ? 1.0 : 0.001;
    families.push_back(f);
    ++i;
  }
  return config_with(families, 20240601);
}

bool bitwise_equal(const std::vector<Vec3>& x, const std::vector<Vec3>& y) {
  return x.size() == y.size() &&
         (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(Vec3)) == 0);
}

bool same_case(const GeneratedCase& x, const GeneratedCase& y) {
  const CaseRecord& r = x.record;
  const CaseRecord& s = y.record;
  return r.case_id == s.case_id && r.family == s.family && r.shape_a == s.shape_a &&
         r.shape_b == s.shape_b && r.placement == s.placement && r.vertices_a == s.vertices_a &&
         r.vertices_b == s.vertices_b && r.scale == s.scale && r.size == s.size &&
         r.intended_gap == s.intended_gap && bitwise_equal(x.a, y.a) && bitwise_equal(x.b, y.b) &&
         x.direction == y.direction;
}

double max_dot(const std::vector<Vec3>& cloud, const Vec3& u) {
  double m = -HUGE_VAL;
  for (const Vec3& p : cloud)
    m = std::max(m, p.dot(u));
  return m;
}
double min_dot(const std::vector<Vec3>& cloud, const Vec3& u) {
  double m = HUGE_VAL;
  for (const Vec3& p : cloud)
    m = std::min(m, p.dot(u));
  return m;
}
Vec3 mean_of(const std::vector<Vec3>& cloud) {
  Vec3 s = Vec3::Zero();
  for (const Vec3& p : cloud)
    s += p;
  return s / static_cast<double>(cloud.size());
}

}  // namespace

TEST_CASE("a case is a function of (seed, case id) alone", "[unit][families]") {
  const ExperimentConfig c = varied_config();
  const GeneratedCase first = generate_case(c, 17);
  const GeneratedCase again = generate_case(c, 17);
  CHECK(same_case(first, again));
  CHECK(first.record.case_id == 17);

  std::vector<GeneratedCase> forward;
  for (std::uint64_t i = 0; i < 100; ++i)
    forward.push_back(generate_case(c, i));
  std::vector<GeneratedCase> backward(100);
  for (std::uint64_t i = 100; i-- > 0;)
    backward[i] = generate_case(c, i);
  int mismatches = 0;
  for (std::size_t i = 0; i < 100; ++i)
    mismatches += same_case(forward[i], backward[i]) ? 0 : 1;
  CHECK(mismatches == 0);

  // Different ids and different seeds give different cases.
  CHECK_FALSE(bitwise_equal(forward[3].a, forward[4].a));
  ExperimentConfig other = c;
  other.seed = c.seed + 1;
  CHECK_FALSE(bitwise_equal(generate_case(other, 17).a, first.a));
  // Every family shows up over 100 cases.
  std::set<std::uint32_t> seen;
  for (const GeneratedCase& g : forward)
    seen.insert(g.record.family);
  CHECK(seen.size() == c.families.size());
}

TEST_CASE("case stream seeds are distinct within an experiment", "[unit][families]") {
  std::set<std::uint32_t> seeds;
  for (std::uint64_t i = 0; i < 200000; ++i)
    seeds.insert(case_stream_seed(7, i));
  CHECK(seeds.size() == 200000);
  CHECK(case_stream_seed(7, 5) == case_stream_seed(7, 5));
  CHECK(case_stream_seed(7, 5) != case_stream_seed(8, 5));
}

TEST_CASE("point generators have the stated distributions", "[unit][families]") {
  RandomStream rng(99);
  const int n = 20000;

  SECTION("sphere_points lie on the unit sphere, centred") {
    const auto pts = generate_shape(ShapeKind::sphere_points, n, rng);
    REQUIRE(pts.size() == static_cast<std::size_t>(n));
    double worst = 0;
    for (const Vec3& p : pts)
      worst = std::max(worst, std::abs(p.norm() - 1));
    CHECK(worst <= 1e-12);
    CHECK(mean_of(pts).norm() < 0.03);
    // Uniform on the sphere: z is uniform on [-1, 1], so P(z > 0.5) = 1/4.
    const auto upper =
        std::count_if(pts.begin(), pts.end(), [](const Vec3& p) { return p.z() > 0.5; });
    CHECK(static_cast<double>(upper) / n == Approx(0.25).margin(0.015));
  }
  SECTION("ball_points fill the unit ball uniformly") {
    const auto pts = generate_shape(ShapeKind::ball_points, n, rng);
    REQUIRE(pts.size() == static_cast<std::size_t>(n));
    double largest = 0;
    for (const Vec3& p : pts)
      largest = std::max(largest, p.norm());
    CHECK(largest <= 1.0);
    CHECK(largest > 0.99);
    // Uniform in volume: P(|p| < 1/2) = 1/8.
    const auto inner =
        std::count_if(pts.begin(), pts.end(), [](const Vec3& p) { return p.norm() < 0.5; });
    CHECK(static_cast<double>(inner) / n == Approx(0.125).margin(0.01));
  }
  SECTION("cube_points fill [-1, 1]^3") {
    const auto pts = generate_shape(ShapeKind::cube_points, n, rng);
    REQUIRE(pts.size() == static_cast<std::size_t>(n));
    double largest = 0;
    for (const Vec3& p : pts)
      largest = std::max(largest, p.cwiseAbs().maxCoeff());
    CHECK(largest <= 1.0);
    CHECK(largest > 0.999);
    CHECK(mean_of(pts).norm() < 0.03);
    // Uniform on each axis: P(x > 0.5) = 1/4.
    const auto right =
        std::count_if(pts.begin(), pts.end(), [](const Vec3& p) { return p.x() > 0.5; });
    CHECK(static_cast<double>(right) / n == Approx(0.25).margin(0.015));
  }
  SECTION("gaussian clouds are standard normal") {
    const auto pts = generate_shape(ShapeKind::gaussian, n, rng);
    REQUIRE(pts.size() == static_cast<std::size_t>(n));
    const Vec3 mean = mean_of(pts);
    CHECK(mean.norm() < 0.04);
    Vec3 var = Vec3::Zero();
    for (const Vec3& p : pts)
      var += (p - mean).cwiseProduct(p - mean);
    var /= n;
    for (int k = 0; k < 3; ++k)
      CHECK(var[k] == Approx(1.0).margin(0.05));
    const auto beyond =
        std::count_if(pts.begin(), pts.end(), [](const Vec3& p) { return p.norm() > 1; });
    CHECK(beyond > n / 2);  // P(|p| > 1) ≈ 0.80 for a 3-D standard normal
  }
  SECTION("vertex counts below 1 are refused") {
    CHECK_THROWS_AS(generate_shape(ShapeKind::sphere_points, 0, rng), std::invalid_argument);
  }
}

TEST_CASE("demo shapes have their vertex counts, clamped to their minimums", "[unit][families]") {
  RandomStream rng(1);
  CHECK(generate_shape(ShapeKind::box, 1, rng).size() == 8);
  CHECK(generate_shape(ShapeKind::box, 500, rng).size() == 8);
  CHECK(generate_shape(ShapeKind::cone, 33, rng).size() == 33);
  CHECK(generate_shape(ShapeKind::cone, 2, rng).size() == 4);
  CHECK(generate_shape(ShapeKind::cylinder, 64, rng).size() == 64);
  CHECK(generate_shape(ShapeKind::cylinder, 63, rng).size() == 64);
  CHECK(generate_shape(ShapeKind::cylinder, 3, rng).size() == 6);
  CHECK(generate_shape(ShapeKind::uv_sphere, 482, rng).size() == 482);
  CHECK(generate_shape(ShapeKind::uv_sphere, 500, rng).size() == 482);
  CHECK(generate_shape(ShapeKind::uv_sphere, 1, rng).size() == 6);
  // They fit [-0.5, 0.5]^3 (see geometry/shapes.hpp).
  for (const Vec3& p : generate_shape(ShapeKind::uv_sphere, 100, rng))
    CHECK(p.cwiseAbs().maxCoeff() <= 0.5 + 1e-15);

  // The record holds the actual cloud sizes.
  FamilySpec f = family(ShapeKind::cylinder, 7, 7);
  f.shape_a = ShapeKind::box;
  const GeneratedCase g = generate_case(config_with({f}), 0);
  CHECK(g.record.vertices_a == 8);
  CHECK(g.record.vertices_b == 8);
  CHECK(g.a.size() == 8);
  CHECK(g.b.size() == 8);
}

TEST_CASE("vertex count ranges are drawn log-uniformly", "[unit][families]") {
  const ExperimentConfig c = config_with({family(ShapeKind::sphere_points, 4, 256)});
  const int cases = 2000;
  int below_32 = 0;
  for (int i = 0; i < cases; ++i) {
    const GeneratedCase g = generate_case(c, static_cast<std::uint64_t>(i));
    REQUIRE(g.record.vertices_a >= 4);
    REQUIRE(g.record.vertices_a <= 256);
    REQUIRE(g.record.vertices_b >= 4);
    REQUIRE(g.record.vertices_b <= 256);
    REQUIRE(g.a.size() == static_cast<std::size_t>(g.record.vertices_a));
    below_32 += g.record.vertices_a < 32 ? 1 : 0;
  }
  // P(n < 32) = log(32/4) / log(257/4) ≈ 0.4996 for the log-uniform count.
  CHECK(static_cast<double>(below_32) / cases ==
        Approx(std::log(8.0) / std::log(257.0 / 4)).margin(0.04));
}

TEST_CASE("separated and overlapping placements along the drawn axis", "[unit][families]") {
  FamilySpec sep = family(ShapeKind::cube_points, 4, 64);
  sep.name = "sep";
  sep.placement.mode = PlacementMode::separated;
  sep.placement.gap = {1e-6, 2};
  FamilySpec ovl = family(ShapeKind::gaussian, 4, 64);
  ovl.name = "ovl";
  ovl.placement.mode = PlacementMode::overlapping;
  ovl.placement.depth = {1e-6, 0.4};
  const ExperimentConfig c = config_with({sep, ovl}, 3);

  int separated = 0, overlapping = 0;
  for (std::uint64_t i = 0; i < 400; ++i) {
    const GeneratedCase g = generate_case(c, i);
    const CaseRecord& r = g.record;
    const Vec3& u = g.direction;
    REQUIRE(std::abs(u.norm() - 1) < 1e-12);
    CHECK(r.size == pair_size(g.a, g.b));
    // A's vertex mean stays at the origin.
    CHECK(mean_of(g.a).norm() <= 1e-12 * r.size);
    const double a_hi = max_dot(g.a, u);
    const double b_lo = min_dot(g.b, u);
    const double tol = 1e-12 * r.size;
    if (r.family == 0) {
      ++separated;
      CHECK(r.placement == Placement::separated);
      CHECK(r.intended_gap >= 1e-6);
      CHECK(r.intended_gap <= 2);
      // The projections onto u are disjoint, B's starting intended_gap·size after A's.
      CHECK(a_hi < b_lo);
      CHECK(std::abs((b_lo - a_hi) - r.intended_gap * r.size) <= tol);
    } else {
      ++overlapping;
      CHECK(r.placement == Placement::overlapping);
      CHECK(r.intended_gap <= -1e-6);
      CHECK(r.intended_gap >= -0.4);
      CHECK(b_lo < a_hi);
      CHECK(std::abs((a_hi - b_lo) + r.intended_gap * r.size) <= tol);
    }
  }
  CHECK(separated > 100);
  CHECK(overlapping > 100);
}

TEST_CASE("mixed and random placements", "[unit][families]") {
  FamilySpec mixed = family(ShapeKind::ball_points, 16, 16);
  mixed.placement.mode = PlacementMode::mixed;
  mixed.placement.overlapping_fraction = 0.3;
  int overlapping = 0;
  const int cases = 2000;
  const ExperimentConfig m = config_with({mixed});
  for (int i = 0; i < cases; ++i) {
    const GeneratedCase g = generate_case(m, static_cast<std::uint64_t>(i));
    REQUIRE(g.record.placement != Placement::random);
    if (g.record.placement == Placement::overlapping) {
      ++overlapping;
      CHECK(g.record.intended_gap < 0);
    } else {
      CHECK(g.record.intended_gap > 0);
    }
  }
  CHECK(static_cast<double>(overlapping) / cases == Approx(0.3).margin(0.03));

  FamilySpec random = family(ShapeKind::sphere_points, 8, 8);
  random.placement.mode = PlacementMode::random;
  random.placement.spread = 1.5;
  const ExperimentConfig r = config_with({random});
  double largest = 0;
  for (std::uint64_t i = 0; i < 500; ++i) {
    const GeneratedCase g = generate_case(r, i);
    CHECK(g.record.placement == Placement::random);
    CHECK(g.record.intended_gap == 0);
    CHECK(g.direction == Vec3::Zero());
    const Vec3 offset = (mean_of(g.b) - mean_of(g.a)) / g.record.size;
    largest = std::max(largest, offset.cwiseAbs().maxCoeff());
  }
  CHECK(largest <= 1.5 * (1 + 1e-9));
  CHECK(largest > 1.2);  // the whole cube is used
}

TEST_CASE("families are drawn in proportion to their weights", "[unit][families]") {
  FamilySpec light = family(ShapeKind::sphere_points, 4, 4);
  light.name = "light";
  light.weight = 1;
  FamilySpec heavy = family(ShapeKind::cube_points, 4, 4);
  heavy.name = "heavy";
  heavy.weight = 3;
  const ExperimentConfig c = config_with({light, heavy}, 11);
  const int cases = 4000;
  int counts[2] = {0, 0};
  for (int i = 0; i < cases; ++i) {
    const GeneratedCase g = generate_case(c, static_cast<std::uint64_t>(i));
    REQUIRE(g.record.family < 2);
    ++counts[g.record.family];
    CHECK(g.record.shape_a ==
          (g.record.family == 0 ? ShapeKind::sphere_points : ShapeKind::cube_points));
  }
  CHECK(static_cast<double>(counts[0]) / cases == Approx(0.25).margin(0.025));
  CHECK(static_cast<double>(counts[1]) / cases == Approx(0.75).margin(0.025));
}

TEST_CASE("scale multiplies the clouds and their size", "[unit][families]") {
  for (ShapeKind kind : {ShapeKind::gaussian, ShapeKind::cone}) {
    FamilySpec unit = family(kind, 10, 100);
    FamilySpec big = unit;
    big.scale = 8;  // a power of two: every coordinate scales exactly
    FamilySpec odd = unit;
    odd.scale = 3.7;
    const ExperimentConfig cu = config_with({unit});
    const ExperimentConfig cb = config_with({big});
    const ExperimentConfig co = config_with({odd});
    for (std::uint64_t i = 0; i < 50; ++i) {
      const GeneratedCase u = generate_case(cu, i);
      const GeneratedCase b = generate_case(cb, i);
      const GeneratedCase o = generate_case(co, i);
      CHECK(b.record.scale == 8);
      CHECK(b.record.size == 8 * u.record.size);
      CHECK(o.record.size == Approx(3.7 * u.record.size).epsilon(1e-12));
      CHECK(b.record.intended_gap == u.record.intended_gap);
      REQUIRE(b.a.size() == u.a.size());
      REQUIRE(b.b.size() == u.b.size());
      bool exact = true;
      for (std::size_t k = 0; k < u.a.size(); ++k)
        exact = exact && b.a[k] == 8 * u.a[k];
      for (std::size_t k = 0; k < u.b.size(); ++k)
        exact = exact && b.b[k] == 8 * u.b[k];
      CHECK(exact);
    }
  }
}

TEST_CASE("generated clouds are valid and records complete", "[unit][families]") {
  const ExperimentConfig c = varied_config();
  for (std::uint64_t i = 0; i < 300; ++i) {
    const GeneratedCase g = generate_case(c, i);
    CHECK(describe_invalid_cloud(g.a).empty());
    CHECK(describe_invalid_cloud(g.b).empty());
    const FamilySpec& f = c.families.at(g.record.family);
    CHECK(g.record.case_id == i);
    CHECK(g.record.shape_a == f.shape_a);
    CHECK(g.record.shape_b == f.shape_b);
    CHECK(g.record.scale == f.scale);
    CHECK(g.record.size > 0);
    CHECK(g.record.vertices_a == static_cast<std::int32_t>(g.a.size()));
    CHECK(g.record.vertices_b == static_cast<std::int32_t>(g.b.size()));
  }
  CHECK_THROWS_AS(generate_case(ExperimentConfig{}, 0), std::invalid_argument);
}

TEST_CASE("family registry: every generated shape is one row, and the parser follows it",
          "[unit][families]") {
  std::set<ShapeKind> kinds;
  for (const ShapeGenerator& g : shape_generators()) {
    INFO(to_string(g.kind));
    CHECK(kinds.insert(g.kind).second);  // one row per kind
    CHECK(find_shape_generator(g.kind) == &g);
    RandomStream rng(7);
    CHECK_FALSE(generate_shape(g.kind, g.default_vertices, rng).empty());
    // A family may name exactly the nameable rows, and gets the row's default vertex count.
    const auto listed =
        std::find_if(family_shapes().begin(), family_shapes().end(),
                     [&](const FamilyShapeInfo& s) { return s.name == to_string(g.kind); });
    CHECK((listed != family_shapes().end()) == g.nameable);
    CHECK((find_shape_generator(to_string(g.kind)) == &g) == g.nameable);
    if (!g.nameable) continue;
    const ExperimentConfig config = parse_experiment(
        "name = \"t\"\nseed = 1\ncases = 1\n[[family]]\nshape = \"" +
            std::string(to_string(g.kind)) + "\"\n[[algorithm]]\nname = \"gjk-johnson\"\n",
        "registry.toml");
    CHECK(config.families[0].vertices_a.lo == g.default_vertices);
    CHECK(config.families[0].vertices_b.hi == g.default_vertices);
  }
  // Only the shapes read from files have no generator.
  for (ShapeKind k : {ShapeKind::from_file, ShapeKind::mesh}) {
    CHECK(find_shape_generator(k) == nullptr);
    CHECK(kinds.count(k) == 0);
  }
  CHECK(kinds.size() + 2 == static_cast<std::size_t>(ShapeKind::plate) + 1);
}
