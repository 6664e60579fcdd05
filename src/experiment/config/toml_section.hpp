// The one TOML reader of gjklab's files (private to src/: the experiment layer's config and bench
// rooms and the simulation layer's scene files include it; no public header names toml++).
// A Section reads one table: typed, range-checked values, unknown keys refused, and every
// problem a ConfigError "FILE:LINE: key 'a.b': problem" naming the value's line and dotted key.
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"

namespace gjklab::experiment {

template <typename Range>
std::string join(const Range& items) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    out += std::string_view(item);
  }
  return out;
}

/// "a string", "an integer", ...: a node's type as messages name it.
std::string_view type_name(const toml::node& node);
int line_of(const toml::source_region& region);
int line_of(const toml::node& node);

/// The document in `text`; a syntax error is a ConfigError naming `source` and the line.
toml::table parse_toml(const std::string& text, const std::string& source);

/// One TOML table being read: checks unknown keys up front, then reads typed, range-checked
/// values and reports problems as ConfigError with the dotted key path and the value's line.
class Section {
 public:
  Section(const std::string& file, const toml::table& table, std::string path, int header_line)
      : file_(file), table_(table), path_(std::move(path)), header_line_(header_line) {}

  const toml::table& table() const { return table_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  int header_line() const { return header_line_; }

  std::string key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }

  [[noreturn]] void fail(int line, std::string_view key, const std::string& problem) const {
    throw ConfigError(file_, line, key_path(key), problem);
  }
  [[noreturn]] void fail(const toml::node& node, std::string_view key,
                         const std::string& problem) const {
    fail_at(node.source(), key, problem);
  }
  /// A value (or key) inherited from a base experiment names the base file.
  [[noreturn]] void fail_at(const toml::source_region& where, std::string_view key,
                            const std::string& problem) const {
    throw ConfigError(where.path ? *where.path : file_, line_of(where), key_path(key), problem);
  }
  [[noreturn]] void missing(std::string_view key, const std::string& what = {}) const {
    fail(header_line_, key, what.empty() ? "missing (required)" : what);
  }

  /// Rejects every key not in `allowed` (the first one in file order). `explain` may turn an
  /// unknown key into a more specific message (e.g. a key that belongs to another algorithm).
  template <typename Explain>
  void allow_only(const std::vector<std::string_view>& allowed, Explain explain) const {
    const toml::key* first = nullptr;
    for (auto&& [key, value] : table_) {
      (void)value;
      if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
      if (!first || key.source().begin.line < first->source().begin.line) first = &key;
    }
    if (!first) return;
    std::string problem = explain(first->str());
    if (problem.empty()) problem = "unknown key; valid: " + join(allowed);
    fail_at(first->source(), first->str(), problem);
  }
  void allow_only(const std::vector<std::string_view>& allowed) const {
    allow_only(allowed, [](std::string_view) { return std::string(); });
  }

  const toml::node* find(std::string_view key) const { return table_.get(key); }

  /// The section of a nested table, named `path` (a dotted key path) in messages.
  Section child(const toml::table& table, std::string path) const {
    return Section(file_, table, std::move(path), line_of(table));
  }

