#include "gjklab/experiment/hunt/hunt.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/experiment/meshes/mesh_cases.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/registry/certified.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/run/judging.hpp"
#include "gjklab/geometry/enum_names.hpp"
#include "gjklab/geometry/polytope.hpp"

namespace gjklab::experiment {

namespace {

constexpr auto kObjectiveNames = std::to_array<EnumName<HuntObjective>>({
    {HuntObjective::wrong_boolean, "wrong_boolean"},
    {HuntObjective::error, "error"},
    {HuntObjective::iterations, "iterations"},
    {HuntObjective::not_converged, "not_converged"},
    {HuntObjective::false_convergence, "false_convergence"},
});
static_assert(in_value_order(kObjectiveNames) &&
              ends_at(kObjectiveNames, HuntObjective::false_convergence));

// What each objective counts as a failure, in the words tools print beside a study's table.
constexpr auto kObjectiveMeanings = std::to_array<EnumName<HuntObjective>>({
    {HuntObjective::wrong_boolean,
     "a boolean that differs from the exact one outside the touching band"},
    {HuntObjective::error,
     "the relative distance error, scored; a failure above the touching band"},
    {HuntObjective::iterations, "the iterations used, scored; a failure at the step limit"},
    {HuntObjective::not_converged, "any termination other than converged"},
    {HuntObjective::false_convergence,
     "a `converged` answer whose proven bracket misses the exact distance, or, without a "
     "bracket, a wrong `converged` answer"},
});
static_assert(in_value_order(kObjectiveMeanings) &&
              ends_at(kObjectiveMeanings, HuntObjective::false_convergence));

/// A pair as the search moves it.
struct Pair {
  std::vector<Vec3> a, b;
  SweptRadii radii;
  /// A non-convex pair's triangles (a and b are the meshes' vertices); empty for polytopes.
  std::vector<MeshFace> faces_a, faces_b;
};

/// A restart's base case: the pair, its size, and its placement along the axis u (B moved so
/// that its extent along u starts gap·size after A's; gap < 0 overlaps; u = 0 for random
/// placement).
struct BaseCase {
  Pair pair;
  double size = 0;
  Vec3 axis = Vec3::Zero();
  double gap = 0;
};

/// A judged query: whether it fails the objective, and the score the search maximises.
struct Judged {
  bool valid = false;  ///< false: B left the range of valid clouds (no query was made)
  bool failure = false;
  double score = -std::numeric_limits<double>::infinity();
  double relative_error = std::numeric_limits<double>::quiet_NaN();
  double objective_value = 0;
  Outcome outcome;
  exact::OracleAnswer exact;
};

/// Scores above every non-failure (scores of non-failures stay below 1e6).
constexpr double kFailureScore = 1e9;

/// Whether a converged answer is false: its bracket misses the exact distance (nearest double,
/// so each bound is widened by one unit in the last place), or, without a bracket, its
/// boolean or its distance (relative error above the band) is wrong.
bool falsely_converged(const Outcome& o, const AlgorithmRecord& r, double exact_distance,
                       double band) {
  if (o.lower_bound && o.upper_bound) {
    const double below = std::nextafter(*o.lower_bound, -1.0);
    const double above = std::nextafter(*o.upper_bound, std::numeric_limits<double>::infinity());
    return exact_distance < below || exact_distance > above;
  }
  return !r.boolean_correct || (!std::isnan(r.rel_error) && r.rel_error > band);
}

/// A query's answer on a pair, with the exact answer judging it.
struct Answered {
  Outcome outcome;
  exact::OracleAnswer exact;
  ExactRecord record;
  double size = 0;
};

/// The experiment's algorithm the hunt names: its label (as a nonconvex experiment's lists
/// name@decomposition=NAME) or its registry name, first match; null when it lists none.
const AlgorithmSpec* listed_spec(const ExperimentConfig& config, const std::string& name) {
  for (const AlgorithmSpec& spec : config.algorithms)
    if (spec.label == name) return &spec;
  for (const AlgorithmSpec& spec : config.algorithms)
    if (spec.name == name) return &spec;
  return nullptr;
}

/// The algorithm, its options and the objective, applied to a pair. On the non-convex pairs of
/// nonconvex families the algorithm is the experiment's (with its decomposition, or a mesh
/// peer) and the truth is the solids' (exact::mesh_truth).
class Judge {
 public:
  Judge(const ExperimentConfig& config, const HuntOptions& options)
      : config_(config), objective_(options.objective) {
    if (config.has_nonconvex_families()) {
      spec_ = listed_spec(config, options.algorithm);
      if (!spec_) {
        std::string labels;
        for (const AlgorithmSpec& s : config.algorithms)
          labels += (labels.empty() ? "" : ", ") + s.label;
        throw std::invalid_argument("the experiment lists no algorithm '" + options.algorithm +
                                    "' (its non-convex pairs are queried as it lists them, with "
                                    "their decompositions); valid: " +
                                    labels);
      }
      return;
    }
    algorithm_ = find_algorithm(options.algorithm);
    if (!algorithm_)
      throw std::invalid_argument("unknown algorithm '" + options.algorithm +
                                  "'; valid names: " + algorithm_names());
    if (algorithm_->kind == AnswerKind::exact)
      throw std::invalid_argument("algorithm '" + options.algorithm + "' is exact: it cannot fail");
    for (const AlgorithmSpec& spec : config.algorithms)
      if (spec.name == options.algorithm) {
        options_ = spec.options;  // the experiment's options for it, when it lists it
        break;
      }
  }

