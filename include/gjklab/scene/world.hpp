// A world of rigid convex bodies stepped by semi-implicit Euler with a sequential-impulse
// contact solver. Units are the caller's (the scene files use m, kg, s); frames are world
// frames unless a name says body.
//
// One step, of length dt:
//  1. Broad phase: world AABBs of every body, grown by the contact margin and by the distance
//     the body can travel in the step, give the candidate pairs (static pairs dropped).
//  2. Narrow phase: per candidate pair, GJK distance between the two hulls in world
//     coordinates, warm-started from the pair's final simplex of the previous step (the simplex
//     stores vertex indices, re-evaluated on the moved hulls). Pairs closer than the margin
//     plus the distance they can close in the step are in contact (speculatively when apart);
//     intersecting pairs go on to EPA for the depth and normal. A contact manifold of up to four
//     points is built by clipping the incident face against the reference face (both chosen by the
//     normal); when neither face is aligned with the normal (edge or vertex contact) the single
//     GJK/EPA point is used.
//  3. Velocities: v += g dt; then `solver_iterations` passes of sequential impulses on every
//     contact point (non-penetration with restitution, two-axis Coulomb friction), starting
//     from the impulses of the matching points of the previous step.
//  4. Positional correction: a separate pass of pseudo-velocities that push penetrations
//     deeper than `slop` apart by a fraction `baumgarte` per step; they move the bodies but are
//     then discarded, so the correction adds no kinetic energy.
//  5. Positions: x += (v + v_pseudo) dt, q += ½ (ω + ω_pseudo) q dt, renormalised.
//
// Compound bodies (compound.hpp) take part in every step alike; their pairs' narrow phase is
// per piece pair (step 2 for each, cold), and a StepStats query count counts piece pairs.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/simplex.hpp"
#include "gjklab/scene/body.hpp"
#include "gjklab/scene/broadphase.hpp"

