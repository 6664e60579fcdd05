// The proven stopping test of the GJK distance queries (gjk/bracket.hpp) and the double-word
// sub-simplex solve they continue with (gjk/precise_subsimplex.hpp): every branch of the proof
// is pinned here by a case that fails without it.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gjklab/exact/hull_adjacency.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/scalar_cloud.hpp"
#include "gjklab/gjk/bracket.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/gjk_nesterov.hpp"
#include "gjklab/gjk/precise_subsimplex.hpp"
#include "gjklab/gjk/subalgorithms.hpp"

using namespace gjklab;

namespace {

/// Every thin contact family, near contact (gaps and depths 1e-12 … 1e-6 of the size), at
/// scales 1e-3, 1 and 1e3 and moved by up to 1e6.
experiment::ExperimentConfig thin_contacts() {
  std::string text = R"(
name = "thin"
seed = 5
cases = 1
[placement]
mode = "mixed"
gap = [1e-12, 1e-6]
depth = [1e-12, 1e-6]
)";
  int index = 0;
  for (const char* contact : {"crossing-segments", "needle-point", "needle-segment", "thin-rods",
                              "crossing-wedges", "tilted-plates"})
    for (const char* extra : {"", "scale = 1e-3", "scale = 1e3", "offset = [1, 1e6]"})
      text += "[[family]]\nname = \"f" + std::to_string(index++) +
              "\"\nshape = \"contact\"\ncontact = \"" + contact +
              "\"\naspect = [1e2, 1e9]\nangle = [1e-9, 1e-3]\n" + extra + "\n";
  text += "[[algorithm]]\nname = \"gjk-johnson\"\n";
  return experiment::parse_experiment(text, "thin contacts");
}

template <class Query>
int check_bracket_holds(const Query& query, const char* name, int cases) {
  const auto config = thin_contacts();
  int converged = 0;
  for (int i = 0; i < cases; ++i) {
    const auto c = experiment::generate_case(config, static_cast<std::uint64_t>(i));
    const Polytope a(c.a), b(c.b);
    const auto exact = exact::solve(c.a, c.b);
    const DistanceResult r = query(a, b);
    INFO(name << ", case " << i << ": exact " << exact.distance << ", answer " << r.distance
              << " in [" << r.lower_bound << ", " << r.upper_bound << "], "
              << to_string(r.termination));
    // The exact distance is the nearest double of a real number; the bounds are proven for the
    // real number, so each may be one unit in the last place off the rounded value.
    CHECK(std::nextafter(r.lower_bound, -1.0) <= exact.distance);
    CHECK(exact.distance <= std::nextafter(r.upper_bound, 2 * r.upper_bound + 1));
    CHECK(r.lower_bound <= r.distance);
    CHECK(r.distance <= r.upper_bound);
    if (r.termination == Termination::converged) {
      ++converged;
      CHECK(bracket_accepted(GjkDistanceOptions{},
                             DistanceBracketT<double>{r.lower_bound, r.upper_bound},
                             pair_magnitude<double>(a, b)));
      CHECK(std::abs(r.distance - exact.distance) <= r.upper_bound - r.lower_bound + 1e-300);
      CHECK(r.intersect == (r.distance == 0));
    }
  }
  return converged;
}

}  // namespace

TEST_CASE("distance bracket: holds the exact distance on thin contacts, for every variant",
          "[unit][bracket]") {
  const GjkDistanceOptions o;
  const int n = 240;
  std::vector<int> converged;
  converged.push_back(check_bracket_holds(
      [&](const Polytope& a, const Polytope& b) { return gjk_distance(a, b, o); }, "gjk-johnson",
      n));
  converged.push_back(check_bracket_holds(
      [&](const Polytope& a, const Polytope& b) {
        return gjk_distance_with<JohnsonBackupSubAlgorithm>(a, b, o);
      },
      "gjk-johnson-backup", n));
  converged.push_back(check_bracket_holds(
      [&](const Polytope& a, const Polytope& b) {
        return gjk_distance_with<SignedVolumesSubAlgorithm>(a, b, o);
      },
      "gjk-sv", n));
  converged.push_back(check_bracket_holds(
      [&](const Polytope& a, const Polytope& b) {
        return gjk_distance_with<VoronoiSubAlgorithm>(a, b, o);
      },
      "gjk-voronoi", n));
  converged.push_back(check_bracket_holds(
      [&](const Polytope& a, const Polytope& b) {
        return gjk_nesterov(a, b, GjkNesterovOptions{});
      },
      "gjk-nesterov", n));
  converged.push_back(check_bracket_holds(
      [&](const Polytope& a, const Polytope& b) { return gjk_polyak(a, b, o); }, "gjk-polyak", n));
  // The sample must show converged answers, near contact, on needles: most of them.
  REQUIRE(converged.size() == 6);
  for (const int c : converged)
    CHECK(c > n * 9 / 10);
}