  bool handles_pair(const Pair& p) const { return spec_ || handles(*algorithm_, p.radii); }

  /// Judges the pair; `contact_target` (log10 of distance or depth over size) is where the
  /// search of a yes/no objective is drawn while it has found no failure.
  Judged operator()(const Pair& p, double contact_target) const {
    Judged j;
    const std::optional<Answered> a = spec_ ? answer_meshes(p) : answer_polytopes(p);
    if (!a) return j;
    j.valid = true;
    j.outcome = a->outcome;
    j.exact = a->exact;
    AlgorithmRecord r = algorithm_record(j.outcome);
    judge(r, j.outcome, a->record, a->size);
    j.relative_error = r.rel_error;
    score(j, r, -std::abs(contact_scale(j.exact, a->size) - contact_target));
    return j;
  }

 private:
  std::optional<Answered> answer_polytopes(const Pair& p) const {
    if (!describe_invalid_cloud(p.a).empty() || !describe_invalid_cloud(p.b).empty())
      return std::nullopt;
    const Polytope a(p.a), b(p.b);
    Answered out;
    out.size = pair_size(p.a, p.b, p.radii.a, p.radii.b);
    if (!(out.size > 0) || !std::isfinite(out.size)) return std::nullopt;
    out.outcome = run_algorithm(*algorithm_, a, b, p.radii, options_);
    out.exact = solve_certified(a, b, p.radii, config_.oracle_options(true)).answer;
    out.record = exact_record(out.exact, config_.touching_band * out.size);
    return out;
  }

  /// A pose that no longer bounds solids (rounding made the surface cross itself) is invalid.
  std::optional<Answered> answer_meshes(const Pair& p) const {
    const TriangleMesh a{p.a, p.faces_a}, b{p.b, p.faces_b};
    Answered out;
    out.size = pair_size(p.a, p.b, 0, 0);
    if (!(out.size > 0) || !std::isfinite(out.size)) return std::nullopt;
    try {
      exact::validate_closed_mesh(a, "mesh A");
      exact::validate_closed_mesh(b, "mesh B");
    } catch (const std::runtime_error&) {
      return std::nullopt;
    }
    const MeshTruthRecords truth =
        mesh_truth_records(exact::mesh_truth(a, b), config_.touching_band * out.size);
    out.exact = truth.answer;
    out.record = truth.exact;
    out.outcome = run_mesh_algorithm(*spec_, a, b, "a hunted pose");
    return out;
  }

