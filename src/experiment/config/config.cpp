#include "gjklab/experiment/config/config.hpp"

#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/cases/real_objects.hpp"
#include "gjklab/experiment/cases/scene_stream.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"

#include <toml++/toml.h>

#include "experiment/config/family_config.hpp"
#include "experiment/config/mesh_config.hpp"
#include "experiment/config/toml_section.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <system_error>

namespace gjklab::experiment {

namespace {

std::string format_message(const std::string& file, int line, const std::string& key,
                           const std::string& problem) {
  std::string message = file;
  if (line > 0) message += ":" + std::to_string(line);
  message += ": ";
  if (!key.empty()) message += "key '" + key + "': ";
  message += problem;
  return message;
}

}  // namespace

ConfigError::ConfigError(const std::string& file, int line, const std::string& key,
                         const std::string& problem)
    : std::runtime_error(format_message(file, line, key, problem)) {}

namespace {

// ---- limits that are not in the header ----
constexpr std::int64_t kMaxThreads = 1024;
constexpr std::int64_t kMaxCases = std::int64_t{1} << 32;  // case ids index 2^32 seed streams
constexpr std::int64_t kMaxRepetitions = 1'000'000;

/// The algorithms that answer for sphere-swept shapes, for messages.
std::string swept_algorithm_names() {
  std::vector<std::string_view> names;
  for (const AlgorithmInfo& a : algorithms())
    if (a.can.swept) names.push_back(a.name);
  return join(names);
}

/// `into` with every key of `over` put in: tables merge key by key, anything else (values,
/// arrays, arrays of tables such as [[family]] and [[algorithm]]) is replaced whole.
void merge_over(toml::table& into, const toml::table& over) {
  for (const auto& [key, node] : over) {
    toml::node* existing = into.get(key);
    if (existing && existing->is_table() && node.is_table()) {
      merge_over(*existing->as_table(), *node.as_table());
    } else {
      into.insert_or_assign(key, node);
    }
  }
}

/// `exclude_families = ["NAME", ...]`: drops the named families (typically a base experiment's
/// that do not suit the derived one); every name must exist and at least one family must stay.
void exclude_families(const Section& top, std::vector<FamilySpec>& families) {
  const toml::node* node = top.find("exclude_families");
  if (!node) return;
  const toml::array* names = node->as_array();
  if (!names) top.fail(*node, "exclude_families", "expected an array of family names");
  for (const toml::node& entry : *names) {
    if (!entry.is_string()) top.fail(entry, "exclude_families", "expected family names (strings)");
    const std::string& name = entry.as_string()->get();
    const auto found = std::find_if(families.begin(), families.end(),
                                    [&](const FamilySpec& f) { return f.name == name; });
    if (found == families.end()) {
      std::vector<std::string_view> known;
      for (const FamilySpec& f : families)
        known.push_back(f.name);
      top.fail(entry, "exclude_families", "no family '" + name + "'; families: " + join(known));
    }
    families.erase(found);
  }
  if (families.empty()) top.fail(*node, "exclude_families", "excludes every family");
}

/// Bases may themselves have a base, up to this depth (which also stops a cycle).
constexpr int kMaxBaseDepth = 8;

/// Rewrites each relative `path` of the base's [[family]] tables (relative to the base file's
/// folder) to name the same file relative to the derived file's folder, so that a base used
/// from another folder still finds its meshes and case files.
void rebase_family_paths(toml::table& base, const std::filesystem::path& base_folder,
                         const std::filesystem::path& derived_folder) {
  toml::array* families = base.get_as<toml::array>("family");
  if (!families) return;
  for (toml::node& node : *families) {
    toml::table* family = node.as_table();
    if (!family) continue;
    toml::value<std::string>* path = family->get_as<std::string>("path");
    if (!path || std::filesystem::path(path->get()).is_absolute()) continue;
    const std::filesystem::path target = (base_folder / path->get()).lexically_normal();
    const std::filesystem::path from =
        derived_folder.empty() ? std::filesystem::path(".") : derived_folder.lexically_normal();
    std::filesystem::path moved = target.lexically_relative(from);
    if (moved.empty()) moved = std::filesystem::absolute(target);
    *path = moved.generic_string();
  }
}

/// The experiment `derived` (read from `source`) over its base file: `base = "FILE"`, relative
/// to `source`'s folder. Keys of `derived` win; tables merge (see merge_over).
toml::table with_base(toml::table derived, const std::string& source, int depth) {
  const toml::node& node = *derived.get("base");
  const Section s(source, derived, "", 1);
  if (!node.is_string()) s.fail(node, "base", "expected a file name (a string)");
  if (depth >= kMaxBaseDepth)
    s.fail(node, "base",
           "bases nest deeper than " + std::to_string(kMaxBaseDepth) + " files (a cycle?)");
  std::filesystem::path path(node.as_string()->get());
  if (path.is_relative()) path = std::filesystem::path(source).parent_path() / path;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path))
    s.fail(node, "base", "cannot read the base experiment " + path.string());
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  toml::table base = parse_toml(text, path.string());
  if (base.contains("base")) base = with_base(std::move(base), path.string(), depth + 1);
  rebase_family_paths(base, path.parent_path(), std::filesystem::path(source).parent_path());
  derived.erase("base");
  merge_over(base, derived);
  return base;
}