TEST_CASE("distance bracket: in float and long double too", "[unit][bracket]") {
  const auto config = thin_contacts();
  for (int i = 0; i < 120; ++i) {
    const auto c = experiment::generate_case(config, static_cast<std::uint64_t>(i));
    const ScalarCloud<float> fa(c.a), fb(c.b);
    const ScalarCloud<long double> la(c.a), lb(c.b);
    // The clouds rounded to float are other clouds: their own exact distance.
    std::vector<Vec3> ra, rb;
    for (const auto& p : fa.vertices())
      ra.push_back(p.cast<double>());
    for (const auto& p : fb.vertices())
      rb.push_back(p.cast<double>());
    const auto exact_float = exact::solve(ra, rb);
    const auto exact = exact::solve(c.a, c.b);
    const auto f = gjk_distance(fa, fb);
    const auto l = gjk_distance(la, lb);
    INFO("case " << i);
    CHECK(static_cast<double>(f.lower_bound) <= exact_float.distance * (1 + 1e-15));
    CHECK(exact_float.distance <= static_cast<double>(f.upper_bound) * (1 + 1e-15));
    CHECK(static_cast<double>(l.lower_bound) <= exact.distance * (1 + 1e-15));
    CHECK(exact.distance <= static_cast<double>(l.upper_bound) * (1 + 1e-15));
  }
}

TEST_CASE("distance bracket: hill-climbing supports take their lower bound from a full scan",
          "[unit][bracket]") {
  // A hill-climbing support is a local maximum of rounded values, which proves no plane: the
  // loop's planes are not used, and without the final scan no lower bound would be proven and
  // a separated query could never converge.
  std::vector<Vec3> sphere;
  const int n = 400;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = 2.399963 * i;
    sphere.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  std::vector<Vec3> moved;
  for (const Vec3& p : sphere)
    moved.push_back(p + Vec3(2.5, 0.3, -0.2));
  Polytope a(sphere), b(moved);
  a.enable_hill_climbing(exact::hull_vertex_adjacency(sphere));
  b.enable_hill_climbing(exact::hull_vertex_adjacency(moved));
  const auto exact = exact::solve(sphere, moved);
  const DistanceResult r = gjk_distance(a, b);
  CHECK(r.termination == Termination::converged);
  CHECK(r.lower_bound > 0);
  CHECK(r.lower_bound <= exact.distance);
  CHECK(exact.distance <= r.upper_bound);
}

TEST_CASE("distance bracket: the acceptance test, branch by branch", "[unit][bracket]") {
  GjkDistanceOptions o;  // relative, 1e-12
  const double magnitude = 4;
  const double resolution = bracket_resolution(magnitude);
  using B = DistanceBracketT<double>;
  // Within the resolution: accepted whatever the criterion (contact, and near contact).
  CHECK(bracket_accepted(o, B{0, 0.5 * resolution}, magnitude));
  CHECK_FALSE(bracket_accepted(o, B{0, 2 * resolution}, magnitude));
  // The relative criterion on the proven numbers: U − L ≤ relative_gap·U.
  CHECK(bracket_accepted(o, B{1 - 0.5e-12, 1}, magnitude * 1e-6));
  CHECK_FALSE(bracket_accepted(o, B{1 - 2e-12, 1}, magnitude * 1e-6));
  // Its absolute floor: U·(U − L) ≤ absolute_gap_squared.
  o.absolute_gap_squared = 1e-6;
  CHECK(bracket_accepted(o, B{1 - 0.5e-6, 1}, magnitude * 1e-6));
  // The absolute criterion alone.
  o.convergence = GjkConvergence::absolute;
  CHECK(bracket_accepted(o, B{1 - 0.5e-6, 1}, magnitude * 1e-6));
  CHECK_FALSE(bracket_accepted(o, B{1 - 2e-6, 1}, magnitude * 1e-6));
  // The duality gap: 2·U·(U − L) ≤ duality_gap_tolerance.
  o.convergence = GjkConvergence::duality_gap;
  o.duality_gap_tolerance = 1e-6;
  CHECK(bracket_accepted(o, B{1 - 0.4e-6, 1}, magnitude * 1e-6));
  CHECK_FALSE(bracket_accepted(o, B{1 - 0.6e-6, 1}, magnitude * 1e-6));
  // Nothing proven: never accepted.
  CHECK_FALSE(bracket_accepted(o, B{0, std::numeric_limits<double>::infinity()}, magnitude));
  CHECK_FALSE(bracket_accepted(o, B{0, std::nan("")}, magnitude));
}