  /// The objective's value, failure and score of a judged query; `closeness` ranks the
  /// non-failures of yes/no objectives by nearness to the contact target.
  void score(Judged& j, const AlgorithmRecord& r, double closeness) const {
    switch (objective_) {
      case HuntObjective::wrong_boolean:
        j.failure = !r.boolean_correct;
        j.objective_value = j.failure ? 1 : 0;
        j.score = j.failure ? kFailureScore : closeness;
        break;
      case HuntObjective::error:
        j.objective_value = std::isnan(r.rel_error) ? 0 : r.rel_error;
        j.failure = j.objective_value > config_.touching_band;
        j.score = j.objective_value > 0 ? std::log10(j.objective_value) : -400 + closeness;
        break;
      case HuntObjective::iterations:
        j.objective_value = j.outcome.iterations;
        j.failure = j.outcome.termination == Termination::step_limit;
        j.score = j.outcome.iterations + 1e-3 * closeness;
        break;
      case HuntObjective::not_converged:
        j.failure = j.outcome.termination != Termination::converged;
        j.objective_value = j.failure ? 1 : 0;
        j.score = j.failure ? kFailureScore : closeness;
        break;
      case HuntObjective::false_convergence:
        j.failure = j.outcome.termination == Termination::converged &&
                    falsely_converged(j.outcome, r, j.exact.distance, config_.touching_band);
        j.objective_value = j.failure ? 1 : 0;
        j.score = j.failure ? kFailureScore : closeness;
        break;
    }
  }

  /// log10 of the exact distance (separated) or depth (intersecting) over size; −400 for 0.
  static double contact_scale(const exact::OracleAnswer& e, double size) {
    const double measure = e.intersect ? e.depth.value_or(0.0) : e.distance;
    return measure > 0 ? std::log10(measure / size) : -400.0;
  }

