// Sphere-swept shapes (spheres, capsules, rounded polytopes) on configurations with closed-form
// answers: every algorithm that handles them, the exact oracle's correctly rounded answers,
// and the errors for algorithms and inputs that cannot take them.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/gjk/swept.hpp"

using namespace gjklab;
using experiment::AnswerKind;

namespace {

struct SweptCase {
  const char* name;
  std::vector<Vec3> a, b;
  SweptRadii radii;
  bool intersect;
  double distance;  // exact distance of the swept shapes (0 when intersecting)
  double depth;     // exact penetration depth when intersecting
};

std::vector<Vec3> segment(const Vec3& p, const Vec3& q) {
  return {p, q};
}

/// The cube [-1, 1]³ moved to `centre`.
std::vector<Vec3> box_at(const Vec3& centre) {
  std::vector<Vec3> v;
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0})
      for (double z : {-1.0, 1.0})
        v.push_back(Vec3(x, y, z) + centre);
  return v;
}

std::vector<SweptCase> swept_cases() {
  const Vec3 o = Vec3::Zero();
  return {
      {"spheres apart, centres 5 apart, radii 1 and 1.5",
       {o},
       {Vec3(3, 4, 0)},
       {1, 1.5},
       false,
       2.5,
       0},
      {"spheres overlapping by 1, centres 5 apart, radii 3 and 3",
       {o},
       {Vec3(0, 0, 5)},
       {3, 3},
       true,
       0,
       1},
      {"spheres touching, centres 2 apart, radii 1 and 1",
       {o},
       {Vec3(2, 0, 0)},
       {1, 1},
       true,
       0,
       0},
      {"parallel capsules 2 apart, radii 0.25",
       segment(Vec3(-1, 0, 0), Vec3(1, 0, 0)),
       segment(Vec3(-1.5, 2, 0), Vec3(0.5, 2, 0)),
       {0.25, 0.25},
       false,
       1.5,
       0},
      {"crossed capsules 3 apart along z, radii 0.5 and 1",
       segment(Vec3(-1, 0, 0), Vec3(1, 0, 0)),
       segment(Vec3(0, -1, 3), Vec3(0, 1, 3)),
       {0.5, 1},
       false,
       1.5,
       0},
      {"crossed capsules overlapping by 0.5",
       segment(Vec3(-1, 0, 0), Vec3(1, 0, 0)),
       segment(Vec3(0, -1, 1), Vec3(0, 1, 1)),
       {0.75, 0.75},
       true,
       0,
       0.5},
      {"capsule end cap and sphere, 5 apart, radii 0.5 and 0.25",
       segment(Vec3(-1, 0, 0), Vec3(1, 0, 0)),
       {Vec3(4, 4, 0)},
       {0.5, 0.25},
       false,
       4.25,
       0},
      {"rounded boxes face to face, cores 2 apart, radii 0.5 and 0.25",
       box_at(o),
       box_at(Vec3(4, 0.5, 0)),
       {0.5, 0.25},
       false,
       1.25,
       0},
      // √3 − 0.75 rounded to nearest (from 50 digits); the double expression is 1 ulp off.
      {"rounded box corner and sphere, √3 − 0.75",
       box_at(o),
       {Vec3(2, 2, 2)},
       {0.5, 0.25},
       false,
       0x1.f6cf5d0b09955p-1,
       0},
      {"rounded boxes with intersecting cores, core depth 0.5",
       box_at(o),
       box_at(Vec3(1.5, 0, 0)),
       {0.125, 0.125},
       true,
       0,
       0.75},
      {"sphere and rounded box, only B swept", box_at(o), {Vec3(0, 0, 3)}, {0, 2.5}, true, 0, 0.5},
  };
}

/// Absolute tolerance of floating-point algorithms on these unit-sized cases.
constexpr double kTolerance = 1e-12;

}  // namespace

TEST_CASE("exact oracle: sphere-swept shapes against closed forms", "[unit][exact][swept]") {
  for (const SweptCase& c : swept_cases()) {
    INFO(c.name);
    const exact::OracleAnswer ans =
        exact::solve_swept(c.a, c.b, c.radii.a, c.radii.b, {.depth = true});
    CHECK(ans.swept);
    CHECK(ans.intersect == c.intersect);
    // The oracle rounds correctly, so it matches each closed form to the last bit.
    CHECK(ans.distance == c.distance);
    if (c.intersect) {
      REQUIRE(ans.depth.has_value());
      CHECK(*ans.depth == c.depth);
    } else {
      CHECK_FALSE(ans.depth.has_value());
    }
  }
}

