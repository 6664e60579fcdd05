// Expected values of the code that turns answers into published numbers, from hand-made
// records: contact classes, judged records, witness errors, kept geometry, failure classes,
// the run and oracle-method summaries.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <sstream>

#include "gjklab/experiment/run/judging.hpp"
#include "gjklab/experiment/cases/records.hpp"
#include "gjklab/experiment/run/summary.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

namespace {

constexpr double kBand = 1e-10;

ExactRecord exact_answer(bool intersect, ContactClass contact) {
  ExactRecord e;
  e.intersect = intersect;
  e.contact = contact;
  return e;
}

AlgorithmRecord answer(bool intersect, double rel_error, Termination t = Termination::converged) {
  AlgorithmRecord r;
  r.intersect = intersect;
  r.distance = 1;
  r.rel_error = rel_error;
  r.abs_error = rel_error;
  r.termination = t;
  return r;
}

}  // namespace

TEST_CASE("classify_failure: every class from a hand-made record", "[unit][measuring]") {
  const ExactRecord apart = exact_answer(false, ContactClass::separated);
  const ExactRecord band = exact_answer(false, ContactClass::touching_band);

  CHECK(classify_failure(answer(false, 1e-12), &apart, kBand) == FailureClass::none);
  CHECK(classify_failure(answer(false, 1e-9), &apart, kBand) == FailureClass::distance_error);
  AlgorithmRecord wrong = answer(true, 1e-12);
  wrong.boolean_correct = false;
  CHECK(classify_failure(wrong, &apart, kBand) == FailureClass::wrong_boolean);
  // Inside the touching band a wrong boolean or distance is the band's, not the algorithm's.
  CHECK(classify_failure(wrong, &band, kBand) == FailureClass::touching_band);
  CHECK(classify_failure(answer(false, 1e-9), &band, kBand) == FailureClass::touching_band);
  // A right answer in the band is no failure.
  CHECK(classify_failure(answer(false, 1e-12), &band, kBand) == FailureClass::none);
  // Terminations come before the answer's accuracy.
  CHECK(classify_failure(answer(false, 0, Termination::step_limit), &apart, kBand) ==
        FailureClass::step_limit);
  CHECK(classify_failure(answer(false, 0, Termination::no_progress), &apart, kBand) ==
        FailureClass::no_progress);
  CHECK(classify_failure(answer(false, 0, Termination::degenerate_simplex), &apart, kBand) ==
        FailureClass::degenerate_simplex);
  CHECK(classify_failure(answer(false, 0, Termination::cycling), &apart, kBand) ==
        FailureClass::cycling);
  CHECK(classify_failure(answer(false, 0, Termination::numerical_failure), &apart, kBand) ==
        FailureClass::non_finite);
  CHECK(classify_failure(answer(false, 0, Termination::invalid_input), &apart, kBand) ==
        FailureClass::non_finite);
  AlgorithmRecord infinite = answer(false, std::numeric_limits<double>::quiet_NaN());
  infinite.distance = std::numeric_limits<double>::infinity();
  CHECK(classify_failure(infinite, &apart, kBand) == FailureClass::non_finite);
  // Without the oracle only the termination can fail.
  CHECK(classify_failure(answer(true, std::nan("")), nullptr, kBand) == FailureClass::none);
  CHECK(classify_failure(answer(true, std::nan(""), Termination::step_limit), nullptr, kBand) ==
        FailureClass::step_limit);
}

TEST_CASE("summary: counts, medians and terminations from hand-made results", "[unit][measuring]") {
  SummaryBuilder builder({"alg"});
  // Five cases: relative errors 1e-16 … 5e-16, one wrong boolean, one step limit.
  for (int i = 1; i <= 5; ++i) {
    CaseResult r;
    r.exact = exact_answer(false, i == 5 ? ContactClass::touching_band : ContactClass::separated);
    AlgorithmRecord a =
        answer(false, i * 1e-16, i == 4 ? Termination::step_limit : Termination::converged);
    a.iterations = i;
    a.boolean_correct = i != 3;
    r.algorithms.push_back(a);
    builder.add(r);
  }
  const RunSummary s = builder.build();
  CHECK(s.cases == 5);
  CHECK(s.contact[static_cast<int>(ContactClass::separated)] == 4);
  CHECK(s.contact[static_cast<int>(ContactClass::touching_band)] == 1);
  REQUIRE(s.algorithms.size() == 1);
  const AlgorithmSummary& a = s.algorithms[0];
  CHECK(a.cases == 5);
  CHECK(a.wrong_booleans == 1);
  CHECK(a.distances == 5);
  CHECK(a.rel_error_median == 3e-16);
  CHECK(a.rel_error_max == 5e-16);
  CHECK(a.terminations[static_cast<int>(Termination::step_limit)] == 1);
  CHECK(a.terminations[static_cast<int>(Termination::converged)] == 4);
  CHECK(a.iterations_mean == 3);
  CHECK(a.iterations_max == 5);
}

