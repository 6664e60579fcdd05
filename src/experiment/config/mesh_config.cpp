#include "experiment/config/mesh_config.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace gjklab::experiment {

namespace {

/// The decompositions the table lists, with the node each was read from (for messages).
std::vector<const DecompositionInfo*> listed_decompositions(const Section& s) {
  const toml::node* node = s.find("decomposition");
  if (!node) return {&decomposition_named("hull")};
  std::vector<const toml::node*> names;
  if (const toml::array* list = node->as_array()) {
    if (list->empty()) s.fail(*node, "decomposition", "lists no decomposition");
    for (const toml::node& entry : *list)
      names.push_back(&entry);
  } else {
    names.push_back(node);
  }
  std::vector<const DecompositionInfo*> out;
  for (const toml::node* name : names) {
    if (!name->is_string())
      s.fail(*name, "decomposition",
             "expected a decomposition's name or a list of them; valid: " + decomposition_names());
    try {
      const DecompositionInfo* d = &decomposition_named(name->as_string()->get());
      if (std::ranges::find(out, d) != out.end())
        s.fail(*name, "decomposition", "lists '" + std::string(d->name) + "' twice");
      out.push_back(d);
    } catch (const std::invalid_argument& e) {
      s.fail(*name, "decomposition", e.what());
    }
  }
  return out;
}

/// The text of an option's value (a number or a boolean).
std::string decomposition_option_text(const Section& s, const toml::node& value,
                                      std::string_view key) {
  if (value.is_boolean()) return value.as_boolean()->get() ? "true" : "false";
  if (value.is_integer()) return std::to_string(value.as_integer()->get());
  if (value.is_floating_point()) return round_trip(value.as_floating_point()->get());
  s.fail(value, key, "expected a number or true/false");
}

/// `decomposition_options = { KEY = VALUE, … }`, set on each listed decomposition that takes
/// options; a key none of them takes is refused.
void read_decomposition_options(const Section& s, const DecompositionInfo& d,
                                DecompositionOptions& options) {
  const toml::node* node = s.find("decomposition_options");
  if (!node || d.options.empty()) return;
  const toml::table* table = node->as_table();
  if (!table) s.fail(*node, "decomposition_options", "expected a table { KEY = VALUE, ... }");
  for (auto&& [key, value] : *table) {
    const std::string path = "decomposition_options." + std::string(key.str());
    try {
      set_decomposition_option(d, options, key.str(),
                               decomposition_option_text(s, value, path));
    } catch (const std::invalid_argument& e) {
      s.fail(value, path, e.what());
    }
  }
}

}  // namespace

AlgorithmSpec read_mesh_peer(const Section& s, const MeshPeerInfo& peer, bool nonconvex) {
  if (!nonconvex) {
    std::string problem = "'";
    problem += peer.name;
    problem += "' answers for two meshes, and this experiment has no nonconvex family";
    s.fail(*s.find("name"), "name", problem);
  }
  s.allow_only({"name", "label"});
  AlgorithmSpec spec;
  spec.name = std::string(peer.name);
  spec.label = spec.name;
  if (const auto label = s.string("label")) {
    if (label->empty() || label->find('/') != std::string::npos ||
        label->find('@') != std::string::npos)
      s.fail(*s.find("label"), "label", "must be non-empty and contain neither '/' nor '@'");
    spec.label = *label;
  }
  spec.mesh_peer = &peer;
  return spec;
}

std::vector<AlgorithmSpec> with_decompositions(const Section& s, AlgorithmSpec spec,
                                               bool nonconvex) {
  if (!nonconvex) {
    for (std::string_view key : kDecompositionKeys)
      if (s.find(key))
        s.fail(*s.find(key), key, "applies only to experiments of nonconvex families");
    return {std::move(spec)};
  }
  const std::vector<const DecompositionInfo*> listed = listed_decompositions(s);
  if (s.find("decomposition_options") &&
      std::ranges::none_of(listed, [](const auto* d) { return !d->options.empty(); }))
    s.fail(*s.find("decomposition_options"), "decomposition_options",
           "none of the decompositions listed takes options");
  if (s.find("label") && listed.size() > 1)
    s.fail(*s.find("label"), "label",
           "cannot name several decompositions' results (each is labelled "
           "name@decomposition=NAME)");
  std::vector<AlgorithmSpec> out;
  for (const DecompositionInfo* d : listed) {
    AlgorithmSpec copy = spec;
    copy.decomposition = d;
    read_decomposition_options(s, *d, copy.decomposition_options);
    if (s.find("decomposition") && !s.find("label"))
      copy.label = spec.name + "@decomposition=" + std::string(d->name);
    out.push_back(std::move(copy));
  }
  return out;
}

void check_nonconvex_experiment(const Section& top, const ExperimentConfig& config) {
  if (!config.has_nonconvex_families()) return;
  const toml::array& families = *top.table_array("family");
  for (std::size_t i = 0; i < config.families.size(); ++i)
    if (!config.families[i].nonconvex)
      top.fail(*families.get(i), "family[" + std::to_string(i) + "].shape",
               "this experiment has nonconvex families, whose cases are meshes: convex families "
               "go in an experiment of their own");
  if (config.geometry_sweep)
    top.fail(*top.find("sweep"), "sweep.parameter",
             "a geometry sweep does not apply to nonconvex families");
  if (const toml::node* trace = top.find("trace"); trace && config.trace != TraceMode::none)
    top.fail(*trace, "trace.mode",
             "traces are not kept for nonconvex families (a query runs over many pairs of "
             "pieces)");
  if (const toml::table* oracle = top.subtable("oracle"))
    for (std::string_view key : {"depth", "certificates", "verify", "hull_vertices"})
      if (oracle->contains(key))
        top.fail(*oracle->get(key), "oracle." + std::string(key),
                 "does not apply to nonconvex families (their truth is exact::mesh_truth, "
                 "without depth; only 'enabled' applies)");
}

}  // namespace gjklab::experiment