TEST_CASE("exact oracle: swept distances are correctly rounded, with no cancellation",
          "[unit][exact][swept]") {
  SECTION("points √2 apart, radii 0.5: √2 − 1") {
    const auto ans =
        exact::solve_swept(std::vector{Vec3(0, 0, 0)}, std::vector{Vec3(1, 1, 0)}, 0.5, 0.5);
    CHECK(ans.distance == 0x1.a827999fcef32p-2);     // √2 − 1 rounded to nearest (50 digits)
    CHECK(ans.distance_squared.numerator() == "2");  // the cores' exact squared distance
  }
  SECTION("√3 − 0.75 from a rounded box corner") {
    const auto ans =
        exact::solve_swept(box_at(Vec3::Zero()), std::vector{Vec3(2, 2, 2)}, 0.5, 0.25);
    CHECK(ans.distance == 0x1.f6cf5d0b09955p-1);
  }
  SECTION("cores 1 + 5e-17 apart, radii 0.5 + 0.5: double arithmetic would give 0") {
    // √(1 + y²) − 1 with y = 1e-8 (as a double): y²/(√(1 + y²) + 1), about 5e-17.
    const double y = 1e-8;
    const auto ans =
        exact::solve_swept(std::vector{Vec3(0, 0, 0)}, std::vector{Vec3(1, y, 0)}, 0.5, 0.5);
    CHECK_FALSE(ans.intersect);
    CHECK(std::sqrt(1 + y * y) - 1 == 0.0);  // what a double evaluation gives
    CHECK(ans.distance == 0x1.cd2b297d889bcp-55);
  }
  SECTION("cores exactly the radii apart touch: intersecting with depth 0") {
    const auto ans = exact::solve_swept(std::vector{Vec3(0, 0, 0)}, std::vector{Vec3(0, 0.75, 0)},
                                        0.5, 0.25, {.depth = true});
    CHECK(ans.intersect);
    CHECK(ans.distance == 0);
    REQUIRE(ans.depth.has_value());
    CHECK(*ans.depth == 0);
    CHECK_FALSE(std::signbit(*ans.depth));
  }
  SECTION("zero radii are the plain polytopes") {
    const auto plain = exact::solve(std::vector{Vec3(0, 0, 0)}, std::vector{Vec3(1, 1, 0)});
    const auto swept =
        exact::solve_swept(std::vector{Vec3(0, 0, 0)}, std::vector{Vec3(1, 1, 0)}, 0, 0);
    CHECK_FALSE(swept.swept);
    CHECK(swept.distance == plain.distance);
  }
  SECTION("a negative or non-finite radius is rejected, naming the shape") {
    const std::vector<Vec3> p{Vec3::Zero()};
    CHECK_THROWS_WITH(exact::solve_swept(p, p, -1, 0), Catch::Contains("shape A"));
    CHECK_THROWS_WITH(exact::solve_swept(p, p, 0, INFINITY), Catch::Contains("shape B"));
    CHECK_THROWS_WITH(exact::solve_swept(p, p, NAN, 0), Catch::Contains("radius"));
  }
}

TEST_CASE("every algorithm that handles sphere-swept shapes answers the closed forms",
          "[unit][swept]") {
  const experiment::AlgorithmOptions options;
  int algorithms_run = 0;
  for (const experiment::AlgorithmInfo& algorithm : experiment::algorithms()) {
    if (!algorithm.can.swept) continue;
    ++algorithms_run;
    for (const SweptCase& c : swept_cases()) {
      INFO(algorithm.name << ": " << c.name);
      const Polytope a(c.a), b(c.b);
      const experiment::Outcome o = experiment::run_algorithm(algorithm, a, b, c.radii, options);
      // Touching pairs may go either way for floating-point algorithms; libccd's EPA meets a
      // non-finite value on the touching spheres (a known libccd 2.1 weakness, see libccd.hpp).
      if (c.intersect && c.depth == 0) {
        if (!algorithm.peer) CHECK(o.termination == Termination::converged);
        continue;
      }
      CHECK(o.termination == Termination::converged);
      CHECK(o.intersect == c.intersect);
      if (o.distance) CHECK(std::abs(*o.distance - c.distance) <= kTolerance);
      const bool exact_depth = algorithm.kind == AnswerKind::exact || algorithm.name == "epa" ||
                               algorithm.name == "gjk-certified";
      if (c.intersect && o.depth && exact_depth) CHECK(std::abs(*o.depth - c.depth) <= kTolerance);
    }
  }
  // gjk-bool, the six GJK distance variants, epa, four libccd queries, gjk-certified and
  // the oracle.
  CHECK(algorithms_run == 14);
}

