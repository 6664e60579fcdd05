// The benchmark's config file (TOML): measurement settings and the published figures the seed
// tables print beside the measured ones; and the environment a report records.
#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "bench_parts.hpp"
#include "experiment/config/toml_section.hpp"
#include "gjklab/build_info.hpp"

namespace gjklab::experiment::bench {

// ---- config file ----------------------------------------------------------------------------

namespace {

/// The file's text; an unreadable file is a ConfigError naming it.
std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path))
    throw ConfigError(path, 0, "", "cannot read the bench config");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// An array of strings (absent: `out` unchanged).
void read_strings(const Section& s, std::string_view key, std::vector<std::string>& out) {
  const toml::node* n = s.find(key);
  if (!n) return;
  const toml::array* a = n->as_array();
  if (!a) s.fail(*n, key, "expected an array of strings, got " + std::string(type_name(*n)));
  out.clear();
  for (const toml::node& e : *a) {
    if (!e.is_string()) s.fail(e, key, "expected strings, got " + std::string(type_name(e)));
    out.push_back(e.as_string()->get());
  }
}

/// `precision`, `samples`, `configurations`, `seed` and `batch_seconds`.
void read_measurement(const Section& s, BenchConfig& c) {
  if (const auto precision = s.string("precision")) {
    const auto p = precision_from_string(*precision);
    if (!p) s.fail(*s.find("precision"), "precision", "must be \"float\", \"double\" or \"long double\"");
    c.precision = *p;
  }
  if (auto v = s.integer("samples", 1, 100000)) c.samples = static_cast<int>(*v);
  if (auto v = s.integer("configurations", 1, 100000)) c.configurations = static_cast<int>(*v);
  if (auto v = s.integer("seed", 0, std::numeric_limits<std::int64_t>::max()))
    c.seed = static_cast<std::uint64_t>(*v);
  if (const toml::node* n = s.find("batch_seconds")) {
    const double v = s.number_value(*n, "batch_seconds");
    if (!(v >= 0 && v <= 10)) s.fail(*n, "batch_seconds", "must be a number in [0, 10]");
    c.batch_seconds = v;
  }
}

/// One published time (µs per pair or ms per scene): a finite number >= 0. TOML reads `inf`
/// and `nan` as numbers, and the tables print the figure and its ratio to the measured time.
double published_time(const Section& s, const toml::node& v, std::string_view key) {
  const double x = s.number_value(v, key);
  if (!(x >= 0)) s.fail(v, key, "must be a finite number >= 0");
  return x;
}

/// [published]: the figures the seed tables are compared with (µs per pair, ms per scene).
void read_published(const Section& pub, BenchConfig& c) {
  pub.allow_only({"source", "pair_us", "scene_ms"});
  if (auto v = pub.string("source")) c.published_source = *v;
  if (const toml::table* pairs = pub.subtable("pair_us")) {
    const Section p = pub.child(*pairs, pub.key_path("pair_us"));
    for (const auto& [k, v] : *pairs)
      c.published_pair_us[std::string(k.str())] = published_time(p, v, k.str());
  }
  if (const toml::table* scene = pub.subtable("scene_ms")) {
    const Section m = pub.child(*scene, pub.key_path("scene_ms"));
    for (const auto& [k, v] : *scene) {
      const double x = published_time(m, v, k.str());
      int objects = 0;
      const std::string_view name = k.str();
      const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), objects);
      if (ec != std::errc() || end != name.data() + name.size() || objects < 1)
        m.fail_at(k.source(), name, "must be an object count (an integer >= 1)");
      c.published_scene_ms[objects] = x;
    }
  }
}

BenchConfig read_bench_config(const std::string& path) {
  const toml::table table = parse_toml(read_text(path), path);
  const Section s(path, table, "", 1);
  s.allow_only({"suites", "algorithms", "reference", "samples", "batch_seconds", "configurations",
                "seed", "cases", "published", "description", "precision"});
  BenchConfig c;
  read_strings(s, "suites", c.suites);
  // An empty list would measure nothing and still exit 0.
  if (c.suites.empty()) {
    const std::string problem = "must name at least one suite (" + suite_list() + ")";
    if (!s.find("suites")) s.missing("suites", problem);
    s.fail(*s.find("suites"), "suites", problem);
  }
  read_strings(s, "algorithms", c.algorithms);
  if (auto v = s.string("reference")) c.reference = *v;
  if (auto v = s.string("cases")) c.case_filter = *v;
  (void)s.string("description");
  read_measurement(s, c);
  if (const toml::table* pub = s.subtable("published"))
    read_published(s.child(*pub, "published"), c);
  return c;
}

}  // namespace

BenchConfig load_bench_config(const std::string& path) {
  try {
    return read_bench_config(path);
  } catch (const ConfigError& e) {
    throw BenchError(e.what());
  }
}

std::map<std::string, std::string> bench_environment() {
  std::map<std::string, std::string> env;
  env["gjklab"] = std::string(build_info::version) + " (" + build_info::git_commit + ")";
  env["compiler"] = std::string(build_info::compiler) + " " + build_info::cxx_flags;
  std::string cpu = "unknown";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  env["cpu"] = cpu;
  return env;
}

}  // namespace gjklab::experiment::bench