  std::optional<std::string> string(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_string())
      fail(*node, key, "expected a string, got " + std::string(type_name(*node)));
    return node->as_string()->get();
  }

  std::optional<bool> boolean(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_boolean())
      fail(*node, key, "expected a boolean (true or false), got " + std::string(type_name(*node)));
    return node->as_boolean()->get();
  }

  /// An integer in [lo, hi].
  std::optional<std::int64_t> integer(std::string_view key, std::int64_t lo,
                                      std::int64_t hi) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    return integer_value(*node, key, lo, hi);
  }

  std::int64_t integer_value(const toml::node& node, std::string_view key, std::int64_t lo,
                             std::int64_t hi) const {
    if (!node.is_integer())
      fail(node, key, "expected an integer, got " + std::string(type_name(node)));
    const std::int64_t v = node.as_integer()->get();
    if (v < lo || v > hi) {
      if (hi == std::numeric_limits<std::int64_t>::max())
        fail(node, key, "must be at least " + std::to_string(lo) + ", got " + std::to_string(v));
      fail(node, key,
           "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " +
               std::to_string(v));
    }
    return v;
  }

  /// A finite number (an integer is accepted and converted).
  double number_value(const toml::node& node, std::string_view key) const {
    double v = 0;
    if (node.is_floating_point())
      v = node.as_floating_point()->get();
    else if (node.is_integer())
      v = static_cast<double>(node.as_integer()->get());
    else
      fail(node, key, "expected a number, got " + std::string(type_name(node)));
    if (!std::isfinite(v)) fail(node, key, "must be finite, got " + round_trip(v));
    return v;
  }

  std::optional<double> positive(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const double v = number_value(*node, key);
    if (!(v > 0)) fail(*node, key, "must be > 0, got " + round_trip(v));
    return v;
  }

  std::optional<double> non_negative(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const double v = number_value(*node, key);
    if (!(v >= 0)) fail(*node, key, "must be >= 0, got " + round_trip(v));
    return v;
  }

  std::optional<double> fraction(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const double v = number_value(*node, key);
    if (!(v >= 0 && v <= 1)) fail(*node, key, "must be between 0 and 1, got " + round_trip(v));
    return v;
  }

  /// A number >= 0 (fixed) or a [lo, hi] pair with 0 < lo <= hi (a log-uniform range).
  /// A radius: a number >= 0 or a positive [lo, hi], at most max_radius (shape units, as
  /// `scale`'s bound: a radius of 1e308 overflowed the placement's coordinates).
  std::optional<Interval> radius_interval(std::string_view key, double max_radius) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    Interval r;
    if (node->is_number()) {
      const double v = number_value(*node, key);
      if (!(v >= 0)) fail(*node, key, "must be >= 0, got " + round_trip(v));
      r = Interval{v, v};
    } else {
      r = *positive_interval(key);
    }
    if (!(r.hi <= max_radius))
      fail(*node, key, "must be at most " + round_trip(max_radius) + ", got " + round_trip(r.hi));
    return r;
  }

  /// A positive number or a [lo, hi] pair with 0 < lo <= hi.
  std::optional<Interval> positive_interval(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    Interval interval;
    if (const toml::array* array = node->as_array()) {
      if (array->size() != 2)
        fail(*node, key,
             "expected [lo, hi] (two numbers), got " + std::to_string(array->size()) + " elements");
      interval.lo = number_value(*array->get(0), key);
      interval.hi = number_value(*array->get(1), key);
    } else if (node->is_number()) {
      interval.lo = interval.hi = number_value(*node, key);
    } else {
      fail(*node, key, "expected a number or [lo, hi], got " + std::string(type_name(*node)));
    }
    if (!(interval.lo > 0))
      fail(*node, key, "lower bound must be > 0, got " + round_trip(interval.lo));
    if (!(interval.lo <= interval.hi))
      fail(*node, key,
           "lower bound " + round_trip(interval.lo) + " exceeds upper bound " +
               round_trip(interval.hi));
    return interval;
  }

  /// An integer count or a [lo, hi] pair of counts with 1 <= lo <= hi <= max_count.
  std::optional<Interval> count_interval(std::string_view key, std::int64_t max_count) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    Interval interval;
    if (const toml::array* array = node->as_array()) {
      if (array->size() != 2)
        fail(
            *node, key,
            "expected [lo, hi] (two integers), got " + std::to_string(array->size()) + " elements");
      interval.lo = static_cast<double>(integer_value(*array->get(0), key, 1, max_count));
      interval.hi = static_cast<double>(integer_value(*array->get(1), key, 1, max_count));
      if (interval.lo > interval.hi)
        fail(*node, key,
             "lower bound " + std::to_string(static_cast<std::int64_t>(interval.lo)) +
                 " exceeds upper bound " + std::to_string(static_cast<std::int64_t>(interval.hi)));
    } else if (node->is_integer()) {
      interval.lo = interval.hi = static_cast<double>(integer_value(*node, key, 1, max_count));
    } else {
      fail(*node, key, "expected an integer or [lo, hi], got " + std::string(type_name(*node)));
    }
    return interval;
  }

  /// A sub-table (either [a.b] or an inline table), or nullptr if absent.
  const toml::table* subtable(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return nullptr;
    if (!node->is_table())
      fail(*node, key, "expected a table, got " + std::string(type_name(*node)));
    return node->as_table();
  }

  /// An array of tables ([[key]]); its elements must all be tables.
  const toml::array* table_array(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return nullptr;
    const toml::array* array = node->as_array();
    if (!array)
      fail(*node, key,
           "expected an array of tables ([[" + std::string(key) + "]]), got " +
               std::string(type_name(*node)));
    for (std::size_t i = 0; i < array->size(); ++i)
      if (!array->get(i)->is_table())
        fail(*array->get(i), std::string(key) + "[" + std::to_string(i) + "]",
             "expected a table, got " + std::string(type_name(*array->get(i))));
    return array;
  }

 private:
  const std::string& file_;
  const toml::table& table_;
  std::string path_;
  int header_line_;
};


}  // namespace gjklab::experiment
