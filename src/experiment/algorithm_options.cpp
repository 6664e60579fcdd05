#include "gjklab/experiment/algorithm_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gjklab::experiment {

namespace {

bool is_libccd(std::string_view a) {
  return a == "libccd-gjk" || a == "libccd-mpr";
}
bool is_libccd_depth(std::string_view a) {
  return a == "libccd-gjk-epa" || a == "libccd-mpr-depth";
}

/// The GJK distance queries that take GjkDistanceOptions (gjk-nesterov takes its extension).
bool uses_distance_options(std::string_view a) {
  return a == "gjk-johnson" || a == "gjk-johnson-backup" || a == "gjk-sv" || a == "gjk-voronoi" ||
         a == "gjk-polyak";
}

std::vector<double> numbers(std::string_view key, std::string_view text) {
  std::vector<double> out;
  std::istringstream in{std::string(text)};
  for (std::string word; in >> word;) {
    double x = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), x);
    if (ec != std::errc() || end != word.data() + word.size())
      throw std::invalid_argument("expected a number, got '" + std::string(text) + "'");
    out.push_back(x);
  }
  if (out.empty()) throw std::invalid_argument(std::string(key) + ": no value");
  return out;
}

double number(std::string_view key, std::string_view text) {
  const auto v = numbers(key, text);
  if (v.size() != 1)
    throw std::invalid_argument("expected one number, got '" + std::string(text) + "'");
  if (!std::isfinite(v[0])) throw std::invalid_argument("must be finite, got " + std::string(text));
  return v[0];
}

double non_negative(std::string_view key, std::string_view text) {
  const double v = number(key, text);
  if (!(v >= 0)) throw std::invalid_argument("must be >= 0, got " + round_trip(v));
  return v;
}

int iterations(std::string_view key, std::string_view text) {
  const double v = number(key, text);
  if (!(v >= 1 && v <= std::numeric_limits<int>::max()) || v != std::floor(v))
    throw std::invalid_argument("must be an integer >= 1, got " + std::string(text));
  return static_cast<int>(v);
}

Vec3 direction(std::string_view key, std::string_view text) {
  const auto v = numbers(key, text);
  if (v.size() != 3)
    throw std::invalid_argument("expected [x, y, z], got '" + std::string(text) + "'");
  const Vec3 d(v[0], v[1], v[2]);
  if (!d.allFinite() || d.isZero(0)) throw std::invalid_argument("must be finite and non-zero");
  return d;
}

bool boolean(std::string_view text) {
  if (text == "true") return true;
  if (text == "false") return false;
  throw std::invalid_argument("expected true or false, got '" + std::string(text) + "'");
}

ScalarPrecision precision(std::string_view text) {
  const auto p = precision_from_string(text);
  if (!p)
    throw std::invalid_argument("unknown precision '" + std::string(text) +
                                "'; valid: float, double, long double");
  return *p;
}

std::string text_of(const Vec3& d) {
  return round_trip(d.x()) + " " + round_trip(d.y()) + " " + round_trip(d.z());
}

/// Sets a key of GjkDistanceOptions; false if the key is not one of them.
bool set_distance_option(GjkDistanceOptions& o, std::string_view key, std::string_view text) {
  if (key == "max_iterations")
    o.max_iterations = iterations(key, text);
  else if (key == "relative_gap")
    o.relative_gap = non_negative(key, text);
  else if (key == "absolute_gap_squared")
    o.absolute_gap_squared = non_negative(key, text);
  else if (key == "duality_gap_tolerance")
    o.duality_gap_tolerance = non_negative(key, text);
  else if (key == "relative_contact")
    o.relative_contact = non_negative(key, text);
  else if (key == "initial_direction")
    o.initial_direction = direction(key, text);
  else if (key == "recenter")
    o.recenter = boolean(text);
  else if (key == "start") {
    const auto start = distance_start_from_string(text);
    if (!start)
      throw std::invalid_argument("unknown start '" + std::string(text) +
                                  "'; valid: fixed_direction, centre_direction");
    o.start = *start;
  } else if (key == "convergence") {
    const auto c = convergence_from_string(text);
    if (!c)
      throw std::invalid_argument("unknown criterion '" + std::string(text) +
                                  "'; valid: relative, absolute, duality_gap");
    o.convergence = *c;
  } else {
    return false;
  }
  return true;
}

std::vector<std::pair<std::string, std::string>> describe_distance(const GjkDistanceOptions& d) {
  return {{"max_iterations", std::to_string(d.max_iterations)},
          {"convergence", std::string(to_string(d.convergence))},
          {"relative_gap", round_trip(d.relative_gap)},
          {"absolute_gap_squared", round_trip(d.absolute_gap_squared)},
          {"duality_gap_tolerance", round_trip(d.duality_gap_tolerance)},
          {"relative_contact", round_trip(d.relative_contact)},
          {"start", std::string(to_string(d.start))},
          {"initial_direction", text_of(d.initial_direction)},
          {"recenter", d.recenter ? "true" : "false"}};
}

}  // namespace