TEST_CASE("distance bracket: the termination a stop reports", "[unit][bracket]") {
  using detail::judged_termination;
  CHECK(judged_termination(Termination::converged, true) == Termination::converged);
  CHECK(judged_termination(Termination::converged, false) == Termination::no_progress);
  CHECK(judged_termination(Termination::no_progress, true) == Termination::converged);
  CHECK(judged_termination(Termination::degenerate_simplex, true) == Termination::converged);
  CHECK(judged_termination(Termination::degenerate_simplex, false) ==
        Termination::degenerate_simplex);
  CHECK(judged_termination(Termination::step_limit, true) == Termination::step_limit);
  CHECK(judged_termination(Termination::numerical_failure, true) == Termination::numerical_failure);
}

TEST_CASE("distance bracket: bounds from a plane and from the simplex", "[unit][bracket]") {
  // Two points 3 apart along x, far from the origin: the plane bound is 3 − E, the simplex
  // bound 3 + E, with E = 24u·√3·(M_A + M_B).
  const Polytope a(std::vector<Vec3>{Vec3(1e3, 0, 0)}), b(std::vector<Vec3>{Vec3(1e3 + 3, 0, 0)});
  const double mu = pair_magnitude<double>(a, b);
  CHECK(mu == Approx(std::sqrt(3.0) * (2e3 + 3)));
  const double e = bracket_rounding(mu);
  const Vec3 d(-1, 0, 0), w = a.vertices()[0] - b.vertices()[0];
  CHECK(support_plane_lower_bound(d.dot(w), d.squaredNorm(), e) == Approx(3 - e));
  CHECK(support_plane_lower_bound(-1.0, 1.0, e) == 0);  // a plane behind the origin
  const Vec3 wa = a.vertices()[0], wb = b.vertices()[0];
  CHECK(simplex_upper_bound<double>({1, 0, 0, 0}, 1, wa, wb, e) == Approx(3 + e));
  // Weights naming no point: negative, or summing to 0.
  CHECK(std::isinf(simplex_upper_bound<double>({-1, 0, 0, 0}, 1, -wa, -wb, e)));
  CHECK(std::isinf(simplex_upper_bound<double>({0, 0, 0, 0}, 1, 0 * wa, 0 * wb, e)));
}

TEST_CASE("precise sub-simplex: a needle triangle's plane point, where double loses it",
          "[unit][bracket]") {
  // Three points of a needle triangle (aspect 1e7) in the plane z = −3e-12: the closest point
  // is (0, 0, −3e-12) exactly. Johnson's cofactors in double put it 4e-4 off in x; the
  // double-word cofactors and the plane's projection find it.
  const std::array<Vec3, 4> y{Vec3(0.75, -5e-08, -3e-12), Vec3(-1.25, -5e-08, -3e-12),
                              Vec3(0.25, 1.5e-07, -3e-12), Vec3::Zero()};
  const auto s = precise_closest_point(y, 3);
  REQUIRE(s.found);
  CHECK(s.subset == 7);
  CHECK(s.closest == Vec3(0, 0, -3e-12));
  CHECK(s.weights[0] == 0.4375);
  CHECK(s.weights[1] == 0.3125);
  CHECK(s.weights[2] == 0.25);
  const auto j = johnson_closest_point(y, 3);
  CHECK(std::abs(j.closest.x()) > 1e-6);  // what the continuation exists for
}

