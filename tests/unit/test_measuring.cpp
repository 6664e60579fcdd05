// Expected values of the code that turns answers into published numbers, from hand-made
// records: the failure classes, the run and oracle-method summaries.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <sstream>

#include "gjklab/experiment/records.hpp"
#include "gjklab/experiment/summary.hpp"

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

TEST_CASE("summary: counts, medians and terminations from hand-made results",
          "[unit][measuring]") {
  SummaryBuilder builder({"alg"});
  // Five cases: relative errors 1e-16 … 5e-16, one wrong boolean, one step limit.
  for (int i = 1; i <= 5; ++i) {
    CaseResult r;
    r.exact = exact_answer(false, i == 5 ? ContactClass::touching_band : ContactClass::separated);
    AlgorithmRecord a = answer(false, i * 1e-16, i == 4 ? Termination::step_limit
                                                         : Termination::converged);
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
