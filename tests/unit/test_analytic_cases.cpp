// Every registered algorithm on configurations whose exact answer is known in closed form.
#include <catch2/catch.hpp>

#include <cmath>

#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/shapes.hpp"

using namespace gjklab;
using experiment::AnswerKind;

namespace {

struct AnalyticCase {
  const char* name;
  Polytope a, b;
  bool intersect;
  double distance;  // exact distance (0 when intersecting)
};

Pose rotation_about(const Vec3& axis, double angle, const Vec3& t = Vec3::Zero()) {
  return {Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(), t};
}

std::vector<AnalyticCase> analytic_cases() {
  const Polytope unit = shapes::box();
  const double pi = M_PI;
  std::vector<AnalyticCase> cases;
  cases.push_back({"boxes face-face, gap 0.25", unit,
                   unit.transformed(Pose::from_translation(Vec3(1.25, 0.125, -0.25))), false,
                   0.25});
  // A's edge parallel to y sits at x = √2/2; B's edge parallel to z at x = 2 − √2/2.
  cases.push_back({"boxes edge-edge, skew perpendicular edges",
                   unit.transformed(rotation_about(Vec3::UnitY(), pi / 4)),
                   unit.transformed(rotation_about(Vec3::UnitZ(), pi / 4, Vec3(2, 0, 0))), false,
                   2 - std::sqrt(2.0)});
  // A's vertex (½,½,½) turned onto +x sits at x = √3/2; B's face at x = 1.5 − ½.
  cases.push_back(
      {"boxes vertex-face",
       unit.transformed(
           {Quat::FromTwoVectors(Vec3(1, 1, 1), Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()}),
       unit.transformed(Pose::from_translation(Vec3(1.5, 0, 0))), false, 1 - std::sqrt(3.0) / 2});
  cases.push_back({"boxes far apart", unit,
                   unit.transformed(Pose::from_translation(Vec3(-3, 4, 12))), false,
                   std::sqrt(2.0 * 2 + 3 * 3 + 11 * 11)});
  cases.push_back(
      {"small box nested in a large box", shapes::box(Vec3(4, 4, 4)),
       shapes::box(Vec3(0.5, 0.25, 1)).transformed(Pose::from_translation(Vec3(0.5, -0.25, 1))),
       true, 0});
  cases.push_back({"boxes overlapping by 0.5", unit,
                   unit.transformed(Pose::from_translation(Vec3(0.5, 0.25, 0))), true, 0});
  cases.push_back({"sphere and cone overlapping at their centres", shapes::uv_sphere(),
                   shapes::cone().transformed(Pose::from_translation(Vec3(0.1, 0.2, 0.3))), true,
                   0});
  cases.push_back({"cylinder above a box, gap 0.5 along z", unit,
                   shapes::cylinder().transformed(Pose::from_translation(Vec3(0.2, 0.1, 1.5))),
                   false, 0.5});
  return cases;
}

}  // namespace

TEST_CASE("every algorithm answers the analytic cases", "[unit][analytic]") {
  for (const AnalyticCase& c : analytic_cases()) {
    for (const auto& algorithm : experiment::algorithms()) {
      INFO(c.name << " with " << algorithm.name);
      const auto o = experiment::run_algorithm(algorithm, c.a, c.b, {}, {});
      CHECK(o.intersect == c.intersect);
      CHECK(o.termination == Termination::converged);
      // Peers (FCL, Bullet) stop at their own, looser tolerances.
      const double tolerance = algorithm.peer ? 1e-6 : 1e-14;
      if (algorithm.kind != AnswerKind::boolean) {
        REQUIRE(o.distance.has_value());
        CHECK(std::abs(*o.distance - c.distance) <= tolerance);
      }
      if (algorithm.kind == AnswerKind::distance && !c.intersect) {
        // Witness points: on their shapes' boundary and at the reported distance.
        CHECK(std::abs((*o.witness_a - *o.witness_b).norm() - *o.distance) <= tolerance);
      }
      if (c.intersect && algorithm.depth && algorithm.kind != AnswerKind::exact) {
        REQUIRE(o.depth.has_value());
        CHECK(*o.depth > 0);
        REQUIRE(o.normal.has_value());
        CHECK(std::abs(o.normal->norm() - 1) <= 1e-12);
      }
    }
  }
}

TEST_CASE("touching boxes: shared face is an intersection for the exact oracle and GJK",
          "[unit][analytic]") {
  const Polytope a = shapes::box();
  const Polytope b = a.transformed(Pose::from_translation(Vec3(1, 0.25, 0.5)));
  for (const char* name : {"exact", "gjk-johnson", "gjk-bool"}) {
    INFO(name);
    const auto o = experiment::run_algorithm(*experiment::find_algorithm(name), a, b, {}, {});
    CHECK(o.intersect);
    if (o.distance) CHECK(*o.distance == 0);
  }
}

TEST_CASE("gjk-johnson stops at the step limit and says so", "[unit][analytic]") {
  const Polytope a = shapes::uv_sphere();
  const Polytope b =
      shapes::uv_sphere().transformed(rotation_about(Vec3(1, 2, 3), 0.7, Vec3(1.0001, 0.01, 0.02)));
  experiment::AlgorithmOptions options;
  options.set_max_iterations(2);
  const auto o =
      experiment::run_algorithm(*experiment::find_algorithm("gjk-johnson"), a, b, {}, options);
  CHECK(o.termination == Termination::step_limit);
  CHECK(o.iterations == 2);
  CHECK(o.support_calls == 3);
  // The reported distance is still an upper bound of the true one.
  const auto exact = experiment::run_algorithm(*experiment::find_algorithm("exact"), a, b, {}, {});
  CHECK(*o.distance >= *exact.distance);
}