  const ExperimentConfig& config_;
  HuntObjective objective_;
  const AlgorithmInfo* algorithm_ = nullptr;  ///< polytope pairs
  AlgorithmOptions options_;
  const AlgorithmSpec* spec_ = nullptr;  ///< non-convex pairs
};

/// The pose of B relative to its case: rotation vector (radians), translation (units of the
/// pair's size) and log scale, all about B's vertex mean, and the change of the placement gap
/// along the case's axis in decades (|gap| multiplied by 10^log_gap, its sign kept): near
/// contact is where things fail, and distances there span many decades.
struct Pose {
  Vec3 rotation = Vec3::Zero();
  Vec3 translation = Vec3::Zero();
  double log_scale = 0;
  double log_gap = 0;
};

Pair moved(const BaseCase& base_case, const Pose& pose) {
  const Pair& base = base_case.pair;
  const double size = base_case.size;
  Pair p = base;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& x : base.b)
    centre += x;
  centre /= static_cast<double>(base.b.size());
  const double angle = pose.rotation.norm();
  const Mat3 rotation = angle > 0
                            ? Eigen::AngleAxisd(angle, pose.rotation / angle).toRotationMatrix()
                            : Mat3::Identity();
  const double scale = std::exp(pose.log_scale);
  const double gap_change = base_case.gap * (std::pow(10.0, pose.log_gap) - 1);
  const Vec3 shift = pose.translation * size + gap_change * size * base_case.axis;
  for (Vec3& x : p.b)
    x = centre + scale * (rotation * (x - centre)) + shift;
  p.radii.b = base.radii.b * scale;
  return p;
}

/// A Gaussian step of the pose, with step size `sigma` (1 ≈ 0.05 rad, 0.02 size, 2 % scale,
/// half a decade of gap).
Pose step(const Pose& from, double sigma, std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Pose p = from;
  for (int i = 0; i < 3; ++i)
    p.rotation[i] += 0.05 * sigma * n(rng);
  for (int i = 0; i < 3; ++i)
    p.translation[i] += 0.02 * sigma * n(rng);
  p.log_scale += 0.02 * sigma * n(rng);
  p.log_gap += 0.5 * sigma * n(rng);
  return p;
}

/// The case's coordinates rounded to `digits` significant decimal digits.
std::vector<Vec3> rounded(const std::vector<Vec3>& cloud, int digits) {
  std::vector<Vec3> out = cloud;
  char buffer[64];
  for (Vec3& x : out)
    for (int i = 0; i < 3; ++i) {
      std::snprintf(buffer, sizeof buffer, "%.*g", digits, x[i]);
      x[i] = std::strtod(buffer, nullptr);
    }
  return out;
}

/// Shrinks a failing pair: vertices removed one at a time (last first), then every coordinate
/// rounded to the fewest significant digits (3 … 16) that still fail. Each try is a query,
/// at most `budget` of them; `queries` counts them.
Pair shrink(Pair p, const Judge& judge, double target, int budget, std::uint64_t& queries) {
  auto still_fails = [&](const Pair& candidate) {
    if (budget <= 0) return false;
    --budget;
    ++queries;
    const Judged j = judge(candidate, target);
    return j.valid && j.failure;
  };
  // A mesh's vertex cannot be removed without its faces: meshes are only rounded.
  for (std::vector<Vec3>* cloud : {&p.a, &p.b}) {
    if (!p.faces_a.empty()) break;
    for (std::size_t i = cloud->size(); i-- > 0 && cloud->size() > 1;) {
      Pair candidate = p;
      std::vector<Vec3>& c = cloud == &p.a ? candidate.a : candidate.b;
      c.erase(c.begin() + static_cast<std::ptrdiff_t>(i));
      if (still_fails(candidate)) p = std::move(candidate);
    }
  }
  for (int digits = 3; digits <= 16; ++digits) {
    Pair candidate = p;
    candidate.a = rounded(p.a, digits);
    candidate.b = rounded(p.b, digits);
    if (still_fails(candidate)) return candidate;
  }
  return p;
}

/// The restart's contact target: log10 of the distance or depth (over size) the search is drawn
/// to, log-uniform over the four decades above the touching band, where the tolerances of
/// double-precision queries decide (libccd's and FCL's wrong booleans on the hard
/// configurations sit at 1e-10 … 1e-8 of the size).
double draw_contact_target(const ExperimentConfig& config, std::mt19937_64& rng) {
  const double band = std::log10(std::max(config.touching_band, 1e-300));
  std::uniform_real_distribution<double> u(band, band + 4);
  return u(rng);
}

Pair pair_of(const GeneratedCase& g) {
  Pair p{g.a, g.b, {g.record.radius_a, g.record.radius_b}, {}, {}};
  if (g.mesh_a) p.faces_a = g.mesh_a->faces;
  if (g.mesh_b) p.faces_b = g.mesh_b->faces;
  return p;
}

BaseCase base_of(const GeneratedCase& g) {
  // A pair placed without a drawn gap (NaN: random placement, non-convex pairs) has none to
  // scale.
  const double gap = std::isnan(g.record.intended_gap) ? 0.0 : g.record.intended_gap;
  return {pair_of(g), g.record.size, g.direction, gap};
}

/// One restart: a (1+1) evolution strategy from the base case until a failure or the budget.
/// Returns the failing pair, if any, with its judged query.
std::optional<std::pair<Pair, Judged>> local_search(const BaseCase& base, const Judge& judge,
                                                    double target, int budget, std::mt19937_64& rng,
                                                    HuntReport& report) {
  // Start at the target's scale of contact where the case has a placement gap to scale.
  Pose best_pose;
  if (base.gap != 0 && !is_zero(base.axis))
    best_pose.log_gap = target - std::log10(std::abs(base.gap));
  double sigma = 1.0;
  double best_score = -std::numeric_limits<double>::infinity();
  for (int q = 0; q < budget; ++q) {
    const Pose pose = q == 0 ? best_pose : step(best_pose, sigma, rng);
    const Pair candidate = moved(base, pose);
    const Judged j = judge(candidate, target);
    if (!j.valid) {
      sigma *= 0.5;
      continue;
    }
    ++report.queries;
    if (!std::isnan(j.relative_error))
      report.worst_relative_error = std::max(report.worst_relative_error, j.relative_error);
    if (j.failure) return std::make_pair(candidate, j);
    // One-fifth rule: grow the step after a success, shrink it after a failure, so that about
    // one step in five succeeds.
    if (j.score >= best_score) {
      best_score = j.score;
      best_pose = pose;
      sigma *= 1.5;
    } else {
      sigma *= 0.9;
    }
    sigma = std::clamp(sigma, 1e-12, 20.0);
  }
  return std::nullopt;
}

/// The id of a found case: hunt-ALGORITHM-INDEX, with the rank before the index in a
/// distributed hunt (hunt-ALGORITHM-RANK.INDEX), so that the ranks' lines stay distinct.
std::string found_case_id(const HuntOptions& options, std::size_t index) {
  const std::string rank = options.ranks > 1 ? std::to_string(options.rank) + "." : "";
  return "hunt-" + options.algorithm + "-" + rank + std::to_string(index);
}

FoundCase found_case(const Pair& p, const Judged& j, std::uint64_t base_case, std::uint64_t query,
                     std::string id) {
  FoundCase f;
  f.points.id = std::move(id);
  f.points.a = p.a;
  f.points.b = p.b;
  f.points.radius_a = p.radii.a;
  f.points.radius_b = p.radii.b;
  if (!p.faces_a.empty()) {
    f.points.mesh_a = TriangleMesh{p.a, p.faces_a};
    f.points.mesh_b = TriangleMesh{p.b, p.faces_b};
  }
  f.objective_value = j.objective_value;
  f.base_case = base_case;
  f.query = query;
  f.exact = j.exact;
  f.answer_intersect = j.outcome.intersect;
  f.answer_distance = j.outcome.distance;
  f.answer_termination = j.outcome.termination;
  f.answer_iterations = j.outcome.iterations;
  return f;
}

/// The random baseline: `queries` judged cases of the experiment, from case id `first` in steps
/// of `step` (a distributed hunt's ranks share the ids 0, 1, 2, … that way).
std::uint64_t random_baseline_failures(const ExperimentConfig& config, const Judge& judge,
                                       std::uint64_t queries, std::uint64_t first,
                                       std::uint64_t step, std::uint64_t& made) {
  std::uint64_t failures = 0;
  for (std::uint64_t k = 0; made < queries && k < 4 * queries + 16; ++k) {
    const Pair p = pair_of(generate_case(config, first + k * step));
    if (!judge.handles_pair(p)) continue;
    const Judged j = judge(p, 0.0);
    if (!j.valid) continue;
    ++made;
    failures += j.failure;
  }
  return failures;
}

}  // namespace