/// The option keys of each algorithm beyond `name` and `max_iterations`.
std::vector<std::string_view> own_option_keys(std::string_view algorithm) {
  std::vector<std::string_view> keys = option_keys(algorithm);
  std::erase(keys, std::string_view("max_iterations"));
  return keys;
}

/// The text of one option's TOML value: a number, [x, y, z], a boolean or a string.
std::string option_text(const Section& s, const toml::node& node, std::string_view key) {
  if (node.is_string()) return node.as_string()->get();
  if (node.is_boolean()) return node.as_boolean()->get() ? "true" : "false";
  if (const toml::array* array = node.as_array()) {
    std::string text;
    for (std::size_t i = 0; i < array->size(); ++i)
      text += (i ? " " : "") + round_trip(s.number_value(*array->get(i), key));
    return text;
  }
  return round_trip(s.number_value(node, key));
}

/// The algorithms an experiment may list: the registry without the exact oracle.
std::vector<std::string_view> query_algorithm_names() {
  std::vector<std::string_view> names;
  for (const AlgorithmInfo& info : algorithms())
    if (info.kind != AnswerKind::exact) names.push_back(info.name);
  return names;
}

/// One [[algorithm]] table: one spec, or in a nonconvex experiment one per decomposition it
/// lists (mesh_config.hpp).
std::vector<AlgorithmSpec> read_algorithm(const Section& s, bool nonconvex) {
  std::vector<std::string_view> valid = query_algorithm_names();
  if (nonconvex)
    for (const MeshPeerInfo& peer : mesh_peers())
      valid.push_back(peer.name);
  const auto name = s.string("name");
  if (!name) s.missing("name", "missing (required); valid: " + join(valid));
  const toml::node& name_node = *s.find("name");
  if (const MeshPeerInfo* peer = find_mesh_peer(*name)) return {read_mesh_peer(s, *peer, nonconvex)};
  const AlgorithmInfo* info = find_algorithm(*name);
  if (info && info->kind == AnswerKind::exact)
    s.fail(name_node, "name",
           "'" + *name +
               "' is not listed as an algorithm: the exact oracle runs on every case "
               "and is configured by [oracle] (enabled, depth); valid: " +
               join(valid));
  if (!info) s.fail(name_node, "name", "unknown algorithm '" + *name + "'; valid: " + join(valid));

  std::vector<std::string_view> allowed = {"name", "label", "max_iterations"};
  for (std::string_view key : own_option_keys(*name))
    allowed.push_back(key);
  allowed.insert(allowed.end(), std::begin(kDecompositionKeys), std::end(kDecompositionKeys));
  s.allow_only(allowed, [&](std::string_view key) {
    std::vector<std::string_view> owners;
    for (std::string_view other : valid) {
      const auto keys = own_option_keys(other);
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) owners.push_back(other);
    }
    if (owners.empty()) return std::string();
    return "applies to " + join(owners) + ", not to " + *name + "; valid for " + *name + ": " +
           join(allowed);
  });

  AlgorithmSpec spec;
  spec.name = *name;
  spec.label = *name;
  if (const auto label = s.string("label")) {
    // The result group's name: lets one algorithm run twice with different options.
    if (label->empty() || label->find('/') != std::string::npos ||
        label->find('@') != std::string::npos)
      s.fail(*s.find("label"), "label", "must be non-empty and contain neither '/' nor '@'");
    spec.label = *label;
  }
  if (const toml::node* n = s.find("max_iterations"))
    s.integer_value(*n, "max_iterations", 1, std::numeric_limits<int>::max());
  for (std::string_view key : option_keys(*name)) {
    const toml::node* node = s.find(key);
    if (!node) continue;
    try {
      set_option(spec, key, option_text(s, *node, key));
    } catch (const std::invalid_argument& e) {
      s.fail(*node, key, e.what());
    }
  }
  return with_decompositions(s, std::move(spec), nonconvex);
}