TEST_CASE("swept witnesses and normals keep the penetration conventions", "[unit][swept]") {
  const experiment::AlgorithmInfo& epa = *experiment::find_algorithm("epa");
  const experiment::AlgorithmOptions options;
  SECTION("separated: witness_b − witness_a = distance · normal, on the swept surfaces") {
    const Polytope a(std::vector{Vec3(0, 0, 0)}), b(std::vector{Vec3(3, 4, 0)});
    const auto o = experiment::run_algorithm(epa, a, b, {1, 1.5}, options);
    REQUIRE(o.witness_a);
    REQUIRE(o.witness_b);
    CHECK(o.witness_a->isApprox(Vec3(0.6, 0.8, 0), 1e-15));
    CHECK(o.witness_b->isApprox(Vec3(3, 4, 0) - 1.5 * Vec3(0.6, 0.8, 0), 1e-15));
  }
  SECTION("cores apart by less than the radii: depth along the core axis") {
    const Polytope a(std::vector{Vec3(0, 0, 0)}), b(std::vector{Vec3(0, 0, 5)});
    const auto o = experiment::run_algorithm(epa, a, b, {3, 3}, options);
    REQUIRE(o.depth);
    REQUIRE(o.normal);
    CHECK(*o.depth == Approx(1).margin(1e-15));
    CHECK(o.normal->isApprox(Vec3::UnitZ(), 1e-15));
    CHECK((*o.witness_a - *o.witness_b).isApprox(*o.depth * *o.normal, 1e-15));
  }
  SECTION("intersecting cores: the core depth grows by both radii") {
    const Polytope a(box_at(Vec3::Zero())), b(box_at(Vec3(1.5, 0, 0)));
    const auto o = experiment::run_algorithm(epa, a, b, {0.125, 0.125}, options);
    REQUIRE(o.depth);
    CHECK(*o.depth == Approx(0.75).margin(1e-15));
    CHECK((*o.witness_a - *o.witness_b).isApprox(*o.depth * *o.normal, 1e-15));
  }
}

TEST_CASE("swept_distance shifts a core answer by the radii", "[unit][swept]") {
  DistanceResult core;
  core.distance = 2;
  core.lower_bound = 1.9;
  core.witness_a = Vec3(0, 0, 0);
  core.witness_b = Vec3(0, 2, 0);
  const DistanceResult apart = swept_distance(core, {0.5, 0.25});
  CHECK_FALSE(apart.intersect);
  CHECK(apart.distance == 1.25);
  CHECK(apart.lower_bound == Approx(1.15));
  CHECK(apart.witness_a == Vec3(0, 0.5, 0));
  CHECK(apart.witness_b == Vec3(0, 1.75, 0));
  const DistanceResult overlap = swept_distance(core, {1.5, 1});
  CHECK(overlap.intersect);
  CHECK(overlap.distance == 0);
  CHECK(overlap.lower_bound == 0);
  core.intersect = true;
  core.distance = 0;
  CHECK(swept_distance(core, {1, 1}).distance == 0);
}

TEST_CASE("algorithms for polytopes only refuse sphere-swept shapes by name", "[unit][swept]") {
  const Polytope p(std::vector{Vec3(0, 0, 0)}), q(std::vector{Vec3(3, 0, 0)});
  const experiment::AlgorithmInfo& sat = *experiment::find_algorithm("sat");
  CHECK_FALSE(experiment::handles(sat, {1, 0}));
  CHECK(experiment::handles(sat, {0, 0}));
  CHECK_THROWS_WITH(experiment::run_algorithm(sat, p, q, {1, 0}, {}),
                    Catch::Contains("'sat'") && Catch::Contains("polytopes only"));
  const experiment::AlgorithmInfo& mpr = *experiment::find_algorithm("libccd-mpr");
  TraceRecorder trace;
  CHECK_THROWS_WITH(experiment::run_algorithm_traced(mpr, p, q, {1, 0}, {}, trace),
                    Catch::Contains("'libccd-mpr'") && Catch::Contains("cannot be traced"));
}