std::string round_trip(double x) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : std::to_string(x);
}

std::vector<std::string_view> option_keys(std::string_view algorithm) {
  static const std::vector<std::string_view> distance = {"max_iterations",
                                                         "convergence",
                                                         "relative_gap",
                                                         "absolute_gap_squared",
                                                         "duality_gap_tolerance",
                                                         "relative_contact",
                                                         "start",
                                                         "initial_direction",
                                                         "recenter",
                                                         "precision"};
  if (algorithm == "gjk-bool")
    return {"max_iterations", "start", "initial_direction", "recenter", "precision"};
  if (uses_distance_options(algorithm)) return distance;
  if (algorithm == "gjk-nesterov") {
    auto keys = distance;
    keys.push_back("normalize_direction");
    return keys;
  }
  if (is_libccd(algorithm)) return {"max_iterations", "mpr_tolerance"};
  if (is_libccd_depth(algorithm))
    return {"max_iterations", "max_depth_iterations", "mpr_tolerance", "epa_tolerance"};
  if (algorithm == "epa")
    return {"max_iterations",     "max_faces", "epa_relative_gap", "relative_noise",
            "gjk_max_iterations", "gjk_start", "recenter",         "precision"};
  if (algorithm == "sat") return {"early_exit"};
#ifdef GJKLAB_HAVE_FCL
  if (algorithm == "fcl-libccd" || algorithm == "fcl-indep")
    return {"max_iterations", "epa_max_iterations", "epa_max_faces", "epa_max_vertices"};
#endif
  return {};
}

void set_option(AlgorithmSpec& spec, std::string_view key, std::string_view text) {
  const auto keys = option_keys(spec.name);
  if (std::find(keys.begin(), keys.end(), key) == keys.end())
    throw std::invalid_argument("option '" + std::string(key) + "' does not apply to " + spec.name);
  AlgorithmOptions& o = spec.options;
  const std::string& n = spec.name;
  if (key == "precision") {  // every GJK query takes it (option_keys decides which)
    o.precision = precision(text);
    return;
  }
  if (n == "gjk-bool") {
    if (key == "max_iterations") {
      o.gjk_boolean.max_iterations = iterations(key, text);
    } else if (key == "recenter") {
      o.gjk_boolean.recenter = boolean(text);
    } else if (key == "start") {
      const auto start = boolean_start_from_string(text);
      if (!start)
        throw std::invalid_argument("unknown start '" + std::string(text) +
                                    "'; valid: fixed_direction, centre_direction, centre_point");
      o.gjk_boolean.start = *start;
    } else {
      o.gjk_boolean.initial_direction = direction(key, text);
    }
  } else if (uses_distance_options(n)) {
    set_distance_option(o.gjk_distance, key, text);
  } else if (n == "gjk-nesterov") {
    if (key == "normalize_direction")
      o.gjk_nesterov.normalize_direction = boolean(text);
    else
      set_distance_option(o.gjk_nesterov, key, text);
  } else if (is_libccd(n) || is_libccd_depth(n)) {
    if (key == "max_iterations") {
      o.libccd.max_iterations = iterations(key, text);
    } else if (key == "max_depth_iterations") {
      o.libccd.max_depth_iterations = iterations(key, text);
    } else {
      const double v = number(key, text);
      if (!(v > 0)) throw std::invalid_argument("must be > 0, got " + round_trip(v));
      (key == "mpr_tolerance" ? o.libccd.mpr_tolerance : o.libccd.epa_tolerance) = v;
    }
  } else if (n == "sat") {
    o.sat.early_exit = boolean(text);
#ifdef GJKLAB_HAVE_FCL
  } else if (n == "fcl-libccd" || n == "fcl-indep") {
    const int v = iterations(key, text);
    if (key == "max_iterations")
      o.fcl.max_iterations = v;
    else if (key == "epa_max_iterations")
      o.fcl.epa_max_iterations = v;
    else if (key == "epa_max_faces")
      o.fcl.epa_max_faces = v;
    else
      o.fcl.epa_max_vertices = v;
#endif
  } else if (n == "epa") {
    if (key == "max_iterations")
      o.epa.max_iterations = iterations(key, text);
    else if (key == "max_faces") {
      o.epa.max_faces = iterations(key, text);
      // EPA's own bound (epa.hpp), checked here so that the error names the file and line.
      if (o.epa.max_faces < 4 || o.epa.max_faces > (1 << 26))
        throw std::invalid_argument("must be in [4, 2^26], got " + std::string(text));
    } else if (key == "gjk_max_iterations")
      o.gjk_distance.max_iterations = iterations(key, text);
    else if (key == "gjk_start")
      set_distance_option(o.gjk_distance, "start", text);
    else if (key == "recenter")
      set_distance_option(o.gjk_distance, "recenter", text);
    else if (key == "epa_relative_gap")
      o.epa.relative_gap = non_negative(key, text);
    else
      o.epa.relative_noise = non_negative(key, text);
  }
}