namespace gjklab::scene {

/// The narrow phase's name for its own query, used when the settings supply none: GJK distance
/// with Johnson's sub-algorithm, warm-started, as the registry's algorithm of that name runs it.
inline constexpr std::string_view kDefaultNarrowPhase = "gjk-johnson";

/// A narrow-phase query the caller supplies (the scene layer names no algorithm: the registry
/// lies above it). Must be safe to call from several threads at once.
struct NarrowQuery {
  std::string name;  ///< recorded in archives
  /// Answers one pair of world hulls: from `warm` (the pair's simplex of its previous query,
  /// vertex indices into a's and b's lists) when not empty, else cold.
  std::function<DistanceResult(const Polytope& a, const Polytope& b,
                               std::span<const SimplexVertex> warm)>
      run;
  /// run takes a warm start, and its answer's simplex (kept for the pair's next query) starts
  /// EPA; false: it is always called cold, and EPA starts from a cold gjk-johnson query.
  bool warm_startable = false;
};

/// The penetration of an intersecting pair: depth (length units, ≥ 0), the unit normal from A
/// towards B (the direction in which B must move by depth), and a point midway between the
/// deepest points.
struct Penetration {
  double depth = 0;
  Vec3 normal = Vec3::UnitZ();
  Vec3 point = Vec3::Zero();
  bool converged = true;
};

/// A depth query the caller supplies (a registry algorithm that reports a depth); nullopt when
/// it gives none for the pair. Must be safe to call from several threads at once.
struct DepthQuery {
  std::string name;  ///< recorded in archives
  std::function<std::optional<Penetration>(const Polytope& a, const Polytope& b)> run;
};

struct WorldSettings {
  Vec3 gravity = Vec3(0, 0, -9.81);  ///< length/s²
  double dt = 1.0 / 120.0;           ///< s
  int solver_iterations = 20;        ///< velocity passes per step (≥ 1)
  int position_iterations = 4;       ///< pseudo-velocity passes per step (≥ 0)
  /// Absolute (length units): pairs closer than this get contacts (speculative when apart).
  double contact_margin = 0.02;
  /// Absolute (length units): penetration tolerated without positional correction.
  double slop = 0.002;
  /// Fraction of the penetration beyond slop removed per step (dimensionless, in [0, 1]).
  double baumgarte = 0.2;
  /// Approach speed (length/s) below which restitution is ignored (resting contacts).
  double restitution_threshold = 0.5;
  /// Set: this query answers every pair; absent: the scene's own kDefaultNarrowPhase, with
  /// `gjk`. Intersecting pairs take EPA from the query's simplex (or from a cold gjk-johnson
  /// query's, see NarrowQuery::warm_startable) unless `depth` is set.
  std::optional<NarrowQuery> query;
  /// Set: the depth of intersecting pairs comes from this query instead of EPA.
  std::optional<DepthQuery> depth;
  /// The options of the scene's own queries: kDefaultNarrowPhase and EPA's cold start.
  GjkDistanceOptions gjk{};
  /// Start each query from the pair's previous simplex (false: every query cold); only a
  /// warm-startable query is ever started warm.
  bool warm_start = true;
  /// Also run every query cold, only to count its iterations (StepStats::iterations_cold_mean):
  /// the warm-versus-cold comparison on the same stream, at the price of a second query.
  bool measure_cold = false;
  BroadPhaseKind broad_phase = BroadPhaseKind::sweep_and_prune;
  double grid_cell_size = 0;  ///< length units; ≤ 0: automatic (see UniformGrid)
  /// Threads of the narrow phase (≥ 1): the candidate pairs are queried in parallel and their
  /// contacts merged in pair order, so a step is bit for bit the same for any thread count.
  int threads = 1;
};

/// One contact point between bodies a and b.
struct Contact {
  std::uint32_t a = 0, b = 0;
  Vec3 point = Vec3::Zero();    ///< world, midway between the two surfaces
  Vec3 normal = Vec3::UnitZ();  ///< unit, from a towards b
  double depth = 0;             ///< > 0 penetrating, < 0 separated by −depth (speculative)
  double normal_impulse = 0;    ///< accumulated this step (mass·length/s)
  double tangent_impulse[2] = {0, 0};
};

/// What one step did, for the archive's frames table.
struct StepStats {
  std::size_t candidate_pairs = 0;  ///< pairs from the broad phase (static pairs dropped)
  std::size_t narrow_queries = 0;   ///< GJK queries (= candidate pairs, but compound pairs')
  std::size_t epa_queries = 0;      ///< of which went on to EPA (intersecting)
  std::size_t contacts = 0;         ///< contact points
  std::int64_t broadphase_ns = 0;   ///< AABBs and broad phase
  std::int64_t narrowphase_ns = 0;  ///< GJK, EPA and manifolds
  std::int64_t solver_ns = 0;
  double iterations_mean = 0;       ///< mean GJK iterations of the queries (as run)
  double iterations_cold_mean = 0;  ///< the same queries cold (measure_cold only, else 0)
  std::size_t failed_queries = 0;   ///< GJK or EPA stops other than converged
};

/// One narrow-phase query as a step ran it, for a record of the query stream: the pair, the
/// warm start it was given (the previous step's simplex as vertex indices into a's and b's
/// hulls, oldest first; none for a cold query) and what GJK answered.
struct QueryRecord {
  std::uint32_t a = 0, b = 0;
  int warm_size = 0;  ///< 0 … 4 vertices
  std::array<std::int32_t, 4> warm_index_a{-1, -1, -1, -1}, warm_index_b{-1, -1, -1, -1};
  int iterations = 0;
  bool intersect = false;
  double distance = 0;  ///< length units
};

/// A pair's memory between steps: its final simplex (the next query's warm start) and its
/// contact points with their impulses (the next solve's warm start).
struct PairState {
  std::uint32_t a = 0, b = 0;
  std::vector<SimplexVertex> simplex;
  /// Per contact point: where it lies in a's body frame (length units).
  std::vector<Vec3> local_a;
  /// Per contact point: normal impulse and the two tangent impulses (mass·length/s).
  std::vector<std::array<double, 3>> impulses;
};

/// What a world carries from one step to the next besides its bodies' state: restored into a
/// world built from the same scene, with the bodies' poses and velocities, the next step is bit
/// for bit the one the saved world would have taken (an interrupted simulation resumes).
struct CarriedState {
  double time = 0;               ///< s
  std::uint64_t steps = 0;       ///< steps taken
  std::vector<PairState> pairs;  ///< sorted by (a, b)
};

class World {
 public:
  /// Throws std::invalid_argument for settings out of range.
  explicit World(WorldSettings settings);

  /// Adds a body; returns its index. Bodies are never removed.
  std::uint32_t add(RigidBody body);
  std::vector<RigidBody>& bodies() { return bodies_; }
  const std::vector<RigidBody>& bodies() const { return bodies_; }
  const WorldSettings& settings() const { return settings_; }
  /// Sets the narrow phase's thread count (which changes no result). Throws
  /// std::invalid_argument outside [1, 1024].
  void set_threads(int threads);
  double time() const { return time_; }

  /// The state carried between steps (see CarriedState).
  CarriedState carried_state() const;
  /// Replaces the carried state; the caller restores the bodies' poses and velocities. Throws
  /// std::invalid_argument for a pair whose bodies do not exist.
  void restore(const CarriedState& state);

  /// While `log` is set, every query of a step is appended to it (nullptr: none; the caller
  /// keeps the vector alive). The piece-pair queries of compound bodies are not logged: a
  /// QueryRecord names bodies, not pieces.
  void record_queries(std::vector<QueryRecord>* log) { query_log_ = log; }

