// Every registered algorithm's options come from its schema rows: each key an experiment may
// set must change what the archive records (a key validated but not applied would leave the
// description at its default), and the archived description must rebuild the same options.
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <type_traits>

#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

namespace {

/// A text for the row's key that differs from the value in `options`, within its range.
std::string other_value(const OptionRow& row, AlgorithmOptions options) {
  return std::visit(
      [&](auto access) -> std::string {
        const auto current = access(options);
        using T = std::remove_cvref_t<decltype(current)>;
        if constexpr (std::is_same_v<T, int>) {
          return std::to_string(current > 4 ? current - 1 : current + 1);
        } else if constexpr (std::is_same_v<T, double>) {
          return round_trip(current * 2 + 0.5);
        } else if constexpr (std::is_same_v<T, bool>) {
          return current ? "false" : "true";
        } else if constexpr (std::is_same_v<T, Vec3>) {
          return current.isApprox(Vec3(0.5, -1, 2)) ? "1 2 3" : "0.5 -1 2";
        } else {
          for (unsigned v = 0; v < 8; ++v) {
            const std::string_view name = to_string(static_cast<T>(v));
            if (name == "unknown") break;
            if (static_cast<T>(v) != current) return std::string(name);
          }
          FAIL("enum option " << row.key << " has one value only");
          return "";
        }
      },
      row.member);
}

std::map<std::string, std::string> as_map(
    const std::vector<std::pair<std::string, std::string>>& described) {
  return {described.begin(), described.end()};
}

}  // namespace

TEST_CASE("every option key an algorithm takes is applied and archived", "[unit][options]") {
  int keys_checked = 0;
  for (const AlgorithmInfo& info : algorithms()) {
    for (const OptionRow& row : info.options) {
      if (row.use != OptionUse::setting) continue;
      INFO(info.name << ": " << row.key);
      AlgorithmSpec spec;
      spec.name = std::string(info.name);
      spec.label = spec.name;
      const auto before = as_map(describe_options(spec));
      const std::string value = other_value(row, spec.options);
      set_option(spec, row.key, value);
      const auto after = as_map(describe_options(spec));
      REQUIRE(after.count(std::string(row.key)) == 1);
      CHECK(after.at(std::string(row.key)) != before.at(std::string(row.key)));
      CHECK(after.at(std::string(row.key)) == value);
      ++keys_checked;
    }
  }
  CHECK(keys_checked >= 40);  // the GJK variants alone take 10 keys each
}

TEST_CASE("an archived description rebuilds the same options", "[unit][options]") {
  for (const AlgorithmInfo& info : algorithms()) {
    INFO(info.name);
    AlgorithmSpec spec;
    spec.name = std::string(info.name);
    spec.label = spec.name;
    for (const OptionRow& row : info.options)
      if (row.use == OptionUse::setting) set_option(spec, row.key, other_value(row, spec.options));
    spec.options.oracle.depth = true;  // `exact` records the [oracle] table's depth flag
    const auto described = describe_options(spec);
    CHECK(describe_options(spec_from_description(spec.name, described)) == described);
    // option_keys lists the settable rows, in order; the description every row.
    std::size_t settable = 0;
    for (const OptionRow& row : info.options)
      settable += row.use == OptionUse::setting;
    CHECK(option_keys(info.name).size() == settable);
    CHECK(described.size() == info.options.size());
  }
}

TEST_CASE("option values outside a row's range are refused with the range", "[unit][options]") {
  AlgorithmSpec epa;
  epa.name = "epa";
  CHECK_THROWS_WITH(set_option(epa, "max_faces", "3"), Catch::Contains("must be in [4, 2^26]"));
  CHECK_THROWS_WITH(set_option(epa, "epa_relative_gap", "-1"), Catch::Contains("must be >= 0"));
  AlgorithmSpec libccd;
  libccd.name = "libccd-gjk";
  CHECK_THROWS_WITH(set_option(libccd, "mpr_tolerance", "0"), Catch::Contains("must be > 0"));
  AlgorithmSpec exact;
  exact.name = "exact";
  CHECK_THROWS_WITH(set_option(exact, "depth", "true"), Catch::Contains("does not apply to exact"));
  CHECK(spec_from_description("exact", {{"depth", "true"}}).options.oracle.depth);
}
