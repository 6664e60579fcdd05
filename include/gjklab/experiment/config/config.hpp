// Experiment files (TOML): what to generate, how to place it, which algorithms to run.
//
// The file format is documented in experiments/README.md. Every error names the file, the
// line and the key, and lists the valid choices where there is a fixed set.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/cases/nonconvex_pairs.hpp"
#include "gjklab/experiment/cases/records.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/meshes/mesh_query.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

namespace gjklab::experiment {

/// A problem in an experiment file: "FILE:LINE: key 'KEY': PROBLEM".
class ConfigError : public std::runtime_error {
 public:
  ConfigError(const std::string& file, int line, const std::string& key,
              const std::string& problem);
};

/// A closed interval [lo, hi]; lo == hi for a fixed value.
struct Interval {
  double lo = 0;
  double hi = 0;
};

/// How a family places its pairs: one Placement for every case, or `mixed`, which draws
/// overlapping or separated per case.
enum class PlacementMode : std::uint8_t { separated, overlapping, mixed, random, touching };
inline constexpr auto kPlacementModeNames = std::to_array<EnumName<PlacementMode>>({
    {PlacementMode::separated, "separated"},
    {PlacementMode::overlapping, "overlapping"},
    {PlacementMode::mixed, "mixed"},
    {PlacementMode::random, "random"},
    {PlacementMode::touching, "touching"},
});
static_assert(in_value_order(kPlacementModeNames) &&
              ends_at(kPlacementModeNames, PlacementMode::touching));
constexpr std::string_view to_string(PlacementMode m) {
  return name_of(kPlacementModeNames, m);
}

/// How the second shape is placed relative to the first, for one family.
struct PlacementSpec {
  /// separated: gap drawn log-uniformly from `gap`; overlapping: overlap drawn log-uniformly
  /// from `depth`; random: B's centre uniform in a cube of half-width `spread` around A's.
  /// `mixed` (not a Placement value): each case is overlapping with `overlapping_fraction`,
  /// else separated. touching (contact families only): exact contact, no ε.
  PlacementMode mode = PlacementMode::mixed;
  Interval gap{1e-6, 10};     ///< relative to the pair's size
  Interval depth{1e-6, 0.5};  ///< relative to the pair's size
  double overlapping_fraction = 0.5;
  double spread = 1.0;  ///< relative to the pair's size
};

/// How each shape of a family is rotated.
enum class Rotation : std::uint8_t {
  none,    ///< as generated
  random,  ///< uniform on SO(3) (coordinates are rounded: flat clouds become nearly flat)
  axes,    ///< one of the 24 signed axis permutations: exact, so flat stays flat
};

/// A pair read from a cases file (the `file` family).
struct StoredPair {
  std::string id;
  std::vector<Vec3> a, b;
  double radius_a = 0, radius_b = 0;  ///< sphere-swept shapes (length units), as stored
  /// `stream` family: the warm start the scene gave the query (its pair's simplex of the
  /// previous frame as vertex indices into a and b, points at those vertices); empty: cold.
  std::vector<SimplexVertex> warm = {};
};

/// One family of cases: the generator of both shapes and how they are placed.
struct FamilySpec {
  std::string name;  ///< label in summaries; defaults to the shape name
  ShapeKind shape_a = ShapeKind::sphere_points;
  ShapeKind shape_b = ShapeKind::sphere_points;
  /// Requested vertex counts (integers); a range is drawn log-uniformly per case. The parser's
  /// default depends on the shape: 32 for the point clouds, 8/33/64/482 for box, cone,
  /// cylinder and uv_sphere.
  Interval vertices_a{32, 32};
  Interval vertices_b{32, 32};
  double scale = 1;  ///< every coordinate is multiplied by this
  Rotation rotation = Rotation::random;
  double weight = 1;  ///< relative share of the cases
  PlacementSpec placement;