std::string_view to_string(HuntObjective o) {
  return name_of(kObjectiveNames, o);
}

std::string_view hunt_objective_meaning(HuntObjective o) {
  return name_of(kObjectiveMeanings, o);
}

std::optional<HuntObjective> hunt_objective_from_string(std::string_view name) {
  return value_named(kObjectiveNames, name);
}

std::vector<std::string> hunt_objective_names() {
  std::vector<std::string> names;
  for (const auto& entry : kObjectiveNames)
    names.emplace_back(entry.name);
  return names;
}

HuntReport hunt(const ExperimentConfig& config, const HuntOptions& options) {
  const Judge judge(config, options);
  HuntReport report;
  report.algorithm = options.algorithm;
  report.objective = options.objective;
  // Rank 0 draws the single process's stream; the others their own (splitmix64's increment).
  std::mt19937_64 rng(options.seed +
                      static_cast<std::uint64_t>(options.rank) * std::uint64_t{0x9E3779B97F4A7C15});
  // Restarts that give no query (cases the algorithm cannot answer) are bounded too.
  for (std::uint64_t attempts = 0;
       report.queries < options.queries && attempts < 4 * options.queries + 16; ++attempts) {
    const std::uint64_t base_case = rng() >> 32;
    const BaseCase base = base_of(generate_case(config, base_case));
    if (!judge.handles_pair(base.pair)) continue;
    ++report.restarts;
    const double target = draw_contact_target(config, rng);
    const int budget = static_cast<int>(
        std::min<std::uint64_t>(options.restart_queries, options.queries - report.queries));
    const auto failing = local_search(base, judge, target, budget, rng, report);
    if (!failing) continue;
    const Pair small =
        shrink(failing->first, judge, target, options.shrink_queries, report.shrink_queries);
    const Judged again = judge(small, target);
    // Shrinking keeps only failing pairs, so `again` fails; the check keeps a stray one out.
    if (!again.valid || !again.failure) continue;
    report.found.push_back(found_case(small, again, base_case, report.queries,
                                      found_case_id(options, report.found.size())));
  }
  if (options.random_baseline)
    report.random_failures = random_baseline_failures(
        config, judge, report.queries, static_cast<std::uint64_t>(options.rank),
        static_cast<std::uint64_t>(options.ranks), report.random_queries);
  return report;
}

