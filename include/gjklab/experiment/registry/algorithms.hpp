// The algorithm registry: every query algorithm by name, behind one call signature.
//
// Experiment files, `gjklab query` and benchmarks select algorithms by these names. Adding an
// algorithm is one entry in src/experiment/registry/algorithms.cpp.
#pragma once

#include <any>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <typeindex>
#include <utility>
#include <vector>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/option_schema.hpp"
#include "gjklab/geometry/enum_names.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/epa.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/simplex.hpp"
#include "gjklab/gjk/swept.hpp"
#include "gjklab/gjk/trace.hpp"
#include "gjklab/peers/fcl_options.hpp"
#include "gjklab/peers/libccd.hpp"
#include "gjklab/peers/sat.hpp"

namespace gjklab::experiment {

/// The option structs of algorithms added from outside the library (AddedAlgorithm), one per
/// type: an added algorithm's schema rows reach its own struct as `o.added.get<MyOptions>()`,
/// which holds the struct's defaults until a key sets it. Copies are deep (T must be
/// copyable), so every AlgorithmSpec owns its options as it owns the library's.
class AddedOptions {
 public:
  template <class T>
  T& get() {
    for (auto& [type, value] : structs_)
      if (type == typeid(T)) return std::any_cast<T&>(value);
    return std::any_cast<T&>(structs_.emplace_back(typeid(T), T{}).second);
  }
  /// The struct as set, or its defaults when nothing set it.
  template <class T>
  T value() const {
    for (const auto& [type, stored] : structs_)
      if (type == typeid(T)) return std::any_cast<const T&>(stored);
    return T{};
  }

 private:
  std::vector<std::pair<std::type_index, std::any>> structs_;
};

/// Options of every algorithm, one struct each; an experiment records all of them. Each
/// struct's keys are its algorithms' option schemas (option_schema.hpp).
struct AlgorithmOptions {
  GjkBooleanOptions gjk_boolean;
  GjkDistanceOptions gjk_distance;  ///< gjk-johnson, gjk-johnson-backup, gjk-sv, gjk-voronoi
  GjkNesterovOptions gjk_nesterov;  ///< gjk-nesterov
  peers::LibccdOptions libccd;
  EpaOptions epa;  ///< `epa` (its GJK phase uses gjk_distance)
  peers::SatOptions sat;
  peers::FclOptions fcl;  ///< fcl-libccd, fcl-indep (registered when FCL was built)
  exact::OracleOptions oracle;
  AddedOptions added;  ///< the added algorithms' own structs
  /// The floating-point type of the GJK queries (gjk-bool, the distance variants, epa): their
  /// inputs are rounded to it and they compute in it; answers are reported in double.
  ScalarPrecision precision = ScalarPrecision::double_float;
  /// The GJK distance variants: start from the case's recorded simplex (the scene's previous
  /// frame, `stream` family) instead of cold; cases without one run cold (see run_query).
  bool warm_start = false;

