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
  fcl.max_iterations = n;
  fcl.epa_max_iterations = n;
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

using SweptPolytope = SphereSwept<Polytope>;

/// Whether the request is in double; an entry that can run in another precision checks this
/// first and hands the others to at_precision (queries.hpp).
bool in_double(const QueryRequest& q) {
  return q.options.precision == ScalarPrecision::double_float;
}

Outcome gjk_bool_query(const QueryRequest& q) {
  if (!in_double(q)) return at_precision<GjkBoolIn>(q);
  const GjkBooleanOptions& o = q.options.gjk_boolean;
  auto query = [&](const auto& a, const auto& b) {
    return q.trace ? gjk_intersect(a, b, o, *q.trace) : gjk_intersect(a, b, o);
  };
  if (!q.radii.any()) return from_boolean(query(q.a, q.b));
  return from_boolean(query(SweptPolytope(q.a, q.radii.a), SweptPolytope(q.b, q.radii.b)));
}

/// A GJK distance query from its core (a type whose run() takes shapes of any precision, traced
/// or not; see SubAlgorithmQuery); swept shapes: on the cores, shifted by the radii.
template <class Core>
Outcome distance_query(const QueryRequest& q) {
  if (!in_double(q)) return at_precision<DistanceIn<Core>::template At>(q);
  const DistanceResult d = q.trace ? Core::run(q.a, q.b, q.options, *q.trace)
                                   : Core::run(q.a, q.b, q.options, NoTrace{});
  return from_distance(q.radii.any() ? swept_distance(d, q.radii) : d);
}

/// A GJK distance variant as a scene's narrow phase runs it (NarrowPhaseQuery).
template <class Sub>
DistanceResult narrow_phase_with(const Polytope& a, const Polytope& b,
                                 std::span<const SimplexVertex> warm,
                                 const GjkDistanceOptions& options) {
  return warm.empty() ? gjk_distance_with<Sub>(a, b, options)
                      : gjk_distance_warm_with<Sub>(a, b, warm, options);
}

/// A GJK distance query with the sub-algorithm Sub: started from the request's recorded simplex
/// (vertex indices re-read on the shapes, see gjk_distance_warm_with) when it has one.
template <class Sub>
Outcome gjk_variant_query(const QueryRequest& q) {
  if (q.warm.empty()) return distance_query<SubAlgorithmQuery<Sub>>(q);
  const GjkDistanceOptions& o = q.options.gjk_distance;
  const DistanceResult d = q.trace ? gjk_distance_warm_with<Sub>(q.a, q.b, q.warm, o, *q.trace)
                                   : gjk_distance_warm_with<Sub>(q.a, q.b, q.warm, o);
  return from_distance(q.radii.any() ? swept_distance(d, q.radii) : d);
}

/// EPA after gjk-johnson-backup; swept shapes: on the cores, shifted by the radii (depth grows
/// by r_A + r_B; cores apart by less than that overlap by the difference).
Outcome epa_query(const QueryRequest& q) {
  if (!in_double(q)) return at_precision<EpaIn>(q);
  thread_local EpaPolytope workspace;  // buffers reused across queries on this thread
  const EpaResult core = gjk_epa(q.a, q.b, q.options.gjk_distance, q.options.epa, workspace);
  Outcome out = from_penetration(q.radii.any() ? swept_penetration(core, q.radii) : core, true);
  out.iterations = core.gjk_iterations + core.iterations;  // GJK's, then EPA's
  return out;
}

Outcome sat_query(const QueryRequest& q) {
  const auto sa = sat_shape(q.a);
  const auto sb = sat_shape(q.b);
  const peers::SatResult r = peers::sat_query(*sa, *sb, q.options.sat);
  return from_depth_answer(r, r.axes_tested);
}

#ifdef GJKLAB_HAVE_FCL
template <peers::FclSolver Solver>
Outcome fcl_query(const QueryRequest& q) {
  const auto fa = fcl_shape(q.a);
  const auto fb = fcl_shape(q.b);
  return from_penetration(peers::fcl_query(*fa, *fb, Solver, q.options.fcl), false);
}
#endif