TEST_CASE("oracle methods: certified fractions per family", "[unit][measuring]") {
  std::vector<CaseResult> results(6);
  for (std::size_t i = 0; i < results.size(); ++i) {
    results[i].record.family = i < 4 ? 0 : 2;  // family 1 has no case
    ExactRecord e;
    e.method = i == 1 ? exact::AnswerMethod::qp : exact::AnswerMethod::certified;
    e.depth_method = i == 2   ? exact::AnswerMethod::certified
                     : i == 3 ? exact::AnswerMethod::qp
                              : exact::AnswerMethod::none;
    results[i].exact = e;
  }
  results[5].exact.reset();  // without the oracle: not counted
  const auto counts = oracle_method_counts(results, {"first", "empty", "last"});
  REQUIRE(counts.size() == 2);
  CHECK(counts[0].family == "first");
  CHECK(counts[0].cases == 4);
  CHECK(counts[0].certified == 3);
  CHECK(counts[0].depths == 2);
  CHECK(counts[0].depths_certified == 1);
  CHECK(counts[1].family == "last");
  CHECK(counts[1].cases == 1);
  CHECK(counts[1].certified == 1);
  CHECK(counts[1].depths == 0);
  std::ostringstream table;
  print_oracle_methods(table, counts);
  CHECK(table.str().find("first                          4     75.00%       2     50.00%") !=
        std::string::npos);
  CHECK(table.str().find("last                           1    100.00%       0          -") !=
        std::string::npos);
  CHECK(table.str().find("all                            5     80.00%       2     50.00%") !=
        std::string::npos);
}

TEST_CASE("contact class and exact record from a hand-made exact answer", "[unit][measuring]") {
  exact::OracleAnswer apart;
  apart.distance_squared = {"1", "4"};
  apart.distance = 0.5;
  apart.method = exact::AnswerMethod::certified;
  CHECK(contact_class(apart, 0.25) == ContactClass::separated);
  CHECK(contact_class(apart, 0.5) == ContactClass::touching_band);  // the band is inclusive
  exact::OracleAnswer deep;
  deep.intersect = true;
  deep.distance_squared = {"0", "1"};
  CHECK(contact_class(deep, 0.1) == ContactClass::intersecting);  // no depth: intersecting
  deep.depth = 0.05;
  deep.depth_squared = exact::Rational{"1", "400"};
  deep.depth_method = exact::AnswerMethod::qp;
  CHECK(contact_class(deep, 0.1) == ContactClass::touching_band);
  CHECK(contact_class(deep, 0.01) == ContactClass::intersecting);

  const ExactRecord r = exact_record(apart, 0.25);
  CHECK_FALSE(r.intersect);
  CHECK(r.distance == 0.5);
  CHECK(r.distance2_num == "1");
  CHECK(r.distance2_den == "4");
  CHECK(std::isnan(r.depth));
  CHECK(r.contact == ContactClass::separated);
  CHECK(r.method == exact::AnswerMethod::certified);
  CHECK(r.depth_method == exact::AnswerMethod::none);
  const ExactRecord d = exact_record(deep, 0.01);
  CHECK(d.depth == 0.05);
  CHECK(d.depth_method == exact::AnswerMethod::qp);
}

TEST_CASE("judge: errors and correctness of an answer against the exact one", "[unit][measuring]") {
  ExactRecord exact = exact_answer(false, ContactClass::separated);
  exact.distance = 2.0;
  Outcome o;
  o.distance = 2.5;
  o.iterations = 7;
  o.termination = Termination::no_progress;
  AlgorithmRecord r = algorithm_record(o);
  CHECK(r.iterations == 7);
  CHECK(r.termination == Termination::no_progress);
  CHECK(std::isnan(r.abs_error));  // not judged yet
  judge(r, o, exact, 4.0);
  CHECK(r.abs_error == 0.5);
  CHECK(r.rel_error == 0.125);
  CHECK(r.boolean_correct);
  CHECK(std::isnan(r.depth_abs_error));

  // A boolean algorithm (no distance) that says intersect for a separated pair.
  Outcome boolean;
  boolean.intersect = true;
  AlgorithmRecord b = algorithm_record(boolean);
  judge(b, boolean, exact, 4.0);
  CHECK_FALSE(b.boolean_correct);
  CHECK(std::isnan(b.abs_error));
  CHECK(std::isnan(b.rel_error));
  exact.contact = ContactClass::touching_band;  // either answer is right inside the band
  judge(b, boolean, exact, 4.0);
  CHECK(b.boolean_correct);

  // Depth errors once the exact depth is known; judged again, nothing stale remains.
  ExactRecord deep = exact_answer(true, ContactClass::intersecting);
  Outcome epa;
  epa.intersect = true;
  epa.distance = 0.0;
  epa.depth = 0.75;
  AlgorithmRecord e = algorithm_record(epa);
  judge(e, epa, deep, 2.0);
  CHECK(std::isnan(e.depth_abs_error));  // the exact depth was not computed
  deep.depth = 0.5;
  judge(e, epa, deep, 2.0);
  CHECK(e.depth_abs_error == 0.25);
  CHECK(e.depth_rel_error == 0.125);
}

