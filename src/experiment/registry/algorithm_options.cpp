#include "gjklab/experiment/registry/algorithm_options.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <variant>

#include "gjklab/experiment/registry/algorithms.hpp"

namespace gjklab::experiment {

namespace {

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

std::string text_of(const Vec3& d) {
  return round_trip(d.x()) + " " + round_trip(d.y()) + " " + round_trip(d.z());
}

// ---- reading and writing one value by its type ----

/// What an error calls a value of an enum option, and the enum's values in order.
template <class E>
struct Choice;
template <>
struct Choice<ScalarPrecision> {
  static constexpr std::string_view noun = "precision";
  static constexpr std::array values = {
      ScalarPrecision::single_float, ScalarPrecision::double_float, ScalarPrecision::long_double};
};
template <>
struct Choice<GjkBooleanStart> {
  static constexpr std::string_view noun = "start";
  static constexpr std::array values = {GjkBooleanStart::fixed_direction,
                                        GjkBooleanStart::centre_direction,
                                        GjkBooleanStart::centre_point};
};
template <>
struct Choice<GjkDistanceStart> {
  static constexpr std::string_view noun = "start";
  static constexpr std::array values = {GjkDistanceStart::fixed_direction,
                                        GjkDistanceStart::centre_direction};
};
template <>
struct Choice<GjkConvergence> {
  static constexpr std::string_view noun = "criterion";
  static constexpr std::array values = {GjkConvergence::relative, GjkConvergence::absolute,
                                        GjkConvergence::duality_gap};
};

int parse(std::string_view key, std::string_view text, const OptionRange& range, int*) {
  const int v = iterations(key, text);
  if (v < range.min || v > range.max)
    throw std::invalid_argument("must be in " + std::string(range.text) + ", got " +
                                std::string(text));
  return v;
}

double parse(std::string_view key, std::string_view text, const OptionRange& range, double*) {
  const double v = number(key, text);
  if (range.min_exclusive && !(v > range.min))
    throw std::invalid_argument("must be > " + round_trip(range.min) + ", got " + round_trip(v));
  if (!(v >= range.min))
    throw std::invalid_argument("must be >= " + round_trip(range.min) + ", got " + round_trip(v));
  return v;
}

bool parse(std::string_view, std::string_view text, const OptionRange&, bool*) {
  return boolean(text);
}

Vec3 parse(std::string_view key, std::string_view text, const OptionRange&, Vec3*) {
  return direction(key, text);
}

template <class E>
E parse(std::string_view, std::string_view text, const OptionRange&, E*) {
  std::string valid;
  for (E value : Choice<E>::values) {
    if (to_string(value) == text) return value;
    valid += (valid.empty() ? "" : ", ") + std::string(to_string(value));
  }
  throw std::invalid_argument("unknown " + std::string(Choice<E>::noun) + " '" + std::string(text) +
                              "'; valid: " + valid);
}

std::string text(int v) {
  return std::to_string(v);
}
std::string text(double v) {
  return round_trip(v);
}
std::string text(bool v) {
  return v ? "true" : "false";
}
std::string text(const Vec3& v) {
  return text_of(v);
}
template <class E>
requires std::is_enum_v<E> std::string text(E v) {
  return std::string(to_string(v));
}

/// Sets the row's member from its text (validated by the member's type and the row's range).
void apply(const OptionRow& row, AlgorithmOptions& o, std::string_view value) {
  std::visit(
      [&](auto access) {
        auto& member = access(o);
        member = parse(row.key, value, row.range, &member);
      },
      row.member);
}

/// The row's member as text.
std::string describe(const OptionRow& row, const AlgorithmOptions& o) {
  AlgorithmOptions copy = o;  // the accessors take a mutable struct; a copy keeps `o` const
  return std::visit([&](auto access) { return text(access(copy)); }, row.member);
}

// ---- what a row accepts, in words (the parsers' rules above, restated for listings) ----

OptionValues values_of(const OptionRange& range, int*) {
  const std::string bounds = range.text.empty() ? ">= 1" : "in " + std::string(range.text);
  return {"integer", {}, "an integer " + bounds};
}

OptionValues values_of(const OptionRange& range, double*) {
  if (range.min_exclusive) return {"number", {}, "a number > " + round_trip(range.min)};
  if (std::isfinite(range.min)) return {"number", {}, "a number >= " + round_trip(range.min)};
  return {"number", {}, "a finite number"};
}

OptionValues values_of(const OptionRange&, bool*) {
  return {"boolean", {}, "true or false"};
}

OptionValues values_of(const OptionRange&, Vec3*) {
  return {"direction", {}, "three finite numbers x y z, not all zero"};
}

template <class E>
requires std::is_enum_v<E> OptionValues values_of(const OptionRange&, E*) {
  OptionValues v{"choice", {}, "one of"};
  for (E value : Choice<E>::values) {
    v.accepts += v.choices.empty() ? " " : ", ";
    v.accepts += to_string(value);
    v.choices.push_back(to_string(value));
  }
  return v;
}

// ---- the schemas ----

// The meanings of keys that several algorithms share, said once.
constexpr std::string_view kMaxIterationsMeaning =
    "bound on main-loop iterations; reaching it is reported as step_limit, not as an answer";
constexpr std::string_view kInitialDirectionMeaning =
    "first search direction (any length) of start = fixed_direction, and of a centre start "
    "that falls back to it";
constexpr std::string_view kRecenterMeaning =
    "translate a pair far from the origin exactly towards it before the query, so that "
    "support values are compared at the pair's scale; false: the coordinates as given";
constexpr std::string_view kMprToleranceMeaning =
    "libccd's mpr_tolerance (absolute, length units): MPR answers no intersection once a "
    "support point moves the portal outward by no more than this";

/// The keys of GjkDistanceOptions, on the member `Options` returns (gjk_distance, or
/// gjk_nesterov, which extends it).
template <auto Options>
constexpr std::array<OptionRow, 9> distance_rows() {
  return {{
      {"max_iterations", [](AlgorithmOptions& o) -> int& { return Options(o).max_iterations; },
       kMaxIterationsMeaning},
      {"convergence", [](AlgorithmOptions& o) -> GjkConvergence& { return Options(o).convergence; },
       "the stopping test: relative (relative_gap), absolute (absolute_gap_squared) or "
       "duality_gap (duality_gap_tolerance); only its tolerances are read"},
      {"relative_gap", [](AlgorithmOptions& o) -> double& { return Options(o).relative_gap; },
       "relative, on squared lengths (dimensionless): converged when the gap |v|^2 - v.w is at "
       "most relative_gap |v|^2 (van den Bergen's test)",
       kNonNegative},
      {"absolute_gap_squared",
       [](AlgorithmOptions& o) -> double& { return Options(o).absolute_gap_squared; },
       "absolute, squared length units: converged when |v|^2 - v.w is at most this "
       "(convergence = absolute; with relative, a floor beside the relative test; 0: none)",
       kNonNegative},
      {"duality_gap_tolerance",
       [](AlgorithmOptions& o) -> double& { return Options(o).duality_gap_tolerance; },
       "absolute, squared length units: converged when the Frank-Wolfe duality gap "
       "2(|v|^2 - v.w) is at most this (convergence = duality_gap)",
       kNonNegative},
      {"relative_contact",
       [](AlgorithmOptions& o) -> double& { return Options(o).relative_contact; },
       "relative to the simplex size, not squared: contact when |v| is at most this times the "
       "largest simplex vertex norm",
       kNonNegative},
      {"start", [](AlgorithmOptions& o) -> GjkDistanceStart& { return Options(o).start; },
       "first support point of a cold start: in initial_direction, or facing the origin from "
       "the difference of the shapes' vertex means"},
      {"initial_direction",
       [](AlgorithmOptions& o) -> Vec3& { return Options(o).initial_direction; },
       kInitialDirectionMeaning},
      {"recenter", [](AlgorithmOptions& o) -> bool& { return Options(o).recenter; },
       kRecenterMeaning},
  }};
}

GjkDistanceOptions& distance_options(AlgorithmOptions& o) {
  return o.gjk_distance;
}
GjkNesterovOptions& nesterov_options(AlgorithmOptions& o) {
  return o.gjk_nesterov;
}

constexpr OptionRow kPrecisionRow{
    "precision", [](AlgorithmOptions& o) -> ScalarPrecision& { return o.precision; },
    "floating-point type the query computes in (inputs rounded to it; answers in double)"};

/// Rows followed by more rows, in one array.
template <std::size_t N, std::size_t M>
constexpr std::array<OptionRow, N + M> join(const std::array<OptionRow, N>& a,
                                            const std::array<OptionRow, M>& b) {
  std::array<OptionRow, N + M> out{};
  for (std::size_t i = 0; i < N; ++i)
    out[i] = a[i];
  for (std::size_t i = 0; i < M; ++i)
    out[N + i] = b[i];
  return out;
}

constexpr auto kGjkBooleanRows = std::to_array<OptionRow>({
    {"max_iterations", [](AlgorithmOptions& o) -> int& { return o.gjk_boolean.max_iterations; },
     kMaxIterationsMeaning},
    {"start", [](AlgorithmOptions& o) -> GjkBooleanStart& { return o.gjk_boolean.start; },
     "first simplex point and search direction: a support point in initial_direction, one "
     "facing the origin from the difference of the vertex means, or that difference itself"},
    {"initial_direction",
     [](AlgorithmOptions& o) -> Vec3& { return o.gjk_boolean.initial_direction; },
     kInitialDirectionMeaning},
    {"recenter", [](AlgorithmOptions& o) -> bool& { return o.gjk_boolean.recenter; },
     kRecenterMeaning},
    kPrecisionRow,
});

constexpr auto kGjkDistanceRows =
    join(distance_rows<distance_options>(), std::array<OptionRow, 1>{kPrecisionRow});

// warm_start last, so that the variants' earlier rows keep their order in archived descriptions.
constexpr auto kGjkVariantRows =
    join(kGjkDistanceRows,
         std::to_array<OptionRow>({
             {"warm_start", [](AlgorithmOptions& o) -> bool& { return o.warm_start; },
              "start from the case's recorded simplex (a scene's previous frame, family "
              "stream); cases without one start cold"},
         }));

constexpr auto kGjkNesterovRows =
    join(distance_rows<nesterov_options>(),
         std::to_array<OptionRow>({
             {"normalize_direction",
              [](AlgorithmOptions& o) -> bool& { return o.gjk_nesterov.normalize_direction; },
              "false: the paper's momentum schedule; true: coal's normalised heuristic for "
              "shapes that are not strictly convex"},
             kPrecisionRow,
         }));

constexpr auto kEpaRows = std::to_array<OptionRow>({
    {"max_iterations", [](AlgorithmOptions& o) -> int& { return o.epa.max_iterations; },
     "bound on EPA's expansion steps (one support evaluation each); reaching it is reported as "
     "step_limit"},
    // EPA's own bound (epa.hpp), checked here so that the error names the file and line.
    {"max_faces",
     [](AlgorithmOptions& o) -> int& { return o.epa.max_faces; },
     "capacity of the face buffer; an expansion needing more stops the query (out of faces)",
     {.min = 4, .max = 1 << 26, .text = "[4, 2^26]"}},
    {"epa_relative_gap", [](AlgorithmOptions& o) -> double& { return o.epa.relative_gap; },
     "relative to the depth, not squared: converged when the closest face's upper and lower "
     "bounds differ by at most this times the lower bound",
     kNonNegative},
    {"relative_noise", [](AlgorithmOptions& o) -> double& { return o.epa.relative_noise; },
     "relative to the polytope's radius, not squared: lengths below this are rounding noise "
     "(the gap test's floor, the flatness threshold)",
     kNonNegative},
    // Its GJK phase runs gjk-johnson with gjk_distance.
    {"gjk_max_iterations",
     [](AlgorithmOptions& o) -> int& { return o.gjk_distance.max_iterations; },
     "bound on the iterations of the GJK phase; reaching it is reported as step_limit"},
    {"gjk_start", [](AlgorithmOptions& o) -> GjkDistanceStart& { return o.gjk_distance.start; },
     "first support point of the GJK phase's cold start: in initial_direction, or facing "
     "the origin from the difference of the shapes' vertex means"},
    {"recenter", [](AlgorithmOptions& o) -> bool& { return o.gjk_distance.recenter; },
     kRecenterMeaning},
    kPrecisionRow,
});

constexpr auto kLibccdRows = std::to_array<OptionRow>({
    {"max_iterations", [](AlgorithmOptions& o) -> int& { return o.libccd.max_iterations; },
     "libccd's iteration budget (its own default is unbounded); the adapter enforces it for "
     "MPR too"},
    {"mpr_tolerance", [](AlgorithmOptions& o) -> double& { return o.libccd.mpr_tolerance; },
     kMprToleranceMeaning, kPositive},
});

constexpr auto kLibccdDepthRows = std::to_array<OptionRow>({
    {"max_iterations", [](AlgorithmOptions& o) -> int& { return o.libccd.max_iterations; },
     "libccd's iteration budget of the boolean phase (its own default is unbounded)"},
    {"max_depth_iterations",
     [](AlgorithmOptions& o) -> int& { return o.libccd.max_depth_iterations; },
     "support evaluations allowed to the depth phase beyond the boolean phase's budget"},
    {"mpr_tolerance", [](AlgorithmOptions& o) -> double& { return o.libccd.mpr_tolerance; },
     kMprToleranceMeaning, kPositive},
    {"epa_tolerance", [](AlgorithmOptions& o) -> double& { return o.libccd.epa_tolerance; },
     "libccd's epa_tolerance (absolute, squared length units): EPA stops when a support "
     "point gains less than this over the polytope",
     kPositive},
});

constexpr auto kSatRows = std::to_array<OptionRow>({
    {"early_exit", [](AlgorithmOptions& o) -> bool& { return o.sat.early_exit; },
     "stop at the first separating axis; false: test every axis and report the largest gap "
     "(the best SAT lower bound of the distance)"},
});

constexpr auto kFclRows = std::to_array<OptionRow>({
    {"max_iterations", [](AlgorithmOptions& o) -> int& { return o.fcl.max_iterations; },
     "GJK iteration bound of both FCL solvers"},
    {"epa_max_iterations", [](AlgorithmOptions& o) -> int& { return o.fcl.epa_max_iterations; },
     "fcl-indep's EPA: bound on iterations"},
    {"epa_max_faces", [](AlgorithmOptions& o) -> int& { return o.fcl.epa_max_faces; },
     "fcl-indep's EPA: bound on the faces of its polytope"},
    {"epa_max_vertices", [](AlgorithmOptions& o) -> int& { return o.fcl.epa_max_vertices; },
     "fcl-indep's EPA: bound on the vertices of its polytope"},
});

// The oracle's depth flag comes from the experiment's [oracle] table; the archive records it
// with the `exact` algorithm so that replay asks for the same answer.
constexpr auto kExactRows = std::to_array<OptionRow>({
    {"depth",
     [](AlgorithmOptions& o) -> bool& { return o.oracle.depth; },
     "also compute the exact penetration depth of intersecting pairs (set by the experiment's "
     "[oracle] table)",
     {},
     OptionUse::recorded},
});

/// The schema of a registered algorithm; empty for an unknown name.
OptionSchema schema_of(std::string_view algorithm) {
  const AlgorithmInfo* info = find_algorithm(algorithm);
  return info ? info->options : OptionSchema{};
}

const OptionRow* find_row(OptionSchema schema, std::string_view key) {
  for (const OptionRow& row : schema)
    if (row.key == key) return &row;
  return nullptr;
}

}  // namespace

OptionSchema gjk_boolean_option_schema() {
  return kGjkBooleanRows;
}
OptionSchema gjk_distance_option_schema() {
  return kGjkDistanceRows;
}
OptionSchema gjk_variant_option_schema() {
  return kGjkVariantRows;
}
OptionSchema gjk_nesterov_option_schema() {
  return kGjkNesterovRows;
}
OptionSchema epa_option_schema() {
  return kEpaRows;
}
OptionSchema libccd_option_schema() {
  return kLibccdRows;
}
OptionSchema libccd_depth_option_schema() {
  return kLibccdDepthRows;
}
OptionSchema sat_option_schema() {
  return kSatRows;
}
OptionSchema fcl_option_schema() {
  return kFclRows;
}
OptionSchema exact_option_schema() {
  return kExactRows;
}

std::string round_trip(double x) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : std::to_string(x);
}

