// The messages in which the ranks of a distributed run send their results to rank 0: every
// archived field survives the trip, and a damaged message is refused.
#include <catch2/catch.hpp>

#include "../../src/experiment/run/result_codec.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/run/driver.hpp"

using namespace gjklab::experiment;

namespace {

// gjk-johnson stopped after two steps fails (step limit) on most pairs, so those cases keep
// their geometry; every query keeps its trace.
constexpr const char* kExperiment = R"(
name = "codec"
seed = 3
cases = 60
[oracle]
enabled = true
[trace]
mode = "all"
[placement]
mode = "mixed"
gap = [1e-14, 1e-9]
depth = [1e-14, 1e-9]
[[family]]
shape = "gaussian"
vertices = [8, 32]
[[algorithm]]
name = "gjk-johnson"
max_iterations = 2
[[algorithm]]
name = "libccd-gjk"
[[algorithm]]
name = "epa"
)";

std::string encoded(std::span<const CaseResult> results) {
  codec::ByteWriter out;
  codec::encode_results(out, results);
  return out.take();
}

}  // namespace

TEST_CASE("result messages carry every archived field, geometry and traces", "[unit]") {
  const ExperimentConfig config = parse_experiment(kExperiment, "codec.toml");
  std::vector<CaseResult> results;
  for (std::uint64_t i = 0; i < config.cases; ++i)
    results.push_back(evaluate_case(config, i));
  const auto kept = std::count_if(results.begin(), results.end(),
                                  [](const CaseResult& r) { return r.geometry.has_value(); });
  REQUIRE(kept > 0);  // the sample exercises the geometry
  REQUIRE(!results[0].traces.at(0).empty());

  const std::string bytes = encoded(results);
  codec::ByteReader in(bytes);
  const std::vector<CaseResult> back = codec::decode_results(in);
  CHECK(in.done());
  REQUIRE(back.size() == results.size());
  // The encoding writes every column of the archive's schema, so equal bytes after a round
  // trip mean every field came back.
  CHECK(encoded(back) == bytes);
  for (std::size_t i = 0; i < back.size(); ++i) {
    CHECK(back[i].record.case_id == results[i].record.case_id);
    CHECK(back[i].geometry.has_value() == results[i].geometry.has_value());
    CHECK(back[i].traces.size() == results[i].traces.size());
  }
}

TEST_CASE("a truncated result message is refused", "[unit]") {
  const ExperimentConfig config = parse_experiment(kExperiment, "codec.toml");
  const std::vector<CaseResult> results{evaluate_case(config, 0), evaluate_case(config, 1)};
  const std::string bytes = encoded(results);
  for (std::size_t cut : {std::size_t{0}, std::size_t{5}, bytes.size() / 2, bytes.size() - 1}) {
    codec::ByteReader in(std::string_view(bytes).substr(0, cut));
    CHECK_THROWS_WITH(codec::decode_results(in), Catch::Contains("malformed result message"));
  }
}
