// The scene archive's schema as data (private to src/experiment/archive): one table of column
// descriptors per row struct of gjklab/experiment/archive/scene_archive.hpp, and one of root
// attributes. The writer, the reader and docs/scenes.md's tables all walk these tables: adding
// a column is one member in the struct and one row here.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "gjklab/experiment/archive/scene_archive.hpp"

namespace gjklab::experiment::scene_schema {

/// The row struct's member a column stores; its element type decides the HDF5 type.
template <class R>
using Field = std::variant<std::vector<double> R::*, std::vector<std::int64_t> R::*,
                           std::vector<std::uint32_t> R::*, std::vector<std::int32_t> R::*,
                           std::vector<std::uint8_t> R::*, std::vector<std::string> R::*>;

enum class Presence : std::uint8_t {
  always,  ///< written (possibly with no rows) whenever its group is
  /// Written only when it holds rows (the broad-phase comparison, Bullet's dbvt); read when
  /// present (also absent from archives written before the column was added).
  when_recorded,
};

/// One dataset: its name in the group, the member, values per row, and what a value means
/// (Markdown: units and frame first).
template <class R>
struct Column {
  std::string_view name;
  Field<R> field;
  std::uint8_t width;
  std::string_view meaning;
  Presence presence = Presence::always;
};

/// A table: its columns, and whether they all have the same number of rows (checked on read).
template <class R, std::size_t N>
struct Table {
  std::array<Column<R>, N> columns;
  bool uniform_rows = true;
};
template <class R, std::size_t N>
Table(std::array<Column<R>, N>, bool = true) -> Table<R, N>;

inline constexpr Table kFrames{std::to_array<Column<SceneFrameRows>>({
    {"time", &SceneFrameRows::time, 1, "s: simulated time at the frame's end"},
    {"kinetic_energy", &SceneFrameRows::kinetic_energy, 1, "mass × length² / s²"},
    {"potential_energy", &SceneFrameRows::potential_energy, 1, "mass × length² / s², gravity's"},
    {"max_penetration", &SceneFrameRows::max_penetration, 1,
     "relative to `body_size`: the deepest contact's depth"},
    {"contacts", &SceneFrameRows::contacts, 1, "contact points the solver saw"},
    {"candidate_pairs", &SceneFrameRows::candidate_pairs, 1, "pairs the broad phase found"},
    {"narrow_queries", &SceneFrameRows::narrow_queries, 1, "GJK queries"},
    {"epa_queries", &SceneFrameRows::epa_queries, 1, "depth queries (EPA or the registry's)"},
    {"failed_queries", &SceneFrameRows::failed_queries, 1,
     "queries that stopped other than converged"},
    {"broadphase_ns", &SceneFrameRows::broadphase_ns, 1, "ns: the broad phase's time"},
    {"narrowphase_ns", &SceneFrameRows::narrowphase_ns, 1, "ns: the narrow phase's time"},
    {"solver_ns", &SceneFrameRows::solver_ns, 1, "ns: the contact solver's time"},
    {"iterations_mean", &SceneFrameRows::iterations_mean, 1, "GJK iterations per query, mean"},
    {"iterations_cold_mean", &SceneFrameRows::iterations_cold_mean, 1,
     "the same queries started cold (with `measure_cold`; else 0)"},
    {"all_pairs_ns", &SceneFrameRows::all_pairs_ns, 1,
     "ns: with `compare_broad_phases`, all-pairs' search on the frame's boxes",
     Presence::when_recorded},
    {"grid_ns", &SceneFrameRows::grid_ns, 1, "ns: the same for the grid", Presence::when_recorded},
    {"sap_ns", &SceneFrameRows::sap_ns, 1, "ns: the same for sweep and prune",
     Presence::when_recorded},
    {"dbvt_ns", &SceneFrameRows::dbvt_ns, 1,
     "ns: the same for Bullet's dbvt (when gjklab is built with Bullet)", Presence::when_recorded},
    {"broad_phases_agree", &SceneFrameRows::broad_phases_agree, 1,
     "1 when every broad phase found all-pairs' pair set", Presence::when_recorded},
})};

inline constexpr Table kBodies{std::to_array<Column<SceneBodyRows>>({
    {"shape", &SceneBodyRows::shape, 1, "per body: its shape's name in the scene file"},
    {"mass", &SceneBodyRows::mass, 1, "per body: its mass (0 for a static body)"},
    {"size", &SceneBodyRows::size, 1, "per body: length units, its hull's diagonal"},
    {"is_static", &SceneBodyRows::is_static, 1, "per body: 1 for a static body"},
})};

inline constexpr Table kPoses{std::to_array<Column<ScenePoseRows>>({
    {"pose_frame", &ScenePoseRows::frame, 1, "every `pose_every` frames: the frame (0: start)"},
    {"pose_body", &ScenePoseRows::body, 1, "the dynamic body"},
    {"position", &ScenePoseRows::position, 3, "world frame, length units"},
    {"orientation", &ScenePoseRows::orientation, 4, "unit quaternion `w x y z`, body to world"},
    {"velocity", &ScenePoseRows::velocity, 3, "world frame, length units / s"},
    {"touching", &ScenePoseRows::touching, 1, "1 when the body had a contact that frame"},
})};

inline constexpr Table kContacts{std::to_array<Column<SceneContactRows>>({
    {"frame", &SceneContactRows::frame, 1, "every `contacts_every` frames"},
    {"body_a", &SceneContactRows::a, 1, "the pair's first body"},
    {"body_b", &SceneContactRows::b, 1, "its second body"},
    {"point", &SceneContactRows::point, 3, "world frame, length units"},
    {"normal", &SceneContactRows::normal, 3, "world frame, unit, from A to B"},
    {"depth", &SceneContactRows::depth, 1, "length units: > 0 penetrating"},
    {"normal_impulse", &SceneContactRows::normal_impulse, 1, "mass × length / s: the solver's impulse"},
})};

inline constexpr Table kAudit{std::to_array<Column<SceneAuditRows>>({
    {"frame", &SceneAuditRows::frame, 1, "the audited step (1 = the first)"},
    {"body_a", &SceneAuditRows::a, 1, "the pair's first body"},
    {"body_b", &SceneAuditRows::b, 1, "its second body (a < b)"},
    {"intersect", &SceneAuditRows::intersect, 1, "exact: the world-frame hulls meet"},
    {"certified", &SceneAuditRows::certified, 1,
     "1 when a certificate proved the answer, 0 when the QP did"},
    {"distance", &SceneAuditRows::distance, 1,
     "length units: the exact distance, nearest double (0 when intersecting)"},
    {"depth", &SceneAuditRows::depth, 1,
     "length units: the exact penetration depth, nearest double (NaN unless asked for and "
     "intersecting)"},
    {"narrow_depth", &SceneAuditRows::narrow_depth, 1,
     "length units: the step's deepest contact of the pair (> 0 penetrating, < 0 apart; NaN "
     "when the narrow phase made no contact)"},
})};

inline constexpr Table kQueries{std::to_array<Column<SceneQueryRows>>({
    {"frame", &SceneQueryRows::frame, 1, "the recorded step"},
    {"body_a", &SceneQueryRows::a, 1, "the query's first body"},
    {"body_b", &SceneQueryRows::b, 1, "its second body"},
    {"pose_a", &SceneQueryRows::pose_a, 12,
     "A's pose at the step's start: the rotation's 9 entries row-major, then the translation"},
    {"pose_b", &SceneQueryRows::pose_b, 12, "the same for B"},
    {"warm_size", &SceneQueryRows::warm_size, 1,
     "vertices of the warm start (the previous frame's simplex)"},
    {"warm_index_a", &SceneQueryRows::warm_index_a, 4,
     "the warm start's vertex indices in A's shape, −1 past `warm_size`"},
    {"warm_index_b", &SceneQueryRows::warm_index_b, 4, "the same in B's shape"},
    {"iterations", &SceneQueryRows::iterations, 1, "GJK's iterations"},
    {"intersect", &SceneQueryRows::intersect, 1, "GJK's answer: 1 intersecting"},
    {"distance", &SceneQueryRows::distance, 1, "length units: GJK's distance"},
})};

inline constexpr Table kShapes{
    std::to_array<Column<SceneShapeRows>>({
        {"vertices", &SceneShapeRows::vertices, 3,
         "body frame, length units: each distinct shape's vertices, shape after shape"},
        {"offset", &SceneShapeRows::offset, 1,
         "shape k is `vertices[offset[k]:offset[k+1]]` (one more row than shapes)"},
        {"body_shape", &SceneShapeRows::body_shape, 1, "per body: its shape"},
        {"radius", &SceneShapeRows::radius, 1,
         "per shape, length units: its swept radius (0: the polytope)", Presence::when_recorded},
    }),
    false};

inline constexpr Table kBodyState{std::to_array<Column<SceneBodyStateRows>>({
    {"position", &SceneBodyStateRows::position, 3, "per body: world frame"},
    {"orientation_xyzw", &SceneBodyStateRows::orientation_xyzw, 4,
     "per body: the integrator's quaternion `x y z w`"},
    {"velocity", &SceneBodyStateRows::velocity, 3, "per body: length units / s"},
    {"angular_velocity", &SceneBodyStateRows::angular_velocity, 3, "per body: rad / s"},
    {"touching", &SceneBodyStateRows::touching, 1, "per body"},
})};

inline constexpr Table kPairState{std::to_array<Column<ScenePairStateRows>>({
    {"pair_a", &ScenePairStateRows::pair_a, 1, "per carried pair: its first body"},
    {"pair_b", &ScenePairStateRows::pair_b, 1, "its second body"},
    {"simplex_size", &ScenePairStateRows::simplex_size, 1, "its warm-start simplex's vertices"},
    {"point_count", &ScenePairStateRows::point_count, 1, "its contact points"},
})};

inline constexpr Table kSimplexState{std::to_array<Column<SceneSimplexStateRows>>({
    {"simplex_w", &SceneSimplexStateRows::simplex_w, 3, "the simplices' vertices, pair after pair"},
    {"simplex_a", &SceneSimplexStateRows::simplex_a, 3, "their support points on A"},
    {"simplex_b", &SceneSimplexStateRows::simplex_b, 3, "their support points on B"},
    {"simplex_index_a", &SceneSimplexStateRows::simplex_index_a, 1, "A's vertex indices"},
    {"simplex_index_b", &SceneSimplexStateRows::simplex_index_b, 1, "B's vertex indices"},
})};

inline constexpr Table kPointState{std::to_array<Column<ScenePointStateRows>>({
    {"point_local_a", &ScenePointStateRows::point_local_a, 3,
     "the contact points in A's frame, pair after pair"},
    {"point_impulse", &ScenePointStateRows::point_impulse, 3, "their accumulated impulses"},
})};

/// A root attribute: the header's member (a bool is stored as uint8).
using HeaderField = std::variant<std::string SceneHeader::*, std::uint64_t SceneHeader::*,
                                 double SceneHeader::*, bool SceneHeader::*>;
struct Attribute {
  std::string_view name;
  HeaderField field;
  std::string_view meaning;
};

/// The root attributes after `format` and `schema_version` and the build's provenance, in the
/// order written; `finite` and `complete` are written after the groups.
inline constexpr auto kRoot = std::to_array<Attribute>({
    {"scene_name", &SceneHeader::scene_name, "the scene file's `name`"},
    {"scene_file", &SceneHeader::scene_file, "the scene file's path as given"},
    {"scene_toml", &SceneHeader::scene_toml, "the scene file's text (a resumed run reads it)"},
    {"seed", &SceneHeader::seed, "the placement's seed"},
    {"frames", &SceneHeader::frames, "frames simulated"},
    {"pose_every", &SceneHeader::pose_every, "frames between rows of bodies/'s poses"},
    {"contacts_every", &SceneHeader::contacts_every, "frames between rows of contacts/"},
    {"audit_every", &SceneHeader::audit_every, "frames between audits (0: no audit/)"},
    {"audit_depth", &SceneHeader::audit_depth, "1 when the audit computed exact depths"},
    {"queries_every", &SceneHeader::queries_every,
     "frames between recorded queries (0: no queries/ and shapes/)"},
    {"body_size", &SceneHeader::body_size,
     "length units: the median dynamic body's hull diagonal"},
    {"dt", &SceneHeader::dt, "s: the time step"},
    {"contact_margin", &SceneHeader::contact_margin, "length units"},
    {"broad_phase", &SceneHeader::broad_phase, "the broad phase's name"},
    {"narrow_algorithm", &SceneHeader::narrow_algorithm, "the narrow phase's algorithm"},
    {"depth_algorithm", &SceneHeader::depth_algorithm, "the depth query's algorithm"},
    {"warm_start", &SceneHeader::warm_start, "1 when GJK started from last frame's simplex"},
});
inline constexpr auto kRootLast = std::to_array<Attribute>({
    {"finite", &SceneHeader::finite, "1 when the state stayed finite"},
    {"complete", &SceneHeader::complete,
     "1 for a finished run (written last); 0 for a checkpoint (FILE.h5.tmp, with state/)"},
});

/// state/'s attributes.
struct StateAttribute {
  std::string_view name;
  std::variant<double SceneState::*, std::uint64_t SceneState::*> field;
  std::string_view meaning;
};
inline constexpr auto kStateAttributes = std::to_array<StateAttribute>({
    {"time", &SceneState::time, "s: the world's clock"},
    {"steps", &SceneState::steps, "steps taken"},
    {"frames_target", &SceneState::frames_target, "frames the run is to reach"},
});

/// A group's rows for docs/scenes.md (name, type, meaning): "root", "frames", "bodies",
/// "contacts", "audit", "queries", "shapes" or "state"; nullopt for another name.
std::optional<std::vector<std::array<std::string, 3>>> rows(std::string_view group);

}  // namespace gjklab::experiment::scene_schema