constexpr std::string_view kGeometrySweeps[] = {"offset", "scale"};

/// The most values a sweep may have (see read_sweep).
constexpr std::size_t kMaxSweepValues = 256;

/// [sweep]: parameter = an algorithm option (each value becomes its own algorithm group) or a
/// geometry parameter (each value its own family group, on the same base pairs).
void read_sweep(const Section& s, ExperimentConfig& config) {
  s.allow_only({"parameter", "values"});
  const auto parameter = s.string("parameter");
  if (!parameter) s.missing("parameter");
  const toml::node* values_node = s.find("values");
  if (!values_node) s.missing("values");
  const toml::array* values = values_node->as_array();
  if (!values || values->empty())
    s.fail(*values_node, "values", "expected a non-empty array of values");
  // Each value is a result group (its own columns in the archive, held in memory per batch):
  // a million of them once took 8 GB before failing.
  if (values->size() > kMaxSweepValues)
    s.fail(*values_node, "values",
           "at most " + std::to_string(kMaxSweepValues) + " values (got " +
               std::to_string(values->size()) + ")");

  if (std::find(std::begin(kGeometrySweeps), std::end(kGeometrySweeps), *parameter) !=
      std::end(kGeometrySweeps)) {
    GeometrySweep sweep{*parameter, {}};
    for (std::size_t i = 0; i < values->size(); ++i) {
      const toml::node& v = *values->get(i);
      const double x = v.is_number() ? s.number_value(v, "values") : -1;
      if (!(*parameter == "offset" ? x >= 0 : x > 0))
        s.fail(
            v, "values",
            *parameter == "offset" ? "offsets must be numbers >= 0" : "scales must be numbers > 0");
      if (std::find(sweep.values.begin(), sweep.values.end(), x) != sweep.values.end())
        s.fail(v, "values", "value " + round_trip(x) + " appears twice");
      sweep.values.push_back(x);
    }
    config.geometry_sweep = std::move(sweep);
    return;
  }

  std::vector<std::string_view> sweepable{std::begin(kGeometrySweeps), std::end(kGeometrySweeps)};
  bool taken = false;
  std::vector<AlgorithmSpec> expanded;
  for (const AlgorithmSpec& spec : config.algorithms) {
    const auto keys = option_keys(spec.name);
    for (std::string_view k : keys)
      if (std::find(sweepable.begin(), sweepable.end(), k) == sweepable.end())
        sweepable.push_back(k);
    if (std::find(keys.begin(), keys.end(), *parameter) == keys.end()) {
      expanded.push_back(spec);  // this algorithm does not take the parameter: run it once
      continue;
    }
    taken = true;
    std::set<std::string> seen;  // each value is a result group: a repeat would clash
    for (std::size_t i = 0; i < values->size(); ++i) {
      const std::string text = option_text(s, *values->get(i), "values");
      if (!seen.insert(text).second)
        s.fail(*values->get(i), "values", "value " + text + " appears twice");
      AlgorithmSpec copy = spec;
      try {
        set_option(copy, *parameter, text);
      } catch (const std::invalid_argument& e) {
        s.fail(*values->get(i), "values", e.what());
      }
      std::string shown = text;
      std::replace(shown.begin(), shown.end(), ' ', ',');
      // A decomposition's label keeps it: the sweep's groups of each decomposition differ.
      const std::string& base = spec.decomposition ? spec.label : spec.name;
      copy.label = base + "@" + *parameter + "=" + shown;
      expanded.push_back(std::move(copy));
    }
  }
  if (!taken)
    s.fail(*s.find("parameter"), "parameter",
           "no listed algorithm takes '" + *parameter + "'; valid: " + join(sweepable));
  config.algorithms = std::move(expanded);
}

