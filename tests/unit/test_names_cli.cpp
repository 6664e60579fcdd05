// `gjklab names`: the document tools read instead of lists of their own must list every
// registered algorithm, with the defaults the registry itself describes, and every name of the
// other tables.
#include <catch2/catch.hpp>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/experiment/bench/bench.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/hunt/hunt.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/meshes/mesh_query.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

using namespace gjklab;
using namespace gjklab::experiment;
using gjklab::testing::run_cli;

namespace {

nlohmann::json names_json() {
  const testing::CliResult r = run_cli({"names", "--json"});
  REQUIRE(r.status == 0);
  REQUIRE(r.err.empty());
  return nlohmann::json::parse(r.out);
}

/// A JSON default as the archive's description writes it (describe_options), so that the two
/// can be compared as text: numbers round-tripped, a direction as "x y z".
std::string as_described(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer()) return std::to_string(value.get<long long>());
  if (value.is_number()) return round_trip(value.get<double>());
  std::string text;
  for (const nlohmann::json& x : value) {
    if (!text.empty()) text += ' ';
    text += as_described(x);
  }
  return text;
}

/// The registry's own description of the algorithm's default options.
std::vector<std::pair<std::string, std::string>> registry_defaults(std::string_view name) {
  AlgorithmSpec spec;
  spec.name = spec.label = std::string(name);
  return describe_options(spec);
}

std::vector<std::string> names_of(const nlohmann::json& list) {
  std::vector<std::string> names;
  for (const nlohmann::json& entry : list)
    names.push_back(entry.is_object() ? entry["name"].get<std::string>()
                                      : entry.get<std::string>());
  return names;
}

// A boolean GJK of the test's own, so that the document is seen to follow the registry.
Outcome run_never(const QueryRequest&) {
  return {};
}

}  // namespace

TEST_CASE("names --json lists every registered algorithm with the registry's defaults",
          "[unit][names]") {
  const nlohmann::json doc = names_json();
  const nlohmann::json& listed = doc["algorithms"];
  REQUIRE(listed.size() == algorithms().size());
  std::size_t i = 0;
  for (const AlgorithmInfo& info : algorithms()) {
    const nlohmann::json& a = listed[i++];
    INFO(info.name);
    CHECK(a["name"] == std::string(info.name));
    CHECK(a["kind"] == std::string(to_string(info.kind)));
    CHECK(a["group"] == std::string(to_string(group_of(info))));
    CHECK(a["answers"]["depth"] == info.depth);
    CHECK(a["answers"]["distance"] == (info.kind != AnswerKind::boolean));
    const auto defaults = registry_defaults(info.name);
    REQUIRE(a["options"].size() == defaults.size());
    for (std::size_t k = 0; k < defaults.size(); ++k) {
      const nlohmann::json& option = a["options"][k];
      INFO(defaults[k].first);
      CHECK(option["key"] == defaults[k].first);
      CHECK(as_described(option["default"]) == defaults[k].second);
      CHECK_FALSE(option["meaning"].get<std::string>().empty());
      CHECK_FALSE(option["accepts"].get<std::string>().empty());
      if (option["type"] == "choice") {
        const auto choices = option["choices"].get<std::vector<std::string>>();
        CHECK(std::find(choices.begin(), choices.end(), defaults[k].second) != choices.end());
      }
    }
  }
}

TEST_CASE("names groups the algorithms: gjklab's GJK variants, its others, peers, the oracle",
          "[unit][names]") {
  const nlohmann::json doc = names_json();
  auto group = [&](const std::string& name) {
    for (const nlohmann::json& a : doc["algorithms"])
      if (a["name"] == name) return a["group"].get<std::string>();
    return std::string("absent");
  };
  CHECK(group("gjk-bool") == "gjk");
  CHECK(group("gjk-johnson") == "gjk");
  CHECK(group("gjk-polyak") == "gjk");
  CHECK(group("epa") == "own");
  CHECK(group("sat") == "own");
  CHECK(group("gjk-certified") == "own");
  CHECK(group("libccd-mpr") == "peer");
  CHECK(group("exact") == "oracle");
}

TEST_CASE("names follows the registry: an added algorithm is listed with its options",
          "[unit][names]") {
  const AddedAlgorithm added({.name = "test-names-added",
                              .kind = AnswerKind::boolean,
                              .description = "an algorithm only this test registers",
                              .run = run_never,
                              .options = sat_option_schema()});
  const nlohmann::json listed = names_json()["algorithms"];
  const nlohmann::json& last = listed.back();
  CHECK(last["name"] == "test-names-added");
  CHECK(last["group"] == "own");
  REQUIRE(last["options"].size() == 1);
  CHECK(last["options"][0]["key"] == "early_exit");
  CHECK(last["options"][0]["type"] == "boolean");
}

TEST_CASE("names lists the shapes, contacts, placements, hunt objectives and bench suites",
          "[unit][names]") {
  const nlohmann::json doc = names_json();
  std::vector<std::string> shapes;
  for (const FamilyShapeInfo& s : family_shapes())
    shapes.emplace_back(s.name);
  CHECK(names_of(doc["shapes"]) == shapes);
  std::vector<std::string> contacts;
  for (std::string_view c : contact_choices())
    contacts.emplace_back(c);
  CHECK(names_of(doc["contacts"]) == contacts);
  CHECK(names_of(doc["placements"]) ==
        std::vector<std::string>{"separated", "overlapping", "mixed", "random", "touching"});
  CHECK(names_of(doc["hunt_objectives"]) == hunt_objective_names());
  for (const nlohmann::json& o : doc["hunt_objectives"])
    CHECK_FALSE(o["meaning"].get<std::string>().empty());
  CHECK(names_of(doc["bench_suites"]) == bench::all_suites());
  std::vector<std::string> decompositions;
  for (const DecompositionInfo& d : experiment::decompositions())
    decompositions.emplace_back(d.name);
  CHECK(names_of(doc["decompositions"]) == decompositions);
  CHECK(decompositions.size() >= 2);
  for (const nlohmann::json& d : doc["decompositions"])
    for (const nlohmann::json& o : d["options"])
      CHECK_FALSE(o["meaning"].get<std::string>().empty());
  std::vector<std::string> peers;
  for (const MeshPeerInfo& p : experiment::mesh_peers())
    peers.emplace_back(p.name);
  CHECK(names_of(doc["mesh_peers"]) == peers);
}

TEST_CASE("names without --json: one line per algorithm and one per other table", "[unit][names]") {
  const testing::CliResult r = run_cli({"names"});
  REQUIRE(r.status == 0);
  for (const AlgorithmInfo& info : algorithms())
    CHECK(r.out.find("\n  " + std::string(info.name) + " ") != std::string::npos);
  CHECK(r.out.find("max_iterations=128") != std::string::npos);  // gjk-johnson's default
  CHECK(r.out.find("\nhunt_objectives: wrong_boolean, ") != std::string::npos);
  CHECK(r.out.find("\nbench_suites: seed, random, scene\n") != std::string::npos);
  CHECK(r.out.find("\ndecompositions: hull, exact") != std::string::npos);
}
