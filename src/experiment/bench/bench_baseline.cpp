// The baseline of `gjklab bench --compare FILE`: the records of an earlier run's `--json`
// output, of each only what a comparison needs. A file that is not such an output is refused
// with its name and the problem, before the run starts, so that a mistyped path does not cost a
// whole run.
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>

#include "bench_parts.hpp"

namespace gjklab::experiment::bench {

namespace {

using Json = nlohmann::json;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw BenchError(path + ": " + what);
}

/// nlohmann's message without its "[json.exception.parse_error.101] " prefix, which names the
/// library's exception rather than the file's problem.
std::string parse_message(const std::exception& e) {
  std::string message = e.what();
  if (message.rfind("[json.exception.", 0) == 0)
    if (const auto end = message.find("] "); end != std::string::npos) message.erase(0, end + 2);
  return message;
}

Json parse_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory, not a JSON file");
  std::ifstream in(path);
  if (!in) fail(path, std::string("cannot be read (") + std::strerror(errno) + ")");
  try {
    return Json::parse(in);
  } catch (const Json::parse_error& e) {
    fail(path, "is not JSON: " + parse_message(e));
  }
}

/// One record of the baseline; its errors name the file and the record ("records[3]").
class RecordReader {
 public:
  RecordReader(const std::string& path, std::size_t index, const Json& record)
      : path_(path), where_("records[" + std::to_string(index) + "]"), record_(record) {
    if (!record_.is_object()) fail_here("is not an object");
  }

  std::string text(const char* key) const {
    const auto it = record_.find(key);
    if (it == record_.end() || !it->is_string())
      fail_here(std::string("has no \"") + key + "\" (a string)");
    return it->get<std::string>();
  }

  /// A ratio: empty when null (no ratio in that run) or, unless `required`, absent; otherwise
  /// a positive number, since the comparison divides by it.
  std::optional<double> ratio(const char* key, bool required) const {
    const auto it = record_.find(key);
    if (it == record_.end()) {
      if (required) fail_here(std::string("has no \"") + key + "\" (a number or null)");
      return std::nullopt;
    }
    if (it->is_null()) return std::nullopt;
    if (!it->is_number()) fail_here(std::string("\"") + key + "\" is not a number or null");
    const double v = it->get<double>();
    if (!(v > 0) || !std::isfinite(v))
      fail_here(std::string("\"") + key + "\" is " + it->dump() + ", not a positive number");
    return v;
  }

  [[noreturn]] void fail_here(const std::string& what) const { fail(path_, where_ + " " + what); }

 private:
  const std::string& path_;
  std::string where_;
  const Json& record_;
};

/// The meta block's scalar fields as text; the comparison only shows and checks them, so a
/// missing or odd meta block is no error.
std::map<std::string, std::string> read_meta(const Json& doc) {
  std::map<std::string, std::string> meta;
  const auto it = doc.find("meta");
  if (it == doc.end() || !it->is_object()) return meta;
  for (const auto& [key, value] : it->items()) {
    if (value.is_string())
      meta[key] = value.get<std::string>();
    else if (value.is_number() || value.is_boolean())
      meta[key] = value.dump();
  }
  return meta;
}

}  // namespace

BenchBaseline read_baseline(const std::string& path) {
  const Json doc = parse_file(path);
  if (!doc.is_object())
    fail(path,
         "is not a bench report: expected an object with \"meta\" and \"records\", as "
         "`gjklab bench --json` writes");
  const auto records = doc.find("records");
  if (records == doc.end() || !records->is_array())
    fail(path, "has no \"records\" array: not a bench report (`gjklab bench --json`)");
  BenchBaseline baseline;
  baseline.path = path;
  baseline.meta = read_meta(doc);
  // Two records of one row would make the comparison pick one of them silently.
  std::map<std::tuple<std::string, std::string, std::string>, std::size_t> seen;
  for (std::size_t i = 0; i < records->size(); ++i) {
    const RecordReader reader(path, i, (*records)[i]);
    BenchRecord r;
    r.suite = reader.text("suite");
    r.case_name = reader.text("case");
    r.algorithm = reader.text("algorithm");
    r.reference = reader.text("reference");
    r.ratio_to_reference = reader.ratio("ratio_to_reference", true);
    r.ratio_to_floor = reader.ratio("ratio_to_floor", false);
    const auto [at, inserted] = seen.try_emplace({r.suite, r.case_name, r.algorithm}, i);
    if (!inserted)
      reader.fail_here("repeats records[" + std::to_string(at->second) + "] (" + r.suite + ", " +
                       r.case_name + ", " + r.algorithm + ")");
    baseline.records.push_back(std::move(r));
  }
  return baseline;
}

}  // namespace gjklab::experiment::bench