TEST_CASE("traced swept queries repeat the untraced answer", "[unit][swept]") {
  const Polytope a(box_at(Vec3::Zero())), b(std::vector{Vec3(2, 2, 2)});
  const experiment::AlgorithmOptions options;
  for (const char* name : {"gjk-bool", "gjk-johnson", "gjk-sv", "gjk-nesterov"}) {
    INFO(name);
    const experiment::AlgorithmInfo& info = *experiment::find_algorithm(name);
    TraceRecorder trace;
    const auto traced = experiment::run_algorithm_traced(info, a, b, {0.5, 0.25}, options, trace);
    const auto plain = experiment::run_algorithm(info, a, b, {0.5, 0.25}, options);
    CHECK(traced.intersect == plain.intersect);
    CHECK(traced.distance == plain.distance);
    CHECK(traced.iterations == plain.iterations);
    CHECK_FALSE(trace.iterations.empty());
  }
}

// ---- experiment files ----

namespace {

experiment::ExperimentConfig parse(const std::string& body) {
  return experiment::parse_experiment(
      "name = \"t\"\nseed = 5\ncases = 40\noutput = \"t.h5\"\n" + body, "swept.toml");
}

}  // namespace

TEST_CASE("experiment files: sphere, capsule and radius keys", "[unit][swept][config]") {
  SECTION("defaults: sphere radius 1, capsule radius 0.5, other shapes none") {
    const auto c = parse(
        "[[family]]\nshape = \"sphere\"\n[[family]]\nshape = \"capsule\"\n"
        "[[family]]\nshape = \"box\"\n[[algorithm]]\nname = \"gjk-johnson\"\n");
    CHECK(c.families[0].radius_a.hi == 1);
    CHECK(c.families[1].radius_b.lo == 0.5);
    CHECK(c.families[2].radius_a.hi == 0);
    CHECK(c.has_swept_shapes());
  }
  SECTION("radius ranges and per-shape radii") {
    const auto c = parse(
        "[[family]]\nshape_a = \"box\"\nshape_b = \"capsule\"\nradius_a = [0.01, 0.1]\n"
        "[[algorithm]]\nname = \"gjk-bool\"\n");
    CHECK(c.families[0].radius_a.lo == 0.01);
    CHECK(c.families[0].radius_a.hi == 0.1);
    CHECK(c.families[0].radius_b.hi == 0.5);  // the capsule's default
  }
  SECTION("an algorithm for polytopes only is a config error naming it and the valid ones") {
    CHECK_THROWS_WITH(
        parse("[[family]]\nshape = \"box\"\nradius = 0.1\n[[algorithm]]\nname = \"sat\"\n"),
        Catch::Contains("swept.toml:") && Catch::Contains("'sat' answers for polytopes only") &&
            Catch::Contains("gjk-johnson"));
  }
  SECTION("bad radii and misplaced radius keys") {
    CHECK_THROWS_WITH(
        parse("[[family]]\nshape = \"box\"\nradius = -1\n[[algorithm]]\nname = \"gjk-bool\"\n"),
        Catch::Contains("radius") && Catch::Contains(">= 0"));
    CHECK_THROWS_WITH(parse("[[family]]\nshape = \"box\"\nradius = [0, 1]\n"
                            "[[algorithm]]\nname = \"gjk-bool\"\n"),
                      Catch::Contains("lower bound must be > 0"));
    CHECK_THROWS_WITH(parse("[[family]]\nshape = \"box\"\nradius = 1\nradius_a = 2\n"
                            "[[algorithm]]\nname = \"gjk-bool\"\n"),
                      Catch::Contains("cannot be combined with 'radius'"));
    CHECK_THROWS_WITH(parse("[[family]]\nshape = \"contact\"\ncontact = \"face-face\"\n"
                            "radius = 1\n[[algorithm]]\nname = \"gjk-bool\"\n"),
                      Catch::Contains("contact and file pairs are exact"));
  }
}

TEST_CASE("generated sphere-swept cases: radii scaled with the shapes, gap placed exactly",
          "[unit][swept][families]") {
  const auto config = parse(
      "[placement]\nmode = \"separated\"\ngap = [0.01, 0.1]\n"
      "[[family]]\nshape = \"sphere\"\nradius = [0.5, 2]\nscale = 4\nscale_b = [1, 3]\n"
      "[[algorithm]]\nname = \"gjk-johnson\"\n");
  bool different_radii = false;
  for (std::uint64_t id = 0; id < 40; ++id) {
    const experiment::GeneratedCase g = experiment::generate_case(config, id);
    INFO("case " << id);
    REQUIRE(g.a.size() == 1);
    REQUIRE(g.b.size() == 1);
    const auto& rec = g.record;
    CHECK(rec.shape_a == experiment::ShapeKind::sphere);
    CHECK(rec.radius_a >= 0.5 * 4);
    CHECK(rec.radius_a <= 2 * 4);
    CHECK(rec.radius_b >= 0.5 * 4);
    CHECK(rec.radius_b <= 2 * 4 * 3);
    different_radii = different_radii || rec.radius_a != rec.radius_b;
    // Two balls: the size is the larger diameter, and the drawn gap is the distance.
    CHECK(rec.size == Approx(2 * std::sqrt(3.0) * std::max(rec.radius_a, rec.radius_b)));
    const auto exact = exact::solve_swept(g.a, g.b, rec.radius_a, rec.radius_b);
    CHECK_FALSE(exact.intersect);
    CHECK(exact.distance == Approx(rec.intended_gap * rec.size).epsilon(1e-12));
  }
  CHECK(different_radii);
}

