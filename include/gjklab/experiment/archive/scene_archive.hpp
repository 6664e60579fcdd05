// The scene archive (`gjklab simulate`'s HDF5 file, format "gjklab-scene") as plain columns: one
// struct per table, each member a column, one value (or `width` values) per row. The writer,
// the reader (a checkpoint resumed, the experiments' `stream` family) and the schema tables of
// docs/scenes.md (archive_schema_table("scene/GROUP")) all walk one table of column descriptors
// (src/experiment/archive/scene_schema.hpp), so a column is named once. The simulation layer fills
// these structs; this room knows no scene types.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gjklab::experiment {

/// Bumped on any change of the scene archive's layout (2: frames/dbvt_ns, audit/; 3: queries/,
/// shapes/).
inline constexpr std::uint64_t kSceneSchemaVersion = 3;

/// frames/: one row per frame.
struct SceneFrameRows {
  std::vector<double> time, kinetic_energy, potential_energy, max_penetration, iterations_mean,
      iterations_cold_mean;
  std::vector<std::int64_t> contacts, candidate_pairs, narrow_queries, epa_queries, failed_queries,
      broadphase_ns, narrowphase_ns, solver_ns;
  // With compare_broad_phases: the pair search alone, timed on the same boxes (dbvt_ns only
  // when Bullet is built in).
  std::vector<std::int64_t> all_pairs_ns, grid_ns, sap_ns, dbvt_ns;
  std::vector<std::uint8_t> broad_phases_agree;
};

/// bodies/, per body: what it is.
struct SceneBodyRows {
  std::vector<std::string> shape;
  std::vector<double> mass, size;
  std::vector<std::uint8_t> is_static;
};

/// bodies/, every pose_every frames: where each dynamic body is.
struct ScenePoseRows {
  std::vector<std::int64_t> frame;
  std::vector<std::uint32_t> body;
  std::vector<double> position, orientation, velocity;  // 3, 4 (w x y z), 3 per row
  std::vector<std::uint8_t> touching;
};

/// contacts/, every contacts_every frames.
struct SceneContactRows {
  std::vector<std::int64_t> frame;
  std::vector<std::uint32_t> a, b;
  std::vector<double> point, normal, depth, normal_impulse;  // 3, 3, 1, 1 per row
};

/// audit/: one row per audited pair (`[oracle] audit_every = k`).
struct SceneAuditRows {
  std::vector<std::int64_t> frame;  ///< the step's frame number (1 = the first step)
  std::vector<std::uint32_t> a, b;  ///< bodies, a < b
  std::vector<std::uint8_t> intersect;
  std::vector<std::uint8_t> certified;  ///< 1: a certificate proved the distance; 0: the QP
  /// The exact distance between the hulls, rounded to the nearest double (0 when intersecting).
  std::vector<double> distance;
  /// The exact penetration depth, rounded (with `depth = true` and intersect; else NaN).
  std::vector<double> depth;
  /// The narrow phase's deepest contact of the pair in that step: > 0 penetrating, < 0 apart
  /// (length units); NaN when it made no contact (it found the pair beyond the contact margin).
  std::vector<double> narrow_depth;
  std::size_t size() const { return frame.size(); }
};

/// queries/: one row per narrow-phase query of the recorded frames.
struct SceneQueryRows {
  std::vector<std::int64_t> frame;
  std::vector<std::uint32_t> a, b;
  /// Per row, each body's pose at the step's start: the rotation's 9 entries (row-major), then
  /// the translation; the query ran on every shape vertex v moved to rotation·v + translation.
  std::vector<double> pose_a, pose_b;  // 12 per row
  std::vector<std::uint8_t> warm_size;
  std::vector<std::int32_t> warm_index_a, warm_index_b;  // 4 per row, −1 past warm_size
  std::vector<std::int32_t> iterations;
  std::vector<std::uint8_t> intersect;
  std::vector<double> distance;
};

/// shapes/ (with queries/): each distinct shape once, in the order bodies first use it.
struct SceneShapeRows {
  std::vector<double> vertices;           ///< body frame, 3 per row
  std::vector<std::int64_t> offset;       ///< shape k is vertices[offset[k], offset[k+1])
  std::vector<std::uint32_t> body_shape;  ///< per body
  std::vector<double> radius;  ///< per shape: its swept radius (length units; 0: polytope)
};

/// state/ (checkpoints only), per body: the integrator's state.
struct SceneBodyStateRows {
  std::vector<double> position, orientation_xyzw, velocity, angular_velocity;  // 3, 4, 3, 3
  std::vector<std::uint8_t> touching;
};

/// state/, per carried pair: its warm-start simplex and contact points.
struct ScenePairStateRows {
  std::vector<std::uint32_t> pair_a, pair_b, simplex_size, point_count;
};

/// state/, the carried pairs' simplex vertices, pair after pair.
struct SceneSimplexStateRows {
  std::vector<double> simplex_w, simplex_a, simplex_b;  // 3 per row
  std::vector<std::int32_t> simplex_index_a, simplex_index_b;
};

/// state/, the carried pairs' contact points, pair after pair.
struct ScenePointStateRows {
  std::vector<double> point_local_a, point_impulse;  // 3 per row
};

/// state/: what a resumed run needs beyond the recording.
struct SceneState {
  double time = 0;
  std::uint64_t steps = 0;
  std::uint64_t frames_target = 0;
  SceneBodyStateRows bodies;
  ScenePairStateRows pairs;
  SceneSimplexStateRows simplex;
  ScenePointStateRows points;
};

/// The root attributes: the run's settings (with the build's provenance beside them).
struct SceneHeader {
  std::string scene_name, scene_file, scene_toml;
  std::uint64_t seed = 0, frames = 0, pose_every = 0, contacts_every = 0, audit_every = 0,
                queries_every = 0;
  bool audit_depth = false;
  double body_size = 1, dt = 0, contact_margin = 0;
  std::string broad_phase, narrow_algorithm, depth_algorithm;
  bool warm_start = false;
  bool finite = true;
  bool complete = false;  ///< written last: a reader that sees true sees every dataset
};

/// A whole scene archive. audit/ is present with audit_every > 0, queries/ and shapes/ with
/// queries_every > 0, state/ in a checkpoint.
struct SceneArchive {
  SceneHeader header;
  std::vector<std::pair<std::string, std::string>> provenance;
  SceneFrameRows frames;
  SceneBodyRows bodies;
  ScenePoseRows poses;
  SceneContactRows contacts;
  SceneAuditRows audit;
  SceneQueryRows queries;
  SceneShapeRows shapes;
  std::optional<SceneState> state;
};

/// Writes `archive` to FILE.writing and renames it to `path`, so a kill while writing leaves
/// the previous file intact; `complete` is the last attribute written. Throws ArchiveError
/// naming the file.
void write_scene_archive(const std::string& path, const SceneArchive& archive);

/// Reads a scene archive (complete or a checkpoint). Every table's columns must have the same
/// number of rows and the widths above; throws ArchiveError naming the file and the dataset.
SceneArchive read_scene_archive(const std::string& path);

}  // namespace gjklab::experiment