  /// Advances by settings().dt; returns what the step did.
  StepStats step();

  /// The contacts of the last step (with their impulses).
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// Largest contact depth of the last step (length units; 0 if nothing penetrates).
  double max_penetration() const;

  double kinetic_energy() const;
  /// Σ −m g·x over dynamic bodies (0 at the world origin).
  double potential_energy() const;
  Vec3 linear_momentum() const;
  /// About the world origin.
  Vec3 angular_momentum() const;
  /// True when every pose and velocity is finite.
  bool finite() const;

  /// World AABBs of every body grown by `margin` plus the body's sweep_distance (length units).
  void bounding_boxes(double margin, std::vector<Aabb>& out) const;
  /// How far any point of body i can travel in one step at its current velocities.
  double sweep_distance(std::uint32_t i) const;

 private:
  struct CachedPoint {
    Vec3 local_a;  ///< contact point in a's body frame
    double normal_impulse;
    double tangent_impulse[2];
  };
  struct PairCache {
    std::vector<SimplexVertex> simplex;
    std::vector<CachedPoint> points;
    std::uint64_t step = 0;
  };

  /// What the query of one pair found, before it is merged into the step (see narrow_phase).
  struct PairOutcome;

  void narrow_phase(const std::vector<BodyPair>& pairs, StepStats& stats);
  /// The queries of one pair: reads only the bodies, the prepared world hulls and the pair's
  /// previous simplex, which it replaces (safe to run for different pairs in parallel).
  void collide(std::uint32_t ia, std::uint32_t ib, std::vector<SimplexVertex>& simplex,
               PairOutcome& out) const;
  /// The contacts of one convex pair (the shapes sa, sb of bodies out.a, out.b, at the world
  /// hulls pa, pb: whole bodies or pieces) from its narrow-phase answer r: out.points and
  /// out.normal (no points: no contact), its depth query counted in out.epa and out.failed.
  void convex_contacts(const ConvexShape& sa, const Polytope& pa, const ConvexShape& sb,
                       const Polytope& pb, const DistanceResult& r, PairOutcome& out) const;
  /// The queries of a pair with a compound body: every piece pair whose world boxes meet
  /// within the pair's margin, cold, each with its own contacts and normal (world_compound.cpp).
  void collide_pieces(std::uint32_t ia, std::uint32_t ib, PairOutcome& out) const;
  /// The narrow phase's query of a pair (the supplied one, else kDefaultNarrowPhase), from
  /// `warm` when not empty.
  DistanceResult narrow_query(const Polytope& pa, const Polytope& pb,
                              std::span<const SimplexVertex> warm) const;
  /// The penetration of a pair the narrow-phase query found intersecting (r): the supplied
  /// depth query's, else EPA's; nullopt when there is none.
  std::optional<Penetration> penetration(const Polytope& pa, const Polytope& pb,
                                         const DistanceResult& r) const;
  /// Appends a pair's contacts (with last step's impulses), counts and query record.
  void merge(const PairOutcome& out, PairCache& cache, StepStats& stats, double& iterations,
             double& iterations_cold);
  const Polytope& world_hull(std::uint32_t i);
  /// A compound body's pieces in world coordinates, rebuilt at most once a step.
  const std::vector<Polytope>& world_pieces(std::uint32_t i);
  void warm_start_impulses(std::size_t first, std::size_t count, const PairCache& cache);
  void store_impulses(PairCache& cache, std::size_t first, std::size_t count) const;
  void solve_velocities();
  void correct_positions(std::vector<Vec3>& dv, std::vector<Vec3>& dw);
  void integrate(const std::vector<Vec3>& dv, const std::vector<Vec3>& dw);

  WorldSettings settings_;
  std::vector<RigidBody> bodies_;
  BroadPhase broad_;
  double time_ = 0;
  std::uint64_t step_count_ = 0;
  std::vector<Aabb> boxes_;
  std::vector<BodyPair> pairs_;
  std::vector<Contact> contacts_;
  /// Per contact: which pair cache it belongs to (by key) to store impulses after solving.
  std::vector<std::pair<std::uint64_t, std::pair<std::size_t, std::size_t>>> pair_ranges_;
  std::unordered_map<std::uint64_t, PairCache> cache_;
  /// World-frame copies of the hulls, rebuilt at most once a step (the GJK queries run on
  /// them directly so that their simplices carry vertex indices).
  std::vector<std::optional<Polytope>> world_hulls_;
  std::vector<std::uint64_t> world_hull_step_;
  /// The same for compound bodies' pieces (world_hull_step_ stamps them too).
  std::vector<std::vector<Polytope>> world_pieces_;
  std::vector<QueryRecord>* query_log_ = nullptr;
};

}  // namespace gjklab::scene