std::vector<std::pair<std::string, std::string>> describe_options(const AlgorithmSpec& spec) {
  const AlgorithmOptions& o = spec.options;
  const std::string& n = spec.name;
  const std::pair<std::string, std::string> precision{"precision",
                                                      std::string(to_string(o.precision))};
  if (n == "gjk-bool")
    return {{"max_iterations", std::to_string(o.gjk_boolean.max_iterations)},
            {"start", std::string(to_string(o.gjk_boolean.start))},
            {"initial_direction", text_of(o.gjk_boolean.initial_direction)},
            {"recenter", o.gjk_boolean.recenter ? "true" : "false"},
            precision};
  if (uses_distance_options(n)) {
    auto described = describe_distance(o.gjk_distance);
    described.push_back(precision);
    return described;
  }
  if (n == "gjk-nesterov") {
    auto described = describe_distance(o.gjk_nesterov);
    described.emplace_back("normalize_direction",
                           o.gjk_nesterov.normalize_direction ? "true" : "false");
    described.push_back(precision);
    return described;
  }
  if (is_libccd(n))
    return {{"max_iterations", std::to_string(o.libccd.max_iterations)},
            {"mpr_tolerance", round_trip(o.libccd.mpr_tolerance)}};
  if (is_libccd_depth(n))
    return {{"max_iterations", std::to_string(o.libccd.max_iterations)},
            {"max_depth_iterations", std::to_string(o.libccd.max_depth_iterations)},
            {"mpr_tolerance", round_trip(o.libccd.mpr_tolerance)},
            {"epa_tolerance", round_trip(o.libccd.epa_tolerance)}};
  if (n == "epa")
    return {{"max_iterations", std::to_string(o.epa.max_iterations)},
            {"max_faces", std::to_string(o.epa.max_faces)},
            {"epa_relative_gap", round_trip(o.epa.relative_gap)},
            {"relative_noise", round_trip(o.epa.relative_noise)},
            {"gjk_max_iterations", std::to_string(o.gjk_distance.max_iterations)},
            {"gjk_start", std::string(to_string(o.gjk_distance.start))},
            {"recenter", o.gjk_distance.recenter ? "true" : "false"},
            precision};
  if (n == "sat") return {{"early_exit", o.sat.early_exit ? "true" : "false"}};
#ifdef GJKLAB_HAVE_FCL
  if (n == "fcl-libccd" || n == "fcl-indep")
    return {{"max_iterations", std::to_string(o.fcl.max_iterations)},
            {"epa_max_iterations", std::to_string(o.fcl.epa_max_iterations)},
            {"epa_max_faces", std::to_string(o.fcl.epa_max_faces)},
            {"epa_max_vertices", std::to_string(o.fcl.epa_max_vertices)}};
#endif
  if (n == "exact") return {{"depth", o.oracle.depth ? "true" : "false"}};
  return {};
}

AlgorithmSpec spec_from_description(const std::string& name,
                                    const std::vector<std::pair<std::string, std::string>>& text) {
  AlgorithmSpec spec;
  spec.name = name;
  spec.label = name;
  // Archives written before the GJK queries had a start option ran the fixed first direction.
  auto described = [&](const char* key) {
    return std::any_of(text.begin(), text.end(), [&](const auto& kv) { return kv.first == key; });
  };
  if (!described("start")) {
    spec.options.gjk_boolean.start = GjkBooleanStart::fixed_direction;
    spec.options.gjk_distance.start = GjkDistanceStart::fixed_direction;
    spec.options.gjk_nesterov.start = GjkDistanceStart::fixed_direction;
  }
  if (name == "epa" && !described("gjk_start"))
    spec.options.gjk_distance.start = GjkDistanceStart::fixed_direction;
  // Archives written before the exact re-centring ran the queries on the coordinates as given.
  if (!described("recenter")) {
    spec.options.gjk_boolean.recenter = false;
    spec.options.gjk_distance.recenter = false;
    spec.options.gjk_nesterov.recenter = false;
  }
  for (const auto& [key, value] : text) {
    if (key == "algorithm") continue;  // the registry name, archived with the options
    try {
      set_option(spec, key, value);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("option '" + key + "' of " + name + ": " + e.what());
    }
  }
  return spec;
}

}  // namespace gjklab::experiment
