// A scene file's TOML tables as the scene reader reads them (private to src/simulation): the
// scene reader's calls (a value or its default, range-checked) over the one TOML reader,
// experiment's Section, so that every problem is a ConfigError "FILE:LINE: key 'a.b': problem"
// as the experiment and bench files' are.
#pragma once

#include <toml++/toml.h>

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "experiment/config/toml_section.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::simulation {

using experiment::line_of;

/// One table being read, named by its dotted key path in messages.
class SceneTable {
 public:
  SceneTable(const std::string& file, const toml::table& t, std::string path)
      : s_(file, t, std::move(path), line_of(t)) {}

  std::string key(std::string_view k) const { return s_.key_path(k); }
  int line() const { return s_.header_line(); }
  /// A problem with key `k`, at its value's line (the table's when the key is absent).
  [[noreturn]] void fail(std::string_view k, const std::string& problem) const {
    if (const toml::node* n = s_.find(k)) s_.fail(*n, k, problem);
    s_.fail(line(), k, problem);
  }
  /// The message fail(k, problem) would throw, for a warning.
  std::string message(std::string_view k, const std::string& problem) const {
    const toml::node* n = s_.find(k);
    return experiment::ConfigError(file(), n ? line_of(*n) : line(), key(k), problem).what();
  }
  void allow_only(std::initializer_list<std::string_view> allowed) const {
    s_.allow_only(std::vector<std::string_view>(allowed));
  }
  bool has(std::string_view k) const { return s_.find(k) != nullptr; }

  /// A finite number in [lo, hi] (an integer converts), or `fallback` when absent.
  double number(std::string_view k, double fallback, double lo, double hi) const {
    const toml::node* n = s_.find(k);
    if (!n) return fallback;
    const double v = s_.number_value(*n, k);
    if (v < lo || v > hi)
      s_.fail(*n, k,
              "must be in [" + experiment::round_trip(lo) + ", " + experiment::round_trip(hi) +
                  "], not " + experiment::round_trip(v));
    return v;
  }
  std::int64_t integer(std::string_view k, std::int64_t fallback, std::int64_t lo,
                       std::int64_t hi) const {
    return s_.integer(k, lo, hi).value_or(fallback);
  }
  bool boolean(std::string_view k, bool fallback) const {
    return s_.boolean(k).value_or(fallback);
  }
  std::string string(std::string_view k, const std::string& fallback) const {
    return s_.string(k).value_or(fallback);
  }
  /// An array of `size` finite numbers.
  std::vector<double> numbers(std::string_view k, std::size_t size) const {
    const toml::array* a = has(k) ? s_.find(k)->as_array() : nullptr;
    if (!a) fail(k, "expected an array of " + std::to_string(size) + " numbers");
    return numbers_of(*a, k, size);
  }
  std::vector<double> numbers_of(const toml::array& a, std::string_view k, std::size_t size) const {
    if (a.size() != size) fail(k, "expected " + std::to_string(size) + " numbers");
    std::vector<double> out;
    for (const toml::node& n : a)
      out.push_back(s_.number_value(n, k));
    return out;
  }
  Vec3 vec3(std::string_view k, const Vec3& fallback) const {
    if (!has(k)) return fallback;
    const auto v = numbers(k, 3);
    return Vec3(v[0], v[1], v[2]);
  }
  /// A sub-table (absent: an empty one).
  SceneTable child(std::string_view k) const {
    const toml::table* t = s_.subtable(k);
    return SceneTable(file(), t ? *t : empty_, key(k));
  }
  /// The tables of an array of tables ([[k]]).
  std::vector<SceneTable> tables(std::string_view k) const {
    std::vector<SceneTable> out;
    const toml::array* a = s_.table_array(k);
    if (!a) return out;
    for (std::size_t i = 0; i < a->size(); ++i)
      out.emplace_back(file(), *a->get(i)->as_table(), key(k) + "[" + std::to_string(i) + "]");
    return out;
  }
  const toml::table& raw() const { return s_.table(); }
  const std::string& file() const { return s_.file(); }

 private:
  static inline const toml::table empty_{};
  experiment::Section s_;
};

}  // namespace gjklab::simulation