TEST_CASE("precise sub-simplex: a needle tetrahedron named by its weights or by a face",
          "[unit][bracket]") {
  // Four points of two thin rods touching (a needle tetrahedron whose volume is of the order
  // of the double-word rounding): the tetrahedron's own weights are noise and name a point
  // 0.54 from the origin, while the face 0-1-2 holds a point within 1.4e-17 of it. The answer
  // is the face.
  const std::array<Vec3, 4> y{Vec3(0.2146751984402282, -0.026093520527302731, -0.49190845615719392),
                              Vec3(-0.21468871412923557, 0.02618888796893603, 0.49189749892504553),
                              Vec3(-0.21467519841823385, 0.02609352037210938, 0.49190845617502488),
                              Vec3(-0.21470222983970488, 0.026284255565697953, 0.4918865416738461)};
  const auto s = precise_closest_point(y, 4);
  REQUIRE(s.found);
  CHECK(s.subset == 7);
  Vec3 named = Vec3::Zero();
  for (int i = 0; i < 4; ++i)
    named += s.weights[i] * y[i];
  CHECK(named.norm() < 1e-16);
}

TEST_CASE("precise sub-simplex: nearly parallel segments' closest point on the line",
          "[unit][bracket]") {
  // The segment from y0 to y1, 1e-11 from the origin with ‖y‖ about 1: the projection onto
  // the line in double-word keeps the point's direction (the weights' sum would not).
  const Vec3 y0(-1, 1e-11, 0), y1(1, 1e-11, 3e-10);
  const auto s = precise_closest_point(std::array<Vec3, 4>{y0, y1, Vec3::Zero(), Vec3::Zero()}, 2);
  REQUIRE(s.found);
  CHECK(s.subset == 3);
  const Vec3 e = y1 - y0;
  CHECK(std::abs(s.closest.dot(e)) <= 1e-30);  // perpendicular to the segment
  CHECK(s.closest.y() == Approx(1e-11).epsilon(1e-12));
}

namespace {

/// A polytope whose support, like a hill climb stopped on a plateau of rounded values, never
/// reaches one vertex (the last): a local maximum that is not the global one. It reports
/// uses_hill_climbing() and offers the full scan, as Polytope does.
struct StuckClimber {
  const Polytope* shape;
  std::span<const Vec3> vertices() const { return shape->vertices(); }
  std::size_t support_index(const Vec3& d) const {
    std::size_t best = 0;
    for (std::size_t i = 1; i + 1 < shape->size(); ++i)
      if (shape->vertices()[i].dot(d) > shape->vertices()[best].dot(d)) best = i;
    return best;
  }
  Vec3 support(const Vec3& d) const { return shape->vertices()[support_index(d)]; }
  std::size_t scan_support_index(const Vec3& d) const { return shape->scan_support_index(d); }
  bool uses_hill_climbing() const { return true; }
  double max_magnitude() const { return shape->max_magnitude(); }
};

}  // namespace

TEST_CASE("distance bracket: a support that is not a full scan proves no plane",
          "[unit][bracket]") {
  // A's vertex nearest B is one its support never returns: the loop converges on the rest of
  // A, 0.5 farther, and its support planes would "prove" a lower bound above the distance. The
  // lower bound must come from the full scan instead, which finds the vertex: the bracket holds
  // the exact distance, and the answer, 0.5 off, is not `converged`.
  const std::vector<Vec3> a_points{Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(-1, 1, -1),
                                   Vec3(1, 1, -1),   Vec3(-1, -1, 1), Vec3(1, -1, 1),
                                   Vec3(-1, 1, 1),   Vec3(0, 0, 1.5)};
  const std::vector<Vec3> b_points{Vec3(-1, -1, 3), Vec3(1, -1, 3), Vec3(-1, 1, 3), Vec3(1, 1, 3)};
  const Polytope a(a_points), b(b_points);
  const StuckClimber stuck{&a};
  const auto exact = exact::solve(a_points, b_points);
  REQUIRE(exact.distance == 1.5);
  const DistanceResult r = gjk_distance(stuck, b);
  INFO(r.distance << " in [" << r.lower_bound << ", " << r.upper_bound << "], "
                  << to_string(r.termination));
  CHECK(r.distance == Approx(2.0));
  CHECK(r.lower_bound <= exact.distance);
  CHECK(exact.distance <= r.upper_bound);
  CHECK(r.termination != Termination::converged);
}