  // ---- degenerate and adversarial families ----
  /// Contact families (shape = "contact"): the configuration, built in exact contact with
  /// the contact normal along a random signed axis; placement then moves B by +ε·size
  /// (separated, ε from placement.gap), −ε·size (overlapping, from placement.depth), or not at
  /// all (touching). contact_any draws one of the six exact types per case.
  ContactType contact = ContactType::none;
  bool contact_any = false;
  Interval angle{1e-6, 1e-6};  ///< parallel-edges contact: angle in radians (log-uniform)
  Interval aspect{10, 10};     ///< sliver: aspect ratio (log-uniform)
  Interval scale_ratio{1, 1};  ///< B's scale relative to A's (log-uniform): scale disparity
  Interval offset{0, 0};       ///< both shapes moved by a random vector of this length
                               ///< (length units, log-uniform; 0: not moved)
  /// Sphere-swept shapes: each shape's hull is swept by a ball of a radius drawn log-uniformly
  /// from its range (shape units: scaled with the shape; {0, 0}: no radius, a plain polytope).
  /// shape = "sphere" and "capsule" default to radius 1 and 0.5.
  Interval radius_a{0, 0};
  Interval radius_b{0, 0};
  std::string path;                ///< `file`: the cases file; `mesh`: a mesh file or folder
  std::vector<StoredPair> stored;  ///< its pairs; case i uses pair i mod size
  /// The `mesh` family's meshes (vertices of each file under `path`, in name order); each
  /// shape of a case is one of them, drawn uniformly, then rotated, scaled and placed.
  std::vector<std::vector<Vec3>> meshes;
  /// The `real_object` family's object names, in the order of `meshes` (its meshes are the
  /// objects' convex hulls at unit size, see real_objects.hpp).
  std::vector<std::string> objects;
  /// `shape = "nonconvex"`: pairs of closed non-convex meshes of this kind
  /// (cases/nonconvex_pairs.hpp), queried as solids; the other placement keys do not apply.
  std::optional<NonconvexPair> nonconvex;
  /// `pair = "meshes"`: its closed meshes at unit size (`path`, or the packaged ones), with
  /// their file names in `objects`.
  std::vector<TriangleMesh> closed_meshes;
};

/// One algorithm to run, with its options.
struct AlgorithmSpec {
  std::string name;  ///< registry name (or a mesh peer's, with mesh_peer set)
  /// result group name: the name, or "name@key=value" in a sweep or for a decomposition
  std::string label;
  AlgorithmOptions options;
  /// Experiments of nonconvex families: the decomposition a convex algorithm runs on (null for
  /// a mesh peer and in convex experiments), with its options.
  const DecompositionInfo* decomposition = nullptr;
  DecompositionOptions decomposition_options;
  /// A mesh peer (fcl-bvh), which answers for the two meshes themselves; null otherwise.
  const MeshPeerInfo* mesh_peer = nullptr;
};

/// A sweep of the pair's geometry: every base pair is run once per value, transformed.
/// offset: both shapes translated by value (length units) along a random unit vector of the
/// pair; scale: both shapes multiplied by value. Result families are "family offset=value".
struct GeometrySweep {
  std::string parameter;  ///< "offset" or "scale"
  std::vector<double> values;
};

struct ExperimentConfig {
  std::string source;  ///< the file it was read from (for messages)
  std::string text;    ///< the file's full text (archived as provenance)
  std::string name;
  std::uint64_t seed = 0;
  std::uint64_t cases = 0;
  int threads = 1;
  std::string output;  ///< archive path, relative to the working directory
  bool oracle = true;  ///< run the exact oracle (needed for errors and booleans' correctness)
  bool depth = false;  ///< also compute exact penetration depth of intersecting pairs
  /// [oracle] certificates: verify gjklab's own GJK/EPA answers exactly before falling back
  /// to the QP (the same rationals, much faster). Off: the QP answers every case.
  bool certificates = true;
  /// [oracle] verify: also solve every certified case by the QP and stop with an error if the
  /// rationals differ (the audit mode).
  bool verify = false;
  /// [oracle] hull_vertices: count each cloud's hull vertices (an exact hull per cloud, costlier
  /// than a certificate); the archive holds −1 otherwise.
  bool hull_vertices = false;
  double touching_band = 1e-10;  ///< relative to size: exact answers this close count as touching
  /// Which queries keep a per-iteration trace in the archive.
  TraceMode trace = TraceMode::none;
  bool timing = false;
  int repetitions = 5;  ///< timed repetitions per query; the median is recorded
  std::vector<FamilySpec> families;
  /// After any [sweep] of an algorithm option is expanded: one entry per (algorithm, value),
  /// labelled "name@key=value".
  std::vector<AlgorithmSpec> algorithms;
  std::optional<GeometrySweep> geometry_sweep;

  /// Rows of the run: cases × the number of geometry-sweep values.
  std::uint64_t total_cases() const {
    return cases * (geometry_sweep ? geometry_sweep->values.size() : 1);
  }
  /// The oracle's options for a case: depth when `depth_wanted`, the rest from [oracle].
  exact::OracleOptions oracle_options(bool depth_wanted) const {
    return {.depth = depth_wanted,
            .certificates = certificates,
            .verify = verify,
            .hull_vertices = hull_vertices};
  }
  /// Whether any family has sphere-swept shapes (a radius).
  bool has_swept_shapes() const;
  /// Whether the families are nonconvex (an experiment's families are all nonconvex or none).
  bool has_nonconvex_families() const;
  /// Names of the result families (index = CaseRecord::family): the families, or each family
  /// once per geometry-sweep value.
  std::vector<std::string> result_family_names() const;
};

/// Every name `contact = "NAME"` of a contact family accepts, in order, "any" last.
std::vector<std::string_view> contact_choices();

/// Parses an experiment from TOML text; `source` names it in errors. Throws ConfigError.
ExperimentConfig parse_experiment(const std::string& text, const std::string& source);
/// Reads and parses an experiment file. Throws ConfigError (also for an unreadable file).
ExperimentConfig load_experiment(const std::filesystem::path& path);

}  // namespace gjklab::experiment