bool valid_experiment_name(std::string_view name) {
  if (name.empty() || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
}

/// The top-level scalars: name, seed, cases, threads, output and touching_band.
void read_run_settings(const Section& top, ExperimentConfig& config) {
  const auto name = top.string("name");
  if (!name) top.missing("name");
  if (!valid_experiment_name(*name))
    top.fail(*top.find("name"), "name",
             "must be non-empty and use only letters, digits, '_', '-' and '.' (not leading), "
             "got '" +
                 *name + "'");
  config.name = *name;

  const auto seed = top.integer("seed", 0, std::numeric_limits<std::int64_t>::max());
  if (!seed) top.missing("seed");
  config.seed = static_cast<std::uint64_t>(*seed);

  const auto cases = top.integer("cases", 1, kMaxCases);
  if (!cases) top.missing("cases");
  config.cases = static_cast<std::uint64_t>(*cases);

  if (const auto threads = top.integer("threads", 1, kMaxThreads))
    config.threads = static_cast<int>(*threads);
  config.output = "results/" + config.name + ".h5";
  if (const auto output = top.string("output")) {
    if (output->empty()) top.fail(*top.find("output"), "output", "must not be empty");
    config.output = *output;
  }
  if (const auto band = top.positive("touching_band")) config.touching_band = *band;
}

/// [oracle]: which exact answers are computed, and the switches that depend on each other.
void read_oracle(const Section& oracle, ExperimentConfig& config) {
  oracle.allow_only({"enabled", "depth", "certificates", "verify", "hull_vertices"});
  if (const auto enabled = oracle.boolean("enabled")) config.oracle = *enabled;
  if (const auto depth = oracle.boolean("depth")) config.depth = *depth;
  if (const auto certificates = oracle.boolean("certificates")) config.certificates = *certificates;
  if (const auto verify = oracle.boolean("verify")) config.verify = *verify;
  if (const auto hull_vertices = oracle.boolean("hull_vertices"))
    config.hull_vertices = *hull_vertices;
  if (config.verify && !config.certificates)
    oracle.fail(*oracle.find("verify"), "verify",
                "audits the certificates, which are off (certificates = false)");
  if (config.depth && !config.oracle)
    oracle.fail(*oracle.find("depth"), "depth", "needs the oracle (enabled = true)");
}

/// [timing]: whether queries are timed, and how often each is repeated.
void read_timing(const Section& timing, ExperimentConfig& config) {
  timing.allow_only({"enabled", "repetitions"});
  if (const auto enabled = timing.boolean("enabled")) config.timing = *enabled;
  if (const auto repetitions = timing.integer("repetitions", 1, kMaxRepetitions))
    config.repetitions = static_cast<int>(*repetitions);
}

/// The [[family]] tables (at least one, distinct names), then exclude_families.
void read_families(const Section& top, const PlacementSpec& placement, ExperimentConfig& config) {
  const toml::array* families = top.table_array("family");
  if (!families) top.missing("family", "missing: at least one [[family]] is required");
  if (families->empty())
    top.fail(*top.find("family"), "family", "at least one [[family]] is required");
  for (std::size_t i = 0; i < families->size(); ++i) {
    const toml::table& t = *families->get(i)->as_table();
    const Section s = top.child(t, "family[" + std::to_string(i) + "]");
    FamilySpec family = read_family(s, placement, config.source);
    for (std::size_t j = 0; j < config.families.size(); ++j)
      if (config.families[j].name == family.name)
        s.fail(s.find("name") ? line_of(*s.find("name")) : s.header_line(), "name",
               "family name '" + family.name + "' is already used by family[" + std::to_string(j) +
                   "]; give each family a distinct name");
    config.families.push_back(std::move(family));
  }
  exclude_families(top, config.families);
}

/// The [[algorithm]] tables (at least one, distinct labels); needs the families read first, to
/// refuse a polytope-only algorithm on sphere-swept shapes.
void read_algorithms(const Section& top, ExperimentConfig& config) {
  const toml::array* algorithms = top.table_array("algorithm");
  if (!algorithms) top.missing("algorithm", "missing: at least one [[algorithm]] is required");
  if (algorithms->empty())
    top.fail(*top.find("algorithm"), "algorithm", "at least one [[algorithm]] is required");
  for (std::size_t i = 0; i < algorithms->size(); ++i) {
    const toml::table& t = *algorithms->get(i)->as_table();
    const Section s = top.child(t, "algorithm[" + std::to_string(i) + "]");
    for (AlgorithmSpec& spec : read_algorithm(s, config.has_nonconvex_families())) {
      spec.options.oracle = config.oracle_options(config.depth);
      if (config.has_swept_shapes() && !find_algorithm(spec.name)->can.swept)
        s.fail(*s.find("name"), "name",
               "'" + spec.name +
                   "' answers for polytopes only, and this experiment has sphere-swept shapes "
                   "(a family with a radius, or shape sphere or capsule); valid here: " +
                   swept_algorithm_names());
      for (std::size_t j = 0; j < config.algorithms.size(); ++j)
        if (config.algorithms[j].label == spec.label)
          s.fail(*s.find(s.find("label") ? "label" : "name"), s.find("label") ? "label" : "name",
                 "'" + spec.label + "' is already used by algorithm[" + std::to_string(j) +
                     "]; give the second one its own label = \"...\"");
      config.algorithms.push_back(std::move(spec));
    }
  }
}

/// [trace]: which cases keep a per-iteration trace.
void read_trace(const Section& trace, ExperimentConfig& config) {
  trace.allow_only({"mode"});
  if (const auto mode = trace.string("mode")) {
    const auto value = trace_mode_from_string(*mode);
    if (!value)
      trace.fail(*trace.find("mode"), "mode",
                 "unknown trace mode '" + *mode + "'; valid: " + names_list(kTraceModeNames));
    config.trace = *value;
  }
}

/// The experiment merged with its base, if it names one, and the text the archive keeps: with a
/// base, the merged experiment, which reads back without the base.
std::pair<toml::table, std::string> resolve_base(const std::string& text,
                                                 const std::string& source) {
  toml::table root = parse_toml(text, source);
  if (!root.contains("base")) return {std::move(root), text};
  root = with_base(std::move(root), source, 0);
  std::ostringstream merged;
  merged << "# " << source << " merged with its base experiment\n"
         << toml::toml_formatter(root) << "\n";
  return {std::move(root), merged.str()};
}

}  // namespace

