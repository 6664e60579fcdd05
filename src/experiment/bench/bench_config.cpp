// The benchmark's config file (TOML): measurement settings and the published figures the seed
// tables print beside the measured ones; and the environment a report records.
#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "bench_parts.hpp"
#include "gjklab/build_info.hpp"

namespace gjklab::experiment::bench {

// ---- config file ----------------------------------------------------------------------------

namespace {

/// A parsed bench configuration file and its typed readers. Every value is checked for its
/// type and range (the command line's ranges): a value of the wrong type is an error, never
/// ignored, and no value is narrowed.
class BenchFile {
 public:
  explicit BenchFile(const std::string& path) : path_(path) {
    try {
      table_ = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
      std::ostringstream msg;
      msg << path << ":" << e.source().begin.line << ": " << e.description();
      throw BenchError(msg.str());
    }
  }

  const toml::table& table() const { return table_; }

  [[noreturn]] void fail(const std::string& what) const { throw BenchError(path_ + ": " + what); }

  void allow_only(const std::set<std::string>& known) const {
    for (const auto& [key, node] : table_) {
      (void)node;
      if (!known.count(std::string(key.str())))
        fail("unknown key '" + std::string(key.str()) + "'");
    }
  }

  void strings(const char* key, std::vector<std::string>& out) const {
    if (const toml::node* n = table_.get(key)) {
      const toml::array* a = n->as_array();
      if (!a) fail(std::string(key) + " must be an array of strings");
      out.clear();
      for (const toml::node& e : *a) {
        if (!e.is_string()) fail(std::string(key) + " must be an array of strings");
        out.push_back(e.as_string()->get());
      }
    }
  }

  void text(const char* key, std::string& out) const {
    if (const toml::node* n = table_.get(key)) {
      if (!n->is_string()) fail(std::string(key) + " must be a string");
      out = n->as_string()->get();
    }
  }

  std::optional<std::int64_t> integer(const char* key, std::int64_t lo, std::int64_t hi) const {
    const toml::node* n = table_.get(key);
    if (!n) return std::nullopt;
    if (!n->is_integer() || n->as_integer()->get() < lo || n->as_integer()->get() > hi)
      fail(std::string(key) + " must be an integer in [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    return n->as_integer()->get();
  }

 private:
  std::string path_;
  toml::table table_;
};

/// `precision`, `samples`, `configurations`, `seed` and `batch_seconds`.
void read_measurement(const BenchFile& f, BenchConfig& c) {
  std::string precision;
  f.text("precision", precision);
  if (!precision.empty()) {
    const auto p = precision_from_string(precision);
    if (!p) f.fail("precision must be \"float\", \"double\" or \"long double\"");
    c.precision = *p;
  }
  if (auto v = f.integer("samples", 1, 100000)) c.samples = static_cast<int>(*v);
  if (auto v = f.integer("configurations", 1, 100000)) c.configurations = static_cast<int>(*v);
  if (auto v = f.integer("seed", 0, std::numeric_limits<std::int64_t>::max()))
    c.seed = static_cast<std::uint64_t>(*v);
  if (const toml::node* n = f.table().get("batch_seconds")) {
    const auto v = n->value<double>();  // integers convert exactly
    if (!v || !(*v >= 0 && *v <= 10)) f.fail("batch_seconds must be a number in [0, 10]");
    c.batch_seconds = *v;
  }
}

/// One published time (µs per pair or ms per scene): a finite number >= 0. TOML reads `inf`
/// and `nan` as numbers, and the tables print the figure and its ratio to the measured time.
double published_time(const BenchFile& f, const toml::node& v, const std::string& key) {
  const auto x = v.value<double>();  // integers convert exactly
  if (!x || !std::isfinite(*x) || *x < 0) f.fail(key + " must be a finite number >= 0");
  return *x;
}

/// [published]: the figures the seed tables are compared with (µs per pair, ms per scene).
void read_published(const BenchFile& f, const toml::table& pub, BenchConfig& c) {
  if (auto v = pub["source"].value<std::string>()) c.published_source = *v;
  if (const toml::table* pairs = pub["pair_us"].as_table())
    for (const auto& [k, v] : *pairs)
      c.published_pair_us[std::string(k.str())] =
          published_time(f, v, "published.pair_us." + std::string(k.str()));
  if (const toml::table* scene = pub["scene_ms"].as_table())
    for (const auto& [k, v] : *scene) {
      const double x = published_time(f, v, "published.scene_ms." + std::string(k.str()));
      int objects = 0;
      const std::string_view name = k.str();
      const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), objects);
      if (ec != std::errc() || end != name.data() + name.size() || objects < 1)
        f.fail("published.scene_ms: key '" + std::string(name) +
               "' must be an object count (an integer >= 1)");
      c.published_scene_ms[objects] = x;
    }
}

}  // namespace

BenchConfig load_bench_config(const std::string& path) {
  const BenchFile f(path);
  BenchConfig c;
  f.strings("suites", c.suites);
  // An empty list would measure nothing and still exit 0.
  if (c.suites.empty()) f.fail("suites must name at least one suite (" + suite_list() + ")");
  f.strings("algorithms", c.algorithms);
  f.allow_only({"suites", "algorithms", "reference", "samples", "batch_seconds", "configurations",
                "seed", "cases", "published", "description", "precision"});
  f.text("reference", c.reference);
  f.text("cases", c.case_filter);
  read_measurement(f, c);
  if (const toml::table* pub = f.table()["published"].as_table()) read_published(f, *pub, c);
  return c;
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