TEST_CASE("capsule family: a segment core of length 2 before scaling", "[unit][swept][families]") {
  const auto config =
      parse("[[family]]\nshape = \"capsule\"\nscale = 2\n[[algorithm]]\nname = \"gjk-bool\"\n");
  const experiment::GeneratedCase g = experiment::generate_case(config, 0);
  REQUIRE(g.a.size() == 2);
  CHECK((g.a[0] - g.a[1]).norm() == Approx(4));
  CHECK(g.record.radius_a == 1);  // default 0.5, scaled by 2
}

// ---- the command line: run, replay, query ----

TEST_CASE("gjklab run, replay and query on sphere-swept shapes", "[smoke][swept]") {
  const testing::ScratchDir dir("swept");
  const auto toml = dir.path() / "swept.toml";
  const auto h5 = dir.path() / "swept.h5";
  {
    std::ofstream f(toml);
    f << "name = \"swept\"\nseed = 9\ncases = 30\noutput = \"swept.h5\"\n"
         "[oracle]\ndepth = true\n"
         "[[family]]\nshape = \"capsule\"\nradius = [0.1, 1]\n"
         "[[family]]\nname = \"rounded\"\nshape = \"cube_points\"\nvertices = 12\n"
         "radius_b = 0.2\n"
         "[[algorithm]]\nname = \"gjk-johnson\"\n[[algorithm]]\nname = \"epa\"\n"
         "[[algorithm]]\nname = \"libccd-mpr\"\n";
  }
  const testing::CliResult run = testing::run_cli({"run", toml.string(), "--out", h5.string()});
  INFO(run.out << run.err);
  REQUIRE(run.status == 0);
  const experiment::Archive archive = experiment::read_archive(h5);
  REQUIRE(archive.results.size() == 30);
  int swept_b = 0;
  for (const auto& r : archive.results) {
    CHECK(r.record.radius_b > 0);
    swept_b += r.record.radius_b > 0;
    for (const auto& a : r.algorithms)
      CHECK(a.failure == experiment::FailureClass::none);
  }
  CHECK(swept_b == 30);

  const testing::CliResult replay =
      testing::run_cli({"replay", h5.string(), "--case", "4", "--trace"});
  INFO(replay.out << replay.err);
  CHECK(replay.status == 0);
  CHECK_THAT(replay.out, Catch::Contains("swept by radii"));
  CHECK_THAT(replay.out, Catch::Contains("equals the archived result"));

  // Two one-point files with radii: spheres 2.5 apart.
  const auto pa = dir.path() / "a.xyz", pb = dir.path() / "b.xyz";
  std::ofstream(pa) << "0 0 0\n";
  std::ofstream(pb) << "3 4 0\n";
  const testing::CliResult query =
      testing::run_cli({"query", pa.string(), pb.string(), "--radius-a", "1", "--radius-b", "1.5",
                        "--algorithms", "gjk-johnson,exact"});
  INFO(query.out << query.err);
  REQUIRE(query.status == 0);
  CHECK_THAT(query.out, Catch::Contains("\"distance\":2.5"));
  CHECK_THAT(query.out, Catch::Contains("\"core_distance2_num\":\"25\""));
  // Without named algorithms, those for polytopes only (sat, FCL, Bullet) are left out.
  const testing::CliResult all =
      testing::run_cli({"query", pa.string(), pb.string(), "--radius-a", "1"});
  CHECK(all.status == 0);
  CHECK_THAT(all.out, !Catch::Contains("\"error\""));
  const testing::CliResult sat = testing::run_cli(
      {"query", pa.string(), pb.string(), "--radius-a", "1", "--algorithms", "sat"});
  CHECK_THAT(sat.out, Catch::Contains("polytopes only"));
}