ExperimentConfig parse_experiment(const std::string& text, const std::string& source) {
  auto [root, effective_text] = resolve_base(text, source);
  const Section top(source, root, "", 1);
  top.allow_only({"name", "seed", "cases", "threads", "output", "touching_band", "oracle", "timing",
                  "placement", "family", "exclude_families", "algorithm", "sweep", "trace"});

  ExperimentConfig config;
  config.source = source;
  config.text = std::move(effective_text);
  read_run_settings(top, config);
  if (const toml::table* t = top.subtable("oracle")) read_oracle(top.child(*t, "oracle"), config);
  if (const toml::table* t = top.subtable("timing")) read_timing(top.child(*t, "timing"), config);
  PlacementSpec placement;
  if (const toml::table* t = top.subtable("placement"))
    placement = read_placement(top.child(*t, "placement"), placement);
  read_families(top, placement, config);
  read_algorithms(top, config);
  if (const toml::table* t = top.subtable("sweep")) read_sweep(top.child(*t, "sweep"), config);
  if (const toml::table* t = top.subtable("trace")) read_trace(top.child(*t, "trace"), config);
  check_nonconvex_experiment(top, config);
  return config;
}

ExperimentConfig load_experiment(const std::filesystem::path& path) {
  std::error_code ec;
  std::ifstream in;
  if (!std::filesystem::is_directory(path, ec)) in.open(path, std::ios::binary);
  if (!in.is_open() || !in) throw ConfigError(path.string(), 0, "", "cannot read");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw ConfigError(path.string(), 0, "", "cannot read");
  return parse_experiment(text, path.string());
}

bool ExperimentConfig::has_swept_shapes() const {
  auto swept_pair = [](const StoredPair& p) { return p.radius_a > 0 || p.radius_b > 0; };
  return std::any_of(families.begin(), families.end(), [&](const FamilySpec& f) {
    return f.radius_a.hi > 0 || f.radius_b.hi > 0 ||
           std::any_of(f.stored.begin(), f.stored.end(), swept_pair);
  });
}

bool ExperimentConfig::has_nonconvex_families() const {
  return std::any_of(families.begin(), families.end(),
                     [](const FamilySpec& f) { return f.nonconvex.has_value(); });
}

std::vector<std::string> ExperimentConfig::result_family_names() const {
  std::vector<std::string> names;
  for (const FamilySpec& f : families) {
    if (!geometry_sweep) {
      names.push_back(f.name);
      continue;
    }
    for (double v : geometry_sweep->values)
      names.push_back(f.name + " " + geometry_sweep->parameter + "=" + round_trip(v));
  }
  return names;
}

}  // namespace gjklab::experiment
