// The benchmark's ratios from injected medians: each row against its reference in the same
// case (the fixed one, libccd-mpr for booleans, the fastest peer distance query for distances)
// and hill-climbing rows against their full scan. An inverted or misattributed ratio fails.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gjklab/experiment/bench/bench.hpp"

using namespace gjklab::experiment;
using namespace gjklab::experiment::bench;

namespace {

BenchRecord row(const std::string& algorithm, double ns) {
  BenchRecord r;
  r.algorithm = algorithm;
  r.ns_median = ns;
  return r;
}

}  // namespace

TEST_CASE("bench ratios from injected medians", "[unit][bench]") {
  std::vector<BenchRecord> rows = {row("gjk-johnson", 120), row("gjk-bool", 30),
                                   row("libccd-mpr", 60),   row("fcl-indep", 80),
                                   row("bullet-gjk", 40),   row("gjk-johnson+hc", 24)};
  const std::vector<RatioRole> roles = {
      {AnswerKind::distance, std::nullopt}, {AnswerKind::boolean, std::nullopt},
      {AnswerKind::boolean, std::nullopt},  {AnswerKind::distance, std::nullopt},
      {AnswerKind::distance, std::nullopt}, {AnswerKind::distance, "gjk-johnson"}};
  set_case_ratios(rows, roles, {"", "libccd-mpr", "libccd-gjk", {"fcl-indep", "bullet-gjk"}});
  // Distances against the fastest peer distance query of the case (bullet-gjk, 40 ns).
  CHECK(rows[0].reference == "bullet-gjk");
  CHECK(*rows[0].ratio_to_reference == 3.0);
  CHECK(*rows[3].ratio_to_reference == 2.0);
  CHECK(*rows[4].ratio_to_reference == 1.0);
  // Booleans against libccd-mpr.
  CHECK(rows[1].reference == "libccd-mpr");
  CHECK(*rows[1].ratio_to_reference == 0.5);
  // Hill climbing against the same algorithm's full scan, and only there.
  CHECK(*rows[5].ratio_to_full_scan == 0.2);
  CHECK_FALSE(rows[0].ratio_to_full_scan.has_value());

  // A fixed reference applies to every row; one missing from the case leaves no ratio.
  set_case_ratios(rows, roles, {"gjk-bool", "libccd-mpr", "libccd-gjk", {"fcl-indep"}});
  CHECK(*rows[0].ratio_to_reference == 4.0);
  CHECK(*rows[2].ratio_to_reference == 2.0);
  std::vector<BenchRecord> alone = {row("gjk-johnson", 10)};
  const std::vector<RatioRole> one = {{AnswerKind::distance, std::nullopt}};
  set_case_ratios(alone, one, {"", "libccd-mpr", "libccd-gjk", {}});
  CHECK(alone[0].reference == "libccd-gjk");  // no peer distance query installed
  CHECK_FALSE(alone[0].ratio_to_reference.has_value());
}