#ifdef GJKLAB_HAVE_BULLET
template <PenetrationResult (*Query)(const peers::BulletShape&, const peers::BulletShape&)>
Outcome bullet_query(const QueryRequest& q) {
  const auto ba = bullet_shape(q.a);
  const auto bb = bullet_shape(q.b);
  return from_penetration(Query(*ba, *bb), true);
}
#endif

/// A libccd adapter's query (it takes the radii itself; zero radii are the plain query).
template <auto Query>
Outcome libccd_query(const QueryRequest& q) {
  const auto answer = Query(q.a, q.b, q.options.libccd, q.radii);
  if constexpr (reports_depth(Query))
    return from_depth_answer(answer, answer.iterations);
  else
    return from_boolean(answer);
}

Outcome exact_query(const QueryRequest& q) {
  Outcome out;
  exact::OracleAnswer answer = solve_certified(q.a, q.b, q.radii, q.options.oracle).answer;
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
Outcome gjk_certified_query(const QueryRequest& q) {
  CertifiedAnswer c = solve_certified(q.a, q.b, q.radii, certified_query_options(q.options));
  Outcome out;
  out.intersect = c.answer.intersect;
  out.distance = c.answer.distance;
  if (c.answer.intersect && c.answer.depth) {
    out.depth = *c.answer.depth;
    out.normal = certified_normal(c);
  }
  if (!q.radii.any()) {
    out.witness_a = c.answer.witness_a;
    out.witness_b = c.answer.witness_b;
  }
  out.iterations = c.iterations;
  out.support_calls = c.support_calls;
  out.exact = std::move(c.answer);
  return out;
}

// ---- the registry entries ------------------------------------------------------------------
//
// One function per algorithm (or per group of algorithms made the same way) builds its entry
// from its query, what the query can be asked (QueryAbilities), its option schema and its
// benchmark loop. registry() lists them, one line each.

/// A GJK distance variant: every form from one core query (see SubAlgorithmQuery).
template <class Core>
AlgorithmInfo gjk_distance_entry(std::string_view name, std::string_view description,
                                 OptionSchema options) {
  return {.name = name,
          .kind = AnswerKind::distance,
          .description = description,
          .run = distance_query<Core>,
          .can = {.swept = true, .traced = true, .precision = true},
          .options = options,
          .bench = bench_distance<Core>};
}

/// A GJK distance query with the sub-algorithm Sub, taking the options gjk_distance (and
/// warm_start): it can also start from a recorded simplex, and be a scene's narrow phase.
template <class Sub>
AlgorithmInfo gjk_variant_entry(std::string_view name, std::string_view description) {
  AlgorithmInfo entry =
      gjk_distance_entry<SubAlgorithmQuery<Sub>>(name, description, gjk_variant_option_schema());
  entry.run = gjk_variant_query<Sub>;
  entry.can.warm = true;
  entry.narrow_phase = narrow_phase_with<Sub>;
  return entry;
}

AlgorithmInfo gjk_bool_entry() {
  return {.name = "gjk-bool",
          .kind = AnswerKind::boolean,
          .description = "boolean GJK walking a simplex with triple-product directions",
          .run = gjk_bool_query,
          .can = {.swept = true, .traced = true, .precision = true},
          .options = gjk_boolean_option_schema(),
          .bench = bench_gjk_bool};
}

AlgorithmInfo epa_entry() {
  return {.name = "epa",
          .kind = AnswerKind::distance,
          .description =
              "gjk-johnson-backup, then the expanding polytope algorithm for the penetration depth",
          .run = epa_query,
          .can = {.swept = true, .precision = true},
          .depth = true,
          .options = epa_option_schema(),
          .bench = bench_epa};
}

AlgorithmInfo sat_entry() {
  return {.name = "sat",
          .kind = AnswerKind::boolean,
          .description =
              "separating axis test on exact hull features (face normals, edge cross "
              "products) with the minimum-overlap depth",
          .run = sat_query,
          .depth = true,
          .options = sat_option_schema(),
          .bench = bench_sat};
}

/// A libccd query, all from its adapter (which takes the radii itself); a penetration adapter
/// reports a depth and takes the depth options.
template <auto Query>
AlgorithmInfo libccd_entry(std::string_view name, std::string_view description) {
  constexpr bool depth = reports_depth(Query);
  return {.name = name,
          .kind = AnswerKind::boolean,
          .description = description,
          .run = libccd_query<Query>,
          .can = {.swept = true},
          .peer = true,
          .depth = depth,
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
          .run = fcl_query<Solver>,
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
          .run = bullet_query<Query>,
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
          .run = gjk_certified_query,
          .can = {.swept = true},
          .bench = bench_gjk_certified};
}

/// The oracle: minutes per query on large clouds, so never in a timed loop (no bench).
AlgorithmInfo exact_entry() {
  return {.name = "exact",
          .kind = AnswerKind::exact,
          .description =
              "exact answer in rational arithmetic: certified from gjklab's own "
              "GJK/EPA, CGAL's QP where no certificate holds",
          .run = exact_query,
          .can = {.swept = true},
          .depth = true,
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
  return !radii.any() || algorithm.can.swept;
}

bool can_trace(const AlgorithmInfo& algorithm, const SweptRadii& radii) {
  return algorithm.can.traced && handles(algorithm, radii);
}

AlgorithmGroup group_of(const AlgorithmInfo& algorithm) {
  if (algorithm.peer) return AlgorithmGroup::peer;
  if (algorithm.kind == AnswerKind::exact) return AlgorithmGroup::oracle;
  return algorithm.can.traced ? AlgorithmGroup::gjk : AlgorithmGroup::own;
}

bool takes_precision(const AlgorithmInfo& algorithm) {
  return algorithm.can.precision;
}

namespace {

std::invalid_argument cannot(const AlgorithmInfo& algorithm, const std::string& what) {
  return std::invalid_argument("algorithm '" + std::string(algorithm.name) + "' " + what);
}

/// Whether the query starts from the case's recorded simplex; throws std::invalid_argument
/// naming the algorithm when warm_start asks for what it cannot do.
bool warm_started(const AlgorithmInfo& algorithm, const QueryRequest& q) {
  if (!q.options.warm_start || q.warm.empty()) return false;
  if (!algorithm.can.warm || q.options.precision != ScalarPrecision::double_float)
    throw cannot(algorithm, "cannot be warm-started here (in double only)");
  return true;
}

/// Whether the query starts from the request's simplex, once the request is checked: throws
/// std::invalid_argument naming the algorithm when it asks for what the entry cannot do (see
/// run_query for the order).
bool checked_warm_start(const AlgorithmInfo& algorithm, const QueryRequest& q) {
  if (q.trace && !can_trace(algorithm, q.radii))
    throw cannot(algorithm, std::string("cannot be traced") +
                                (q.radii.any() ? " on sphere-swept shapes" : ""));
  if (warm_started(algorithm, q)) return true;
  if (q.options.precision != ScalarPrecision::double_float && !algorithm.can.precision)
    throw cannot(algorithm,
                 "runs in double only, not in " + std::string(to_string(q.options.precision)));
  if (!handles(algorithm, q.radii))
    throw cannot(algorithm, "answers for polytopes only, not for sphere-swept shapes (radius > 0)");
  return false;
}

}  // namespace

Outcome run_query(const AlgorithmInfo& algorithm, const QueryRequest& request) {
  if (checked_warm_start(algorithm, request)) return algorithm.run(request);
  QueryRequest cold = request;  // a simplex the options do not ask to start from is not used
  cold.warm = {};
  return algorithm.run(cold);
}

Outcome run_algorithm(const AlgorithmInfo& algorithm, const Polytope& a, const Polytope& b,
                      const SweptRadii& radii, const AlgorithmOptions& options,
                      std::span<const SimplexVertex> warm) {
  return run_query(algorithm, {.a = a, .b = b, .radii = radii, .options = options, .warm = warm});
}

Outcome run_algorithm_traced(const AlgorithmInfo& algorithm, const Polytope& a, const Polytope& b,
                             const SweptRadii& radii, const AlgorithmOptions& options,
                             TraceRecorder& trace, std::span<const SimplexVertex> warm) {
  return run_query(
      algorithm,
      {.a = a, .b = b, .radii = radii, .options = options, .warm = warm, .trace = &trace});
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
      const Outcome o = algorithm.run({.a = *p.a, .b = *p.b, .options = options});
      count_query(t, o.iterations, o.support_calls, o.intersect, o.distance.value_or(0.0));
    }
  }
  return t;
}

}  // namespace gjklab::experiment