TEST_CASE("worth_keeping: wrong, unconverged or inaccurate answers keep their geometry",
          "[unit][measuring]") {
  CaseResult r;
  r.algorithms.push_back(answer(false, 1e-12));
  CHECK_FALSE(worth_keeping(r, kBand));
  r.algorithms.push_back(answer(false, 2e-10));  // above the band
  CHECK(worth_keeping(r, kBand));
  r.algorithms.back() = answer(false, 1e-12, Termination::step_limit);
  CHECK(worth_keeping(r, kBand));
  r.algorithms.back() = answer(false, std::nan(""));
  r.algorithms.back().boolean_correct = false;
  CHECK(worth_keeping(r, kBand));
}

TEST_CASE("witness errors recorded from an outcome's witness points", "[unit][measuring]") {
  const std::vector<Vec3> a = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<Vec3> b = {{3, 0, 0}, {4, 0, 0}};
  exact::OracleAnswer exact_answer;
  exact_answer.distance_squared = {"4", "1"};
  exact_answer.distance = 2;
  Outcome o;
  o.witness_a = Vec3(1, 0, 0);
  o.witness_b = Vec3(3.5, 0, 0);  // on B, but 2.5 from the witness on A
  AlgorithmRecord r = algorithm_record(o);
  add_witnesses(r, o, &exact_answer, a, b);
  CHECK(r.witness_a == Vec3(1, 0, 0));
  CHECK(r.witness_error_a == 0);
  CHECK(r.witness_error_b == 0);
  CHECK(r.witness_distance_error == 0.5);
  o.witness_a = Vec3(-0.75, 0, 0);  // 0.75 from A (its nearest point is the origin)
  AlgorithmRecord off = algorithm_record(o);
  add_witnesses(off, o, &exact_answer, a, b);
  CHECK(off.witness_error_a == 0.75);
  CHECK(off.witness_distance_error == 2.25);  // |4.25 − 2|
  // No oracle, or no witnesses: NaN.
  AlgorithmRecord none = algorithm_record(o);
  add_witnesses(none, o, nullptr, a, b);
  CHECK(none.witness_a == Vec3(-0.75, 0, 0));
  CHECK(std::isnan(none.witness_error_a));
  Outcome boolean;
  AlgorithmRecord no_witness = algorithm_record(boolean);
  add_witnesses(no_witness, boolean, &exact_answer, a, b);
  CHECK(std::isnan(no_witness.witness_a.x()));
  CHECK(std::isnan(no_witness.witness_distance_error));
}

TEST_CASE("per-family table: counts per family and columns aligned for long names",
          "[unit][measuring]") {
  FamilySummaryBuilder builder({"short", "a-family-name-longer-than-24"},
                               {"gjk-johnson", "gjk-johnson-backup"});
  for (int i = 0; i < 3; ++i) {
    CaseResult r;
    r.record.family = i == 0 ? 0 : 1;
    r.exact = exact_answer(false, ContactClass::separated);
    AlgorithmRecord wrong = answer(true, 1e-12);
    wrong.boolean_correct = false;
    r.algorithms = {
        answer(false, 1e-12, i == 2 ? Termination::no_progress : Termination::converged), wrong};
    builder.add(r);
  }
  const auto families = builder.build();
  REQUIRE(families.size() == 2);
  CHECK(families[0].second.cases == 1);
  CHECK(families[1].second.cases == 2);
  CHECK(families[1].second.algorithms[1].wrong_booleans == 2);
  std::ostringstream out;
  print_family_table(out, families);
  std::istringstream lines(out.str());
  std::string header, line;
  std::getline(lines, header);
  const std::size_t cases_end = header.find("cases") + 5;
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    // Every count ends where the header's "cases" ends, whatever the names' lengths.
    CHECK(line.size() > cases_end);
    CHECK(line[cases_end - 1] != ' ');
    CHECK(line[cases_end] == ' ');
  }
  CHECK(rows == 4);
  CHECK(out.str().find("no_progress=1") != std::string::npos);
}

TEST_CASE("needs_exact_depth: a 'separated' answer to an intersecting pair asks for the depth",
          "[unit][measuring]") {
  exact::OracleAnswer deep;
  deep.intersect = true;
  std::vector<AlgorithmRecord> agree = {answer(true, 0)};
  CHECK_FALSE(needs_exact_depth(deep, agree));
  std::vector<AlgorithmRecord> disagree = {answer(true, 0), answer(false, 0)};
  CHECK(needs_exact_depth(deep, disagree));
  // A step-limit stop fails by its termination: its disagreement does not pay for the depth.
  std::vector<AlgorithmRecord> stopped = {answer(false, 0, Termination::step_limit)};
  CHECK_FALSE(needs_exact_depth(deep, stopped));
  deep.depth = 0.25;  // already computed
  CHECK_FALSE(needs_exact_depth(deep, disagree));
  exact::OracleAnswer apart;  // separated pairs need no depth
  CHECK_FALSE(needs_exact_depth(apart, disagree));
}
