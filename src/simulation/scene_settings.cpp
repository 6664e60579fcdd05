// The settings tables of a scene file (see scene_settings.hpp).
#include "scene_settings.hpp"

#include <span>
#include <string>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

namespace gjklab::simulation {

namespace {

/// The options of a registry algorithm from a table of its keys (`[narrow_phase.options]`,
/// `[narrow_phase.depth_options]`), through the registry's own option rows: numbers, booleans,
/// names and [x, y, z] directions; a key the algorithm does not take, or a bad value, fails
/// with the key's line.
experiment::AlgorithmOptions options_of(const SceneTable& t, const std::string& algorithm) {
  experiment::AlgorithmSpec spec{algorithm, algorithm, {}};
  for (auto&& [k, v] : t.raw()) {
    std::string text;
    if (const auto i = v.value_exact<std::int64_t>()) {
      text = std::to_string(*i);
    } else if (const auto d = v.value_exact<double>()) {
      text = experiment::round_trip(*d);
    } else if (const auto b = v.value_exact<bool>()) {
      text = *b ? "true" : "false";
    } else if (const auto str = v.value_exact<std::string>()) {
      text = *str;
    } else if (const toml::array* a = v.as_array()) {
      const auto xyz = t.numbers_of(*a, k.str(), 3);
      text = experiment::round_trip(xyz[0]) + " " + experiment::round_trip(xyz[1]) + " " +
             experiment::round_trip(xyz[2]);
    } else {
      t.fail(k.str(), "expected a number, a boolean, a name or [x, y, z]");
    }
    try {
      experiment::set_option(spec, k.str(), text);
    } catch (const std::invalid_argument& e) {
      t.fail(k.str(), e.what());
    }
  }
  return spec.options;
}

/// A registry algorithm that answers a distance, as the scene's narrow-phase query: cold, on the
/// world hulls, with `options`. Where it reports no closest points, gjk-johnson's are used (the
/// contact needs a point and a normal).
scene::NarrowQuery registry_query(const SceneTable& n, const std::string& name,
                                  const experiment::AlgorithmOptions& options) {
  const experiment::AlgorithmInfo* info = experiment::find_algorithm(name);
  if (!info)
    n.fail("algorithm",
           "unknown algorithm '" + name + "'; valid: " + experiment::algorithm_names());
  if (info->kind == experiment::AnswerKind::boolean)
    n.fail("algorithm", "'" + name + "' answers no distance, which contacts need");
  return {
      name, [info, options](const Polytope& a, const Polytope& b, std::span<const SimplexVertex>) {
        const experiment::Outcome o = experiment::run_algorithm(*info, a, b, SweptRadii{}, options);
        DistanceResult r;
        r.intersect = o.intersect;
        r.distance = o.intersect ? 0.0 : o.distance.value_or(0.0);
        r.iterations = o.iterations;
        r.support_calls = o.support_calls;
        r.termination = o.termination;
        if (o.witness_a && o.witness_b) {
          r.witness_a = *o.witness_a;
          r.witness_b = *o.witness_b;
        } else if (!o.intersect) {
          const DistanceResult g = gjk_distance(a, b);
          r.witness_a = g.witness_a;
          r.witness_b = g.witness_b;
        }
        return r;
      }};
}

/// A GJK distance variant as the scene's narrow phase (its registry entry's narrow_phase):
/// warm-startable, with the scene's GJK options.
scene::NarrowQuery warm_startable_query(const experiment::AlgorithmInfo& info,
                                        const GjkDistanceOptions& gjk) {
  const experiment::NarrowPhaseQuery query = info.narrow_phase;
  return {std::string(info.name),
          [query, gjk](const Polytope& a, const Polytope& b, std::span<const SimplexVertex> warm) {
            return query(a, b, warm, gjk);
          },
          true};
}

/// "gjk-johnson, gjk-johnson-backup, …": the algorithms a scene can start warm.
std::string warm_startable_names() {
  std::string names;
  for (const experiment::AlgorithmInfo& a : experiment::algorithms())
    if (a.narrow_phase) names += (names.empty() ? "" : ", ") + std::string(a.name);
  return names;
}

/// A registry algorithm that reports a depth, as the scene's depth query (with `options`): its
/// depth, normal and the midpoint of its deepest points (where it reports none, A's support
/// point along the normal moved back by half the depth); none for a pair it calls separated
/// or without a depth.
scene::DepthQuery registry_depth_query(const SceneTable& n, const std::string& name,
                                       const experiment::AlgorithmOptions& options) {
  const experiment::AlgorithmInfo* info = experiment::find_algorithm(name);
  if (!info)
    n.fail("depth_algorithm",
           "unknown algorithm '" + name + "'; valid: " + experiment::algorithm_names());
  if (!info->depth) n.fail("depth_algorithm", "'" + name + "' reports no penetration depth");
  return {
      name,
      [info, options](const Polytope& a, const Polytope& b) -> std::optional<scene::Penetration> {
        const experiment::Outcome o = experiment::run_algorithm(*info, a, b, SweptRadii{}, options);
        if (!o.intersect || !o.depth || !o.normal || !(o.normal->norm() > 0)) return std::nullopt;
        const Vec3 normal = o.normal->normalized();
        const Vec3 point = o.witness_a && o.witness_b
                               ? Vec3(0.5 * (*o.witness_a + *o.witness_b))
                               : Vec3(a.support(normal) - 0.5 * *o.depth * normal);
        return scene::Penetration{*o.depth, normal, point, o.termination == Termination::converged};
      }};
}

}  // namespace

void read_settings(const SceneTable& root, scene::WorldSettings& s) {
  const SceneTable p = root.child("physics");
  p.allow_only({"gravity", "dt", "solver_iterations", "position_iterations", "contact_margin",
                "slop", "baumgarte", "restitution_threshold"});
  s.gravity = p.vec3("gravity", s.gravity);
  s.dt = p.number("dt", s.dt, 1e-9, 10);
  s.solver_iterations =
      static_cast<int>(p.integer("solver_iterations", s.solver_iterations, 1, 1000));
  s.position_iterations =
      static_cast<int>(p.integer("position_iterations", s.position_iterations, 0, 1000));
  s.contact_margin = p.number("contact_margin", s.contact_margin, 0, 1e12);
  s.slop = p.number("slop", s.slop, 0, 1e12);
  s.baumgarte = p.number("baumgarte", s.baumgarte, 0, 1);
  s.restitution_threshold = p.number("restitution_threshold", s.restitution_threshold, 0, 1e12);

  const SceneTable b = root.child("broad_phase");
  b.allow_only({"kind", "grid_cell_size"});
  const std::string kind = b.string("kind", std::string(to_string(s.broad_phase)));
  const auto k = scene::broad_phase_from_string(kind);
  if (!k)
    b.fail("kind",
           "unknown broad phase '" + kind + "'; valid: " + names_list(scene::kBroadPhaseKindNames));
  s.broad_phase = *k;
  s.grid_cell_size = b.number("grid_cell_size", 0, 0, 1e12);

  const SceneTable n = root.child("narrow_phase");
  n.allow_only({"algorithm", "depth_algorithm", "options", "depth_options", "warm_start",
                "measure_cold", "max_iterations", "threads"});
  s.measure_cold = n.boolean("measure_cold", false);
  s.threads = static_cast<int>(n.integer("threads", 1, 1, 1024));
  s.gjk.max_iterations =
      static_cast<int>(n.integer("max_iterations", s.gjk.max_iterations, 1, 100000));
  const std::string name = n.string("algorithm", std::string(scene::kDefaultNarrowPhase));
  const experiment::AlgorithmInfo* info = experiment::find_algorithm(name);
  if (info && info->narrow_phase) {
    s.query = warm_startable_query(*info, s.gjk);
    s.warm_start = n.boolean("warm_start", true);
  } else {
    s.query = registry_query(n, name, options_of(n.child("options"), name));
    if (n.boolean("warm_start", false))
      n.fail("warm_start", "'" + name +
                               "' cannot run warm-started; the GJK distance variants can: " +
                               warm_startable_names());
    s.warm_start = false;
  }
  if (const std::string depth = n.string("depth_algorithm", ""); !depth.empty())
    s.depth = registry_depth_query(n, depth, options_of(n.child("depth_options"), depth));
  else if (n.has("depth_options"))
    n.fail("depth_options", "needs depth_algorithm");
  if (s.query->warm_startable && n.has("options"))
    n.fail("options",
           "only for an algorithm other than the GJK variants (which take "
           "max_iterations)");
}

}  // namespace gjklab::simulation
