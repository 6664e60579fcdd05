// Configurations that broke gjk-johnson, kept with their data.
#include <catch2/catch.hpp>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/experiment/cloud_io.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

using namespace gjklab;

namespace {

experiment::PointCase load_case(const char* file) {
  const auto cases = experiment::read_cases_file(std::string(GJKLAB_REGRESSION_DATA_DIR) + "/" + file);
  REQUIRE(cases.size() == 1);
  return std::get<experiment::PointCase>(cases[0]);
}

}  // namespace

TEST_CASE("johnson flat tetrahedron near contact: 102 sphere points vs 9, gap 0.0135",
          "[regression]") {
  // At iteration 7 the new support point is coplanar with the triangle closest to the origin
  // (duality gap 2e-12 of ‖v‖²). The flat tetrahedron's cofactors are rounding noise, all
  // positive, so Johnson's tests accept it and GJK claimed contact — although an earlier
  // support point had already proved separation (v·w > 0).
  const auto c = load_case("johnson_flat_tetrahedron_near_contact.jsonl");
  const Polytope a(c.a), b(c.b);
  const auto exact = exact::solve(a.vertices(), b.vertices());
  REQUIRE_FALSE(exact.intersect);
  const auto r = gjk_distance(a, b);
  CHECK_FALSE(r.intersect);
  CHECK(std::abs(r.distance - exact.distance) <= 1e-10 * pair_size(c.a, c.b));
  CHECK(r.termination == Termination::degenerate_simplex);
}
