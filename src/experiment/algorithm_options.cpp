#include "gjklab/experiment/algorithm_options.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gjklab::experiment {

namespace {

bool is_gjk(std::string_view a) { return a == "gjk-bool" || a == "gjk-johnson"; }
bool is_libccd(std::string_view a) { return a == "libccd-gjk" || a == "libccd-mpr"; }

std::string round_trip(double x) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : std::to_string(x);
}

double non_negative(std::string_view key, double v) {
  if (!(v >= 0) || !std::isfinite(v))
    throw std::invalid_argument("must be >= 0 and finite, got " + round_trip(v));
  return v;
}

}  // namespace

std::vector<std::string_view> option_keys(std::string_view algorithm) {
  if (algorithm == "gjk-bool") return {"max_iterations", "initial_direction"};
  if (algorithm == "gjk-johnson")
    return {"max_iterations", "relative_gap", "absolute_gap_squared", "relative_contact",
            "initial_direction"};
  if (is_libccd(algorithm)) return {"max_iterations", "mpr_tolerance"};
  return {};
}

int option_arity(std::string_view key) { return key == "initial_direction" ? 3 : 1; }

void set_option(AlgorithmSpec& spec, std::string_view key, std::span<const double> values) {
  const auto keys = option_keys(spec.name);
  if (std::find(keys.begin(), keys.end(), key) == keys.end())
    throw std::invalid_argument("option '" + std::string(key) + "' does not apply to " + spec.name);
  if (static_cast<int>(values.size()) != option_arity(key))
    throw std::invalid_argument("option '" + std::string(key) + "' takes " +
                                std::to_string(option_arity(key)) + " number(s)");
  AlgorithmOptions& o = spec.options;
  const double v = values[0];
  if (key == "max_iterations") {
    if (!(v >= 1 && v <= std::numeric_limits<int>::max()) || v != std::floor(v))
      throw std::invalid_argument("max_iterations must be an integer >= 1");
    const int n = static_cast<int>(v);
    if (spec.name == "gjk-bool") o.gjk_boolean.max_iterations = n;
    else if (spec.name == "gjk-johnson") o.gjk_distance.max_iterations = n;
    else o.libccd.max_iterations = n;
  } else if (key == "relative_gap") {
    o.gjk_distance.relative_gap = non_negative(key, v);
  } else if (key == "absolute_gap_squared") {
    o.gjk_distance.absolute_gap_squared = non_negative(key, v);
  } else if (key == "relative_contact") {
    o.gjk_distance.relative_contact = non_negative(key, v);
  } else if (key == "mpr_tolerance") {
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument("mpr_tolerance must be > 0");
    o.libccd.mpr_tolerance = v;
  } else if (key == "initial_direction") {
    const Vec3 d(values[0], values[1], values[2]);
    if (!d.allFinite() || d.isZero(0))
      throw std::invalid_argument("initial_direction must be a finite non-zero vector");
    o.gjk_boolean.initial_direction = d;
    o.gjk_distance.initial_direction = d;
  }
}

std::vector<std::pair<std::string, std::string>> describe_options(const AlgorithmSpec& spec) {
  const AlgorithmOptions& o = spec.options;
  const std::string& n = spec.name;
  auto direction = [](const Vec3& d) {
    return round_trip(d.x()) + " " + round_trip(d.y()) + " " + round_trip(d.z());
  };
  if (n == "gjk-bool")
    return {{"max_iterations", std::to_string(o.gjk_boolean.max_iterations)},
            {"initial_direction", direction(o.gjk_boolean.initial_direction)}};
  if (n == "gjk-johnson")
    return {{"max_iterations", std::to_string(o.gjk_distance.max_iterations)},
            {"relative_gap", round_trip(o.gjk_distance.relative_gap)},
            {"absolute_gap_squared", round_trip(o.gjk_distance.absolute_gap_squared)},
            {"relative_contact", round_trip(o.gjk_distance.relative_contact)},
            {"initial_direction", direction(o.gjk_distance.initial_direction)}};
  if (is_libccd(n))
    return {{"max_iterations", std::to_string(o.libccd.max_iterations)},
            {"mpr_tolerance", round_trip(o.libccd.mpr_tolerance)}};
  if (n == "exact") return {{"depth", o.oracle.depth ? "true" : "false"}};
  return {};
}

AlgorithmSpec spec_from_description(const std::string& name,
                                    const std::vector<std::pair<std::string, std::string>>& text) {
  AlgorithmSpec spec;
  spec.name = name;
  spec.label = name;
  for (const auto& [key, value] : text) {
    std::vector<double> numbers;
    std::istringstream in(value);
    for (std::string word; in >> word;) {
      double x = 0;
      const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), x);
      if (ec != std::errc() || end != word.data() + word.size())
        throw std::invalid_argument("option '" + key + "' of " + name + ": not a number: '" +
                                    value + "'");
      numbers.push_back(x);
    }
    set_option(spec, key, numbers);
  }
  return spec;
}

}  // namespace gjklab::experiment