  /// Sets the iteration bound of every iterative algorithm at once (libccd's penetration
  /// queries: also max_depth_iterations; epa: also max_faces = 4 + 2n, so that the face buffer
  /// does not bind before the iteration bound; Bullet's bounds are fixed at compile time).
  void set_max_iterations(int n);
};

/// One algorithm's answer for one pair, in the vocabulary shared by all algorithms.
struct Outcome {
  bool intersect = false;
  std::optional<double> distance;  ///< absent for boolean-only algorithms
  /// Penetration depth of intersecting pairs, for algorithms that compute one (0 when they
  /// report only touching); absent otherwise.
  std::optional<double> depth;
  /// With depth: the unit direction in which B must move by depth to separate the shapes
  /// (PenetrationResult's convention).
  std::optional<Vec3> normal;
  /// Closest points of separated pairs; for penetration algorithms that report them, the
  /// deepest points of intersecting pairs (witness_a − witness_b = depth·normal).
  std::optional<Vec3> witness_a, witness_b;
  /// The GJK distance queries' proven bracket of the exact distance (DistanceResult's
  /// lower_bound and upper_bound); absent for other algorithms.
  std::optional<double> lower_bound, upper_bound;
  int iterations = 0;
  int support_calls = 0;
  Termination termination = Termination::converged;
  std::optional<exact::OracleAnswer> exact;  ///< the full exact answer (algorithm `exact` only)
};

// ---- benchmark loops ---------------------------------------------------------------------
//
// `gjklab bench` times queries, not the registry's wrapping of them: a benchmark loop calls an
// algorithm's query function directly, many times, with no Outcome, no allocation and no
// exception handling per call, and tallies the answers so that the compiler must compute them.
// Every loop has the same shape (repetitions × pairs, one direct call each), which keeps the
// algorithms comparable.

/// Two shapes of one query.
struct BenchPair {
  const Polytope* a = nullptr;
  const Polytope* b = nullptr;
};

/// Sums over every query a benchmark loop made.
struct BenchTally {
  long long queries = 0;
  long long iterations = 0;
  long long support_calls = 0;
  long long intersections = 0;
  double distance_sum = 0;  ///< distance algorithms only
};

/// Runs the algorithm `repetitions` times over `pairs` (in order, repetition by repetition).
using BenchLoop = BenchTally (*)(std::span<const BenchPair> pairs, const AlgorithmOptions& options,
                                 int repetitions);

/// A boolean GJK answer in the shared vocabulary (no distance), for an entry's run.
Outcome from_boolean(const BooleanResult& r);
/// A distance answer in the shared vocabulary (distance and closest points), for an entry's run.
Outcome from_distance(const DistanceResult& r);

enum class AnswerKind { boolean, distance, exact };
inline constexpr auto kAnswerKindNames = std::to_array<EnumName<AnswerKind>>({
    {AnswerKind::boolean, "boolean"},
    {AnswerKind::distance, "distance"},
    {AnswerKind::exact, "exact"},
});
static_assert(in_value_order(kAnswerKindNames) && ends_at(kAnswerKindNames, AnswerKind::exact));
constexpr std::string_view to_string(AnswerKind k) {
  return name_of(kAnswerKindNames, k);
}

/// One query as an experiment, the benchmark, a scene or replay asks for it: the two polytopes,
/// the radii that sweep them (zero: the polytopes themselves), the options (their precision
/// among them), the recorded simplex to start from (empty: cold) and the trace to fill (null:
/// none). run_query checks a request against the entry's abilities before its run sees it, so a
/// run is only asked for what its entry says it can do.
struct QueryRequest {
  const Polytope& a;
  const Polytope& b;
  SweptRadii radii = {};
  const AlgorithmOptions& options;
  std::span<const SimplexVertex> warm = {};
  TraceRecorder* trace = nullptr;
};

/// What an entry's run can be asked beyond a double query on two polytopes, cold and untraced.
struct QueryAbilities {
  /// Sphere-swept shapes (radii > 0): GJK distance queries run on the cores and shift the
  /// answer by the radii (see gjk/swept.hpp); the boolean GJK and libccd walk the swept support
  /// map; the oracle answers with exact::solve_swept. Not SAT's axes, nor the FCL and Bullet
  /// adapters, which build plain convex hulls.
  bool swept = false;
  /// A per-iteration trace (same arithmetic), on swept shapes too when `swept` (of the cores'
  /// query for distance algorithms). Only gjklab's GJK queries record one.
  bool traced = false;
  /// float and long double (options.precision): the query on the clouds rounded to that
  /// precision, with the radii rounded too; answers are reported in double.
  bool precision = false;
  /// A start from a simplex given by vertex indices into a's and b's vertex lists
  /// (gjk_distance_warm_with; on the cores of swept shapes), in double only.
  bool warm = false;
};

/// A GJK distance variant's own answer, with the final simplex that a scene keeps to
/// warm-start the pair's query in the next frame: from `warm` (vertex indices into a's and b's
/// lists), or cold when it is empty; in double, on polytopes.
using NarrowPhaseQuery = DistanceResult (*)(const Polytope& a, const Polytope& b,
                                            std::span<const SimplexVertex> warm,
                                            const GjkDistanceOptions& options);

struct AlgorithmInfo {
  std::string_view name;
  AnswerKind kind;
  std::string_view description;
  /// The query: every request the abilities allow (run_query checks the others away).
  Outcome (*run)(const QueryRequest& query);
  QueryAbilities can = {};
  /// A third-party library behind an adapter (libccd, FCL, Bullet): its disagreements with
  /// the exact oracle are counted and reported, not treated as gjklab bugs.
  bool peer = false;
  /// Reports a penetration depth for intersecting pairs (Outcome::depth).
  bool depth = false;
  /// The keys the algorithm takes, as data (option_schema.hpp): parsing, validation, the
  /// archive's description and replay all follow from it.
  OptionSchema options = {};
  /// The benchmark's direct loop of the query (see BenchLoop); nullptr when it has none (the
  /// oracle: minutes per query on large clouds), and the benchmark then loops over run.
  BenchLoop bench = nullptr;
  /// The query as a scene's narrow phase runs it (see NarrowPhaseQuery): set exactly for the
  /// warm-startable GJK distance variants (can.warm).
  NarrowPhaseQuery narrow_phase = nullptr;
};

/// Where an algorithm comes from, so that tools can group its results (a study of gjklab's GJK
/// variants against the peers, one colour range per group) without a list of names of their own.
enum class AlgorithmGroup : std::uint8_t {
  gjk,     ///< gjklab's own GJK queries: the ones that can be traced
  own,     ///< gjklab's other queries (EPA, SAT, the certified query)
  peer,    ///< a third-party library behind an adapter (AlgorithmInfo::peer)
  oracle,  ///< the exact answer (AnswerKind::exact)
};
inline constexpr auto kAlgorithmGroupNames = std::to_array<EnumName<AlgorithmGroup>>({
    {AlgorithmGroup::gjk, "gjk"},
    {AlgorithmGroup::own, "own"},
    {AlgorithmGroup::peer, "peer"},
    {AlgorithmGroup::oracle, "oracle"},
});
static_assert(in_value_order(kAlgorithmGroupNames) &&
              ends_at(kAlgorithmGroupNames, AlgorithmGroup::oracle));
constexpr std::string_view to_string(AlgorithmGroup g) {
  return name_of(kAlgorithmGroupNames, g);
}

/// The algorithm's group, from its entry: a peer is a peer, the exact kind is the oracle, and
/// of gjklab's own queries the traceable ones are its GJK variants (a trace records GJK's
/// simplex, so only a GJK query has one).
AlgorithmGroup group_of(const AlgorithmInfo& algorithm);

/// Whether the algorithm can run in another precision than double (options.precision).
bool takes_precision(const AlgorithmInfo& algorithm);

/// Whether the algorithm can answer for a pair with these radii (any algorithm, for zero radii).
bool handles(const AlgorithmInfo& algorithm, const SweptRadii& radii);
/// Whether the algorithm can trace a pair with these radii.
bool can_trace(const AlgorithmInfo& algorithm, const SweptRadii& radii);

/// Runs the request's query with the algorithm. Throws std::invalid_argument naming the
/// algorithm when the request asks for what the entry cannot do (in this order): a trace
/// (!can_trace), a warm start (with options.warm_start and a non-empty `warm`: !can.warm, or
/// another precision than double), another precision (!can.precision), sphere-swept shapes
/// (!can.swept). A `warm` without options.warm_start is ignored: the query runs cold.
Outcome run_query(const AlgorithmInfo& algorithm, const QueryRequest& request);

/// run_query on the polytopes (zero radii) or on the shapes they make swept by the radii,
/// untraced; with options.warm_start, from the case's recorded simplex `warm`.
Outcome run_algorithm(const AlgorithmInfo& algorithm, const Polytope& a, const Polytope& b,
                      const SweptRadii& radii, const AlgorithmOptions& options,
                      std::span<const SimplexVertex> warm = {});
/// The same with a per-iteration trace.
Outcome run_algorithm_traced(const AlgorithmInfo& algorithm, const Polytope& a, const Polytope& b,
                             const SweptRadii& radii, const AlgorithmOptions& options,
                             TraceRecorder& trace, std::span<const SimplexVertex> warm = {});

/// Every registered algorithm, in a fixed order (the default order of outputs).
std::span<const AlgorithmInfo> algorithms();
/// The algorithm with this name, or nullptr.
const AlgorithmInfo* find_algorithm(std::string_view name);
/// "gjk-bool, gjk-johnson, …": the valid names, for error messages.
std::string algorithm_names();

/// An algorithm defined outside the library's registry (a test's, an extension's), registered
/// for as long as this object lives: algorithms(), find_algorithm, experiment files, the
/// benchmark and replay then treat it as any registered one, after the library's algorithms.
/// Its entry is made like theirs (AlgorithmInfo from its query and option schema), so adding
/// one is its file and this one line. Not thread-safe: add and remove while no query runs.
/// Throws std::invalid_argument for a name already registered, std::length_error when too many
/// are added at once.
class AddedAlgorithm {
 public:
  explicit AddedAlgorithm(const AlgorithmInfo& algorithm);
  ~AddedAlgorithm();
  AddedAlgorithm(const AddedAlgorithm&) = delete;
  AddedAlgorithm& operator=(const AddedAlgorithm&) = delete;

 private:
  std::string_view name_;
};

// ---- benchmark loops (the types above; the lookups here) ----------------------------------

/// The algorithm's direct benchmark loop (AlgorithmInfo::bench), or nullptr if it has none or
/// there is no such algorithm (the benchmark then loops over AlgorithmInfo::run and says so).
BenchLoop find_bench_loop(std::string_view name);

/// A loop over AlgorithmInfo::run, for algorithms without a direct loop.
BenchTally run_bench_loop_via_registry(const AlgorithmInfo& algorithm,
                                       std::span<const BenchPair> pairs,
                                       const AlgorithmOptions& options, int repetitions);

}  // namespace gjklab::experiment
