#include "gjklab/experiment/registry/algorithms.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "experiment/registry/bench_loops.hpp"
#include "experiment/registry/queries.hpp"

namespace gjklab::experiment {

void AlgorithmOptions::set_max_iterations(int n) {
  gjk_boolean.max_iterations = n;
  gjk_distance.max_iterations = n;
  gjk_nesterov.max_iterations = n;
  libccd.max_iterations = n;
  libccd.max_depth_iterations = n;
  epa.max_iterations = n;
  epa.max_faces = 4 + 2 * std::min(n, 1 << 24);
#ifdef GJKLAB_HAVE_FCL
  fcl.max_iterations = n;
  fcl.epa_max_iterations = n;
#endif
}

Outcome from_boolean(const BooleanResult& r) {
  Outcome o;
  o.intersect = r.intersect;
  o.iterations = r.iterations;
  o.support_calls = r.support_calls;
  o.termination = r.termination;
  return o;
}

Outcome from_distance(const DistanceResult& r) {
  Outcome o;
  o.intersect = r.intersect;
  o.distance = r.distance;
  o.witness_a = r.witness_a;
  o.witness_b = r.witness_b;
  o.lower_bound = r.lower_bound;
  o.upper_bound = r.upper_bound;
  o.iterations = r.iterations;
  o.support_calls = r.support_calls;
  o.termination = r.termination;
  return o;
}

namespace {

using namespace registry_parts;

Outcome run_gjk_bool(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_boolean(gjk_intersect(a, b, o.gjk_boolean));
}

Outcome trace_gjk_bool(const Polytope& a, const Polytope& b, const AlgorithmOptions& o,
                       TraceRecorder& trace) {
  return from_boolean(gjk_intersect(a, b, o.gjk_boolean, trace));
}

template <class Core>
Outcome run_distance(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return from_distance(Core::run(a, b, o, NoTrace{}));
}
template <class Core>
Outcome trace_distance(const Polytope& a, const Polytope& b, const AlgorithmOptions& o,
                       TraceRecorder& trace) {
  return from_distance(Core::run(a, b, o, trace));
}
template <class Core>
Outcome run_swept_distance(const Polytope& a, const Polytope& b, const SweptRadii& r,
                           const AlgorithmOptions& o) {
  return from_distance(swept_distance(Core::run(a, b, o, NoTrace{}), r));
}
template <class Core>
Outcome trace_swept_distance(const Polytope& a, const Polytope& b, const SweptRadii& r,
                             const AlgorithmOptions& o, TraceRecorder& trace) {
  return from_distance(swept_distance(Core::run(a, b, o, trace), r));
}

Outcome run_epa(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  thread_local EpaPolytope workspace;  // buffers reused across queries on this thread
  const EpaResult r = gjk_epa(a, b, o.gjk_distance, o.epa, workspace);
  Outcome out = from_penetration(r, true);
  out.iterations = r.gjk_iterations + r.iterations;  // GJK's, then EPA's
  return out;
}

Outcome run_sat(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  const auto sa = sat_shape(a);
  const auto sb = sat_shape(b);
  const peers::SatResult r = peers::sat_query(*sa, *sb, o.sat);
  return from_depth_answer(r, r.axes_tested);
}

#ifdef GJKLAB_HAVE_FCL
Outcome run_fcl(const Polytope& a, const Polytope& b, const AlgorithmOptions& o,
                peers::FclSolver solver) {
  const auto fa = fcl_shape(a);
  const auto fb = fcl_shape(b);
  return from_penetration(peers::fcl_query(*fa, *fb, solver, o.fcl), false);
}
Outcome run_fcl_libccd(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return run_fcl(a, b, o, peers::FclSolver::libccd);
}
Outcome run_fcl_indep(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return run_fcl(a, b, o, peers::FclSolver::indep);
}
#endif

#ifdef GJKLAB_HAVE_BULLET
template <PenetrationResult (*Query)(const peers::BulletShape&, const peers::BulletShape&)>
Outcome run_bullet(const Polytope& a, const Polytope& b, const AlgorithmOptions&) {
  const auto ba = bullet_shape(a);
  const auto bb = bullet_shape(b);
  return from_penetration(Query(*ba, *bb), true);
}
#endif

// ---- sphere-swept shapes (see gjk/swept.hpp) ---------------------------------------------

using SweptPolytope = SphereSwept<Polytope>;

Outcome swept_gjk_bool(const Polytope& a, const Polytope& b, const SweptRadii& r,
                       const AlgorithmOptions& o) {
  return from_boolean(gjk_intersect(SweptPolytope(a, r.a), SweptPolytope(b, r.b), o.gjk_boolean));
}

Outcome swept_trace_gjk_bool(const Polytope& a, const Polytope& b, const SweptRadii& r,
                             const AlgorithmOptions& o, TraceRecorder& trace) {
  return from_boolean(
      gjk_intersect(SweptPolytope(a, r.a), SweptPolytope(b, r.b), o.gjk_boolean, trace));
}

/// EPA on the cores, shifted by the radii (depth grows by r_A + r_B; cores apart by less than
/// that overlap by the difference).
Outcome swept_epa(const Polytope& a, const Polytope& b, const SweptRadii& r,
                  const AlgorithmOptions& o) {
  thread_local EpaPolytope workspace;
  const EpaResult core = gjk_epa(a, b, o.gjk_distance, o.epa, workspace);
  Outcome out = from_penetration(swept_penetration(core, r), true);
  out.iterations = core.gjk_iterations + core.iterations;
  return out;
}

/// The run of a libccd adapter (it takes the radii itself).
template <auto Query>
Outcome run_libccd(const Polytope& a, const Polytope& b, const SweptRadii& r,
                   const AlgorithmOptions& o) {
  const auto answer = Query(a, b, o.libccd, r);
  if constexpr (reports_depth(Query))
    return from_depth_answer(answer, answer.iterations);
  else
    return from_boolean(answer);
}

Outcome swept_exact(const Polytope& a, const Polytope& b, const SweptRadii& r,
                    const AlgorithmOptions& o) {
  Outcome out;
  exact::OracleAnswer answer = solve_certified(a, b, r, o.oracle).answer;
  out.intersect = answer.intersect;
  out.distance = answer.distance;
  out.depth = answer.depth;
  out.exact = std::move(answer);
  return out;
}

/// The direction in which B must move by the depth: the certified face normal; for swept
/// shapes whose cores are apart, the direction between the cores' exact closest points; else
/// EPA's normal (depth by the QP), or x when A − B has no interior and EPA did not run.
Vec3 certified_normal(const CertifiedAnswer& c) {
  if (c.answer.depth_normal) return *c.answer.depth_normal;
  if (c.answer.witness_a && c.answer.witness_b && *c.answer.witness_a != *c.answer.witness_b)
    return (*c.answer.witness_b - *c.answer.witness_a).normalized();
  return c.epa_normal.value_or(Vec3::UnitX());
}

/// `gjk-certified`: gjk-johnson (and EPA for intersecting pairs), certified exactly, with the
/// QP as the fallback. Iterations and support calls are the double queries'.
Outcome swept_gjk_certified(const Polytope& a, const Polytope& b, const SweptRadii& r,
                            const AlgorithmOptions& o) {
  CertifiedAnswer c = solve_certified(a, b, r, certified_query_options(o));
  Outcome out;
  out.intersect = c.answer.intersect;
  out.distance = c.answer.distance;
  if (c.answer.intersect && c.answer.depth) {
    out.depth = *c.answer.depth;
    out.normal = certified_normal(c);
  }
  if (!r.any()) {
    out.witness_a = c.answer.witness_a;
    out.witness_b = c.answer.witness_b;
  }
  out.iterations = c.iterations;
  out.support_calls = c.support_calls;
  out.exact = std::move(c.answer);
  return out;
}

using SweptRun = Outcome (*)(const Polytope&, const Polytope&, const SweptRadii&,
                             const AlgorithmOptions&);

/// The polytope query of an algorithm that takes the radii itself (the libccd adapters and the
/// oracle): its swept query with zero radii, which is exactly the plain one.
template <SweptRun Run>
Outcome at_zero_radii(const Polytope& a, const Polytope& b, const AlgorithmOptions& o) {
  return Run(a, b, SweptRadii{}, o);
}

// ---- the registry entries ------------------------------------------------------------------
//
// One function per algorithm (or per group of algorithms made the same way) builds its entry
// from its query: the plain, traced, sphere-swept, other-precision, warm-started and benchmark
// forms where it has them, and its option schema. registry() lists them, one line each.

/// A GJK distance variant: every form from one core query (a type whose run() takes shapes of
/// any precision, traced or not; see SubAlgorithmQuery).
template <class Core>
AlgorithmInfo gjk_distance_entry(std::string_view name, std::string_view description,
                                 OptionSchema options) {
  return {.name = name,
          .kind = AnswerKind::distance,
          .description = description,
          .run = run_distance<Core>,
          .run_traced = trace_distance<Core>,
          .run_swept = run_swept_distance<Core>,
          .run_swept_traced = trace_swept_distance<Core>,
          .run_at_precision = at_precision<DistanceIn<Core>::template At>,
          .options = options,
          .bench = bench_distance<Core>};
}

/// The query of gjk_variant_entry started from a recorded simplex (vertex indices re-read on
/// the shapes, see gjk_distance_warm_with); swept shapes: on the cores, shifted by the radii.
template <class Sub>
Outcome warm_distance_with(const Polytope& a, const Polytope& b, const SweptRadii& r,
                           std::span<const SimplexVertex> warm, const AlgorithmOptions& o,
                           TraceRecorder* trace) {
  const DistanceResult d = trace ? gjk_distance_warm_with<Sub>(a, b, warm, o.gjk_distance, *trace)
                                 : gjk_distance_warm_with<Sub>(a, b, warm, o.gjk_distance);
  return from_distance(r.any() ? swept_distance(d, r) : d);
}

/// A GJK distance query with the sub-algorithm Sub, taking the options gjk_distance (and
/// warm_start).
template <class Sub>
AlgorithmInfo gjk_variant_entry(std::string_view name, std::string_view description) {
  AlgorithmInfo entry =
      gjk_distance_entry<SubAlgorithmQuery<Sub>>(name, description, gjk_variant_option_schema());
  entry.run_warm = warm_distance_with<Sub>;
  return entry;
}

AlgorithmInfo gjk_bool_entry() {
  return {.name = "gjk-bool",
          .kind = AnswerKind::boolean,
          .description = "boolean GJK walking a simplex with triple-product directions",
          .run = run_gjk_bool,
          .run_traced = trace_gjk_bool,
          .run_swept = swept_gjk_bool,
          .run_swept_traced = swept_trace_gjk_bool,
          .run_at_precision = at_precision<GjkBoolIn>,
          .options = gjk_boolean_option_schema(),
          .bench = bench_gjk_bool};
}

AlgorithmInfo epa_entry() {
  return {.name = "epa",
          .kind = AnswerKind::distance,
          .description =
              "gjk-johnson-backup, then the expanding polytope algorithm for the penetration depth",
          .run = run_epa,
          .depth = true,
          .run_swept = swept_epa,
          .run_at_precision = at_precision<EpaIn>,
          .options = epa_option_schema(),
          .bench = bench_epa};
}

AlgorithmInfo sat_entry() {
  return {.name = "sat",
          .kind = AnswerKind::boolean,
          .description =
              "separating axis test on exact hull features (face normals, edge cross "
              "products) with the minimum-overlap depth",
          .run = run_sat,
          .depth = true,
          .options = sat_option_schema(),
          .bench = bench_sat};
}

/// A libccd query, all from its adapter: the adapter takes the radii itself, so the plain run
/// is the swept one at zero radii; a penetration adapter reports a depth and takes the depth
/// options.
template <auto Query>
AlgorithmInfo libccd_entry(std::string_view name, std::string_view description) {
  constexpr bool depth = reports_depth(Query);
  return {.name = name,
          .kind = AnswerKind::boolean,
          .description = description,
          .run = at_zero_radii<run_libccd<Query>>,
          .peer = true,
          .depth = depth,
          .run_swept = run_libccd<Query>,
          .options = depth ? libccd_depth_option_schema() : libccd_option_schema(),
          .bench = bench_libccd<Query>};
}

#ifdef GJKLAB_HAVE_FCL
/// An FCL solver on fcl::Convex (polytopes only).
template <peers::FclSolver Solver>
AlgorithmInfo fcl_entry(std::string_view name, std::string_view description) {
  return {.name = name,
          .kind = AnswerKind::distance,
          .description = description,
          .run = Solver == peers::FclSolver::libccd ? run_fcl_libccd : run_fcl_indep,
          .peer = true,
          .depth = true,
          .options = fcl_option_schema(),
          .bench = bench_fcl<Solver>};
}
#endif

#ifdef GJKLAB_HAVE_BULLET
/// A Bullet query on its own convex hull shape (polytopes only, no options).
template <PenetrationResult (*Query)(const peers::BulletShape&, const peers::BulletShape&)>
AlgorithmInfo bullet_entry(std::string_view name, std::string_view description) {
  return {.name = name,
          .kind = AnswerKind::distance,
          .description = description,
          .run = run_bullet<Query>,
          .peer = true,
          .depth = true,
          .bench = bench_bullet<Query>};
}
#endif

AlgorithmInfo gjk_certified_entry() {
  return {.name = "gjk-certified",
          .kind = AnswerKind::distance,
          .description =
              "gjk-johnson and EPA, verified by exact certificates (CGAL's QP as "
              "fallback): exact answers",
          .run = at_zero_radii<swept_gjk_certified>,
          .run_swept = swept_gjk_certified,
          .bench = bench_gjk_certified};
}

/// The oracle: minutes per query on large clouds, so never in a timed loop (no bench).
AlgorithmInfo exact_entry() {
  return {.name = "exact",
          .kind = AnswerKind::exact,
          .description =
              "exact answer in rational arithmetic: certified from gjklab's own "
              "GJK/EPA, CGAL's QP where no certificate holds",
          .run = at_zero_radii<swept_exact>,
          .depth = true,
          .run_swept = swept_exact,
          .options = exact_option_schema()};
}

/// How many algorithms AddedAlgorithm may add at once: the registry's storage is reserved for
/// them, so that adding one never moves the entries that find_algorithm has handed out.
constexpr std::size_t kMaxAddedAlgorithms = 16;

// The registry: one line per algorithm, in the default order of outputs; the optional peers
// (FCL, Bullet) are listed only when they were built. Built on first use: the schemas live in
// another translation unit, so the table is not a compile-time constant and must not depend on
// the order of static initialisation.
std::vector<AlgorithmInfo>& registry() {
  static const std::array builtin = {
      gjk_bool_entry(),
      gjk_variant_entry<JohnsonSubAlgorithm>("gjk-johnson",
                                             "GJK distance with Johnson's distance sub-algorithm"),
      libccd_entry<peers::libccd_gjk_intersect>("libccd-gjk", "libccd's ccdGJKIntersect"),
      libccd_entry<peers::libccd_mpr_intersect>("libccd-mpr", "libccd's ccdMPRIntersect"),
      gjk_variant_entry<JohnsonBackupSubAlgorithm>(
          "gjk-johnson-backup",
          "GJK distance with Johnson's sub-algorithm and van den Bergen's backup procedure"),
      gjk_variant_entry<SignedVolumesSubAlgorithm>(
          "gjk-sv", "GJK distance with the signed-volumes sub-algorithm (Montanari et al. 2017)"),
      gjk_variant_entry<VoronoiSubAlgorithm>(
          "gjk-voronoi", "GJK distance with Voronoi-region tests (Ericson 2005)"),
      gjk_distance_entry<NesterovQuery>(
          "gjk-nesterov", "Nesterov-accelerated GJK distance (Montaut et al. 2022), signed volumes",
          gjk_nesterov_option_schema()),
      gjk_distance_entry<PolyakQuery>(
          "gjk-polyak",
          "Polyak-accelerated GJK distance (GJK++, Montaut et al. 2024), signed volumes",
          gjk_distance_option_schema()),
      epa_entry(),
      sat_entry(),
      libccd_entry<peers::libccd_gjk_penetration>(
          "libccd-gjk-epa", "libccd's ccdGJKPenetration (GJK, then EPA) with a bounded EPA loop"),
      libccd_entry<peers::libccd_mpr_penetration>("libccd-mpr-depth", "libccd's ccdMPRPenetration"),
#ifdef GJKLAB_HAVE_FCL
      fcl_entry<peers::FclSolver::libccd>(
          "fcl-libccd",
          "FCL's libccd-based GJK solver on fcl::Convex (collide: MPR; distance: GJK)"),
      fcl_entry<peers::FclSolver::indep>(
          "fcl-indep", "FCL's own GJK/EPA solver on fcl::Convex (collide and distance)"),
#endif
#ifdef GJKLAB_HAVE_BULLET
      bullet_entry<peers::bullet_gjk_query>(
          "bullet-gjk",
          "Bullet's btGjkPairDetector (Voronoi simplex solver, GJK-EPA penetration), margins 0"),
      bullet_entry<peers::bullet_epa2_query>(
          "bullet-epa2", "Bullet's btGjkEpaSolver2 (Distance, then Penetration), margins 0"),
#endif
      gjk_certified_entry(),
      exact_entry(),
  };
  static std::vector<AlgorithmInfo> entries = [] {
    std::vector<AlgorithmInfo> v;
    v.reserve(builtin.size() + kMaxAddedAlgorithms);
    v.assign(builtin.begin(), builtin.end());
    return v;
  }();
  return entries;
}

}  // namespace

std::span<const AlgorithmInfo> algorithms() {
  return registry();
}

const AlgorithmInfo* find_algorithm(std::string_view name) {
  for (const AlgorithmInfo& a : registry())
    if (a.name == name) return &a;
  return nullptr;
}

AddedAlgorithm::AddedAlgorithm(const AlgorithmInfo& algorithm) : name_(algorithm.name) {
  if (find_algorithm(algorithm.name))
    throw std::invalid_argument("algorithm '" + std::string(algorithm.name) +
                                "' is already registered");
  std::vector<AlgorithmInfo>& entries = registry();
  if (entries.size() == entries.capacity())
    throw std::length_error("at most " + std::to_string(kMaxAddedAlgorithms) +
                            " algorithms can be added");
  entries.push_back(algorithm);
}

AddedAlgorithm::~AddedAlgorithm() {
  std::vector<AlgorithmInfo>& entries = registry();
  std::erase_if(entries, [&](const AlgorithmInfo& a) { return a.name == name_; });
}

bool handles(const AlgorithmInfo& algorithm, const SweptRadii& radii) {
  return !radii.any() || algorithm.run_swept != nullptr;
}

bool can_trace(const AlgorithmInfo& algorithm, const SweptRadii& radii) {
  return radii.any() ? algorithm.run_swept_traced != nullptr : algorithm.run_traced != nullptr;
}

namespace {

std::invalid_argument polytopes_only(const AlgorithmInfo& algorithm) {
  return std::invalid_argument("algorithm '" + std::string(algorithm.name) +
                               "' answers for polytopes only, not for sphere-swept shapes "
                               "(radius > 0)");
}

}  // namespace

AlgorithmGroup group_of(const AlgorithmInfo& algorithm) {
  if (algorithm.peer) return AlgorithmGroup::peer;
  if (algorithm.kind == AnswerKind::exact) return AlgorithmGroup::oracle;
  return algorithm.run_traced ? AlgorithmGroup::gjk : AlgorithmGroup::own;
}

bool takes_precision(const AlgorithmInfo& algorithm) {
  return algorithm.run_at_precision != nullptr;
}

namespace {

/// Whether the options ask for another precision than double; throws std::invalid_argument
/// naming the algorithm when it cannot run in it.
bool in_other_precision(const AlgorithmInfo& algorithm, const AlgorithmOptions& options) {
  if (options.precision == ScalarPrecision::double_float) return false;
  if (!takes_precision(algorithm))
    throw std::invalid_argument("algorithm '" + std::string(algorithm.name) +
                                "' runs in double only, not in " +
                                std::string(to_string(options.precision)));
  return true;
}

}  // namespace

namespace {

/// Whether the query starts from the case's recorded simplex; throws std::invalid_argument
/// naming the algorithm when warm_start asks for what it cannot do.
bool warm_started(const AlgorithmInfo& algorithm, const AlgorithmOptions& options,
                  std::span<const SimplexVertex> warm) {
  if (!options.warm_start || warm.empty()) return false;
  if (!algorithm.run_warm || options.precision != ScalarPrecision::double_float)
    throw std::invalid_argument("algorithm '" + std::string(algorithm.name) +
                                "' cannot be warm-started here (in double only)");
  return true;
}

}  // namespace

Outcome run_algorithm(const AlgorithmInfo& algorithm, const Polytope& a, const Polytope& b,
                      const SweptRadii& radii, const AlgorithmOptions& options,
                      std::span<const SimplexVertex> warm) {
  if (warm_started(algorithm, options, warm))
    return algorithm.run_warm(a, b, radii, warm, options, nullptr);
  if (in_other_precision(algorithm, options))
    return algorithm.run_at_precision(a, b, radii, options, nullptr);
  if (!radii.any()) return algorithm.run(a, b, options);
  if (!algorithm.run_swept) throw polytopes_only(algorithm);
  return algorithm.run_swept(a, b, radii, options);
}

Outcome run_algorithm_traced(const AlgorithmInfo& algorithm, const Polytope& a, const Polytope& b,
                             const SweptRadii& radii, const AlgorithmOptions& options,
                             TraceRecorder& trace, std::span<const SimplexVertex> warm) {
  if (!can_trace(algorithm, radii))
    throw std::invalid_argument("algorithm '" + std::string(algorithm.name) + "' cannot be traced" +
                                (radii.any() ? " on sphere-swept shapes" : ""));
  if (warm_started(algorithm, options, warm))
    return algorithm.run_warm(a, b, radii, warm, options, &trace);
  if (in_other_precision(algorithm, options))
    return algorithm.run_at_precision(a, b, radii, options, &trace);
  if (!radii.any()) return algorithm.run_traced(a, b, options, trace);
  return algorithm.run_swept_traced(a, b, radii, options, trace);
}

std::string algorithm_names() {
  std::string names;
  for (const AlgorithmInfo& a : registry()) {
    if (!names.empty()) names += ", ";
    names += a.name;
  }
  return names;
}

}  // namespace gjklab::experiment

// ---- benchmark loops ---------------------------------------------------------------------

namespace gjklab::experiment {

BenchLoop find_bench_loop(std::string_view name) {
  const AlgorithmInfo* algorithm = find_algorithm(name);
  return algorithm ? algorithm->bench : nullptr;
}

BenchTally run_bench_loop_via_registry(const AlgorithmInfo& algorithm,
                                       std::span<const BenchPair> pairs,
                                       const AlgorithmOptions& options, int repetitions) {
  BenchTally t;
  for (int r = 0; r < repetitions; ++r) {
    for (const BenchPair& p : pairs) {
      const Outcome o = algorithm.run(*p.a, *p.b, options);
      count_query(t, o.iterations, o.support_calls, o.intersect, o.distance.value_or(0.0));
    }
  }
  return t;
}

}  // namespace gjklab::experiment