OptionValues option_values(const OptionRow& row) {
  return std::visit(
      [&](auto access) {
        using Member = std::remove_reference_t<decltype(access(std::declval<AlgorithmOptions&>()))>;
        return values_of(row.range, static_cast<Member*>(nullptr));
      },
      row.member);
}

std::vector<std::string_view> option_keys(std::string_view algorithm) {
  std::vector<std::string_view> keys;
  for (const OptionRow& row : schema_of(algorithm))
    if (row.use == OptionUse::setting) keys.push_back(row.key);
  return keys;
}

void set_option(AlgorithmSpec& spec, std::string_view key, std::string_view text) {
  const OptionRow* row = find_row(schema_of(spec.name), key);
  if (!row || row->use != OptionUse::setting)
    throw std::invalid_argument("option '" + std::string(key) + "' does not apply to " + spec.name);
  apply(*row, spec.options, text);
}

std::vector<std::pair<std::string, std::string>> describe_options(const AlgorithmSpec& spec) {
  std::vector<std::pair<std::string, std::string>> described;
  for (const OptionRow& row : schema_of(spec.name))
    described.emplace_back(std::string(row.key), describe(row, spec.options));
  return described;
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
      const OptionRow* row = find_row(schema_of(name), key);
      if (!row) throw std::invalid_argument("option '" + key + "' does not apply to " + name);
      apply(*row, spec.options, value);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("option '" + key + "' of " + name + ": " + e.what());
    }
  }
  return spec;
}

}  // namespace gjklab::experiment
