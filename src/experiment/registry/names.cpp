#include "gjklab/experiment/registry/names.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <variant>

#include "gjklab/experiment/bench/bench.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/hunt/hunt.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/meshes/mesh_query.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

namespace gjklab::experiment {

namespace {

using Json = nlohmann::ordered_json;

// A default value in its JSON type: numbers as numbers, a direction as [x, y, z], a choice by
// its name (the name an experiment file writes).
Json json_value(int v) {
  return v;
}
Json json_value(double v) {
  return v;
}
Json json_value(bool v) {
  return v;
}
Json json_value(const Vec3& v) {
  return Json::array({v.x(), v.y(), v.z()});
}
template <class E>
requires std::is_enum_v<E> Json json_value(E v) {
  return std::string(to_string(v));
}

/// The row's value in a default AlgorithmOptions: the default every experiment starts from.
Json default_value(const OptionRow& row) {
  AlgorithmOptions defaults;
  return std::visit([&](auto access) { return json_value(access(defaults)); }, row.member);
}

Json option_entry(const OptionRow& row) {
  const OptionValues values = option_values(row);
  Json j;
  j["key"] = row.key;
  j["type"] = values.type;
  j["default"] = default_value(row);
  j["accepts"] = values.accepts;
  if (!values.choices.empty()) j["choices"] = values.choices;
  j["meaning"] = row.meaning;
  // A key that is not settable is archived and replayed, but set elsewhere (the [oracle] table).
  j["settable"] = row.use == OptionUse::setting;
  return j;
}

Json algorithm_entry(const AlgorithmInfo& info) {
  Json j;
  j["name"] = info.name;
  j["group"] = to_string(group_of(info));
  j["kind"] = to_string(info.kind);
  j["answers"] = {
      {"boolean", true}, {"distance", info.kind != AnswerKind::boolean}, {"depth", info.depth}};
  j["description"] = info.description;
  j["swept"] = info.can.swept;
  j["traceable"] = info.can.traced;
  j["precisions"] = takes_precision(info);
  j["warm_start"] = info.can.warm;
  j["options"] = Json::array();
  for (const OptionRow& row : info.options)
    j["options"].push_back(option_entry(row));
  return j;
}

Json algorithm_list() {
  Json list = Json::array();
  for (const AlgorithmInfo& info : algorithms())
    list.push_back(algorithm_entry(info));
  return list;
}

Json shape_list() {
  Json list = Json::array();
  for (const FamilyShapeInfo& shape : family_shapes())
    list.push_back({{"name", shape.name}, {"description", shape.description}});
  return list;
}

Json placement_list() {
  Json list = Json::array();
  for (const auto& row : kPlacementModeNames)
    list.push_back(row.name);
  return list;
}

Json objective_list() {
  Json list = Json::array();
  for (const std::string& name : hunt_objective_names())
    list.push_back(
        {{"name", name}, {"meaning", hunt_objective_meaning(*hunt_objective_from_string(name))}});
  return list;
}

/// The decompositions of closed meshes, with their options, and the peers that answer for two
/// meshes themselves.
Json decomposition_list() {
  Json list = Json::array();
  for (const DecompositionInfo& d : decompositions()) {
    Json options = Json::array();
    for (const DecompositionOptionRow& row : d.options)
      options.push_back({{"key", row.key}, {"meaning", row.meaning}});
    list.push_back({{"name", d.name}, {"description", d.description}, {"options", options}});
  }
  return list;
}

Json mesh_peer_list() {
  Json list = Json::array();
  for (const MeshPeerInfo& p : mesh_peers())
    list.push_back({{"name", p.name}, {"description", p.description}});
  return list;
}

}  // namespace

nlohmann::ordered_json names_document() {
  Json doc;
  doc["algorithms"] = algorithm_list();
  doc["shapes"] = shape_list();
  doc["contacts"] = contact_choices();
  doc["placements"] = placement_list();
  doc["hunt_objectives"] = objective_list();
  doc["bench_suites"] = bench::all_suites();
  doc["decompositions"] = decomposition_list();
  doc["mesh_peers"] = mesh_peer_list();
  return doc;
}

}  // namespace gjklab::experiment