std::string found_case_line(const FoundCase& f, const HuntReport& report) {
  nlohmann::ordered_json j;
  j["id"] = f.points.id;
  j["a"] = case_side_json<nlohmann::ordered_json>(f.points.a, f.points.mesh_a);
  j["b"] = case_side_json<nlohmann::ordered_json>(f.points.b, f.points.mesh_b);
  if (f.points.radius_a != 0) j["radius_a"] = f.points.radius_a;
  if (f.points.radius_b != 0) j["radius_b"] = f.points.radius_b;
  nlohmann::ordered_json by;
  by["objective"] = to_string(report.objective);
  by["value"] = f.objective_value;
  by["algorithm"] = report.algorithm;
  by["answer"] = {{"intersect", f.answer_intersect},
                  {"termination", to_string(f.answer_termination)},
                  {"iterations", f.answer_iterations}};
  if (f.answer_distance) by["answer"]["distance"] = *f.answer_distance;
  by["exact"] = {{"intersect", f.exact.intersect}, {"distance", f.exact.distance}};
  if (f.exact.depth) by["exact"]["depth"] = *f.exact.depth;
  by["base_case"] = f.base_case;
  by["query"] = f.query;
  j["found_by"] = by;
  return json_line(j);
}

std::uint64_t rank_queries(std::uint64_t queries, int rank, int ranks) {
  const auto n = static_cast<std::uint64_t>(ranks), k = static_cast<std::uint64_t>(rank);
  return queries / n + (k < queries % n ? 1 : 0);
}

std::string merge_hunt_summaries(const std::vector<std::string>& summaries) {
  if (summaries.empty()) throw std::invalid_argument("hunt: no summaries to merge");
  nlohmann::ordered_json merged;
  for (const std::string& line : summaries) {
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_object() || !j.contains("algorithm") || !j.contains("objective"))
      throw std::invalid_argument("hunt: malformed rank summary: " + line.substr(0, 200));
    if (merged.empty()) {
      merged = nlohmann::ordered_json::parse(line);
      continue;
    }
    const auto text = [](const auto& value) { return value.template get<std::string>(); };
    if (text(j.at("algorithm")) != text(merged["algorithm"]) ||
        text(j.at("objective")) != text(merged["objective"]))
      throw std::invalid_argument("hunt: rank summaries of different searches");
    for (const char* key : {"failures_found", "queries", "restarts", "shrink_queries",
                            "random_failures", "random_queries"})
      merged[key] = merged[key].get<std::uint64_t>() + j.at(key).get<std::uint64_t>();
    merged["worst_relative_error"] = std::max(merged["worst_relative_error"].get<double>(),
                                              j.at("worst_relative_error").get<double>());
  }
  merged["ranks"] = summaries.size();
  return json_line(merged);
}

std::string hunt_summary_json(const HuntReport& r) {
  nlohmann::ordered_json j;
  j["algorithm"] = r.algorithm;
  j["objective"] = to_string(r.objective);
  j["failures_found"] = r.found.size();
  j["queries"] = r.queries;
  j["restarts"] = r.restarts;
  j["shrink_queries"] = r.shrink_queries;
  j["random_failures"] = r.random_failures;
  j["random_queries"] = r.random_queries;
  j["worst_relative_error"] = r.worst_relative_error;
  return json_line(j);
}

}  // namespace gjklab::experiment
