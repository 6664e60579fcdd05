// The regression tests' data: one pair of a cases file under tests/regression/data/.
#pragma once

#include <catch2/catch.hpp>

#include <string>
#include <variant>

#include "gjklab/experiment/cases/cloud_io.hpp"

namespace gjklab::testing {

/// The single valid case of tests/regression/data/FILE (a `gjklab query --cases` file).
inline experiment::PointCase regression_case(const std::string& file) {
  const auto cases =
      experiment::read_cases_file(std::string(GJKLAB_REGRESSION_DATA_DIR) + "/" + file);
  REQUIRE(cases.size() == 1);
  REQUIRE(std::holds_alternative<experiment::PointCase>(cases[0]));
  return std::get<experiment::PointCase>(cases[0]);
}

}  // namespace gjklab::testing
