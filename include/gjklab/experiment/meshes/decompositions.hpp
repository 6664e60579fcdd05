// Convex decompositions of closed meshes, by name: what a convex algorithm sees of a non-convex
// solid. Experiment files, `gjklab query --decomposition` and Python select them by these
// names; adding one is one entry in src/experiment/meshes/decompositions.cpp.
//
//  - `hull`: one piece, the convex hull of the mesh's vertices (the classic demo's choice). It
//    covers the solid and more: its false positives are what the non-convex study counts.
//  - `exact`: CGAL's convex decomposition with the proof that the pieces' union is the solid
//    (exact/convex_decomposition.hpp); the pieces' corners are rounded to doubles, which moves
//    them by at most max_rounding.
//  - `approximate`: what engines ship, Bullet's HACD (peers/hacd.hpp; listed when it was found
//    at build time, as the FCL and Bullet peers are). Nothing proves it covers the solid, nor
//    that it lies inside it.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/geometry/types.hpp"
#include "gjklab/peers/hacd.hpp"

namespace gjklab::experiment {

/// The options of every decomposition that takes any.
struct DecompositionOptions {
  peers::HacdOptions hacd;  ///< `approximate`
};

/// A mesh's convex pieces, each the convex hull of its corners (mesh frame, doubles).
struct Decomposition {
  std::string method;  ///< the decomposition's name
  std::vector<std::vector<Vec3>> pieces;
  /// The union of the exact pieces is proven equal to the solid (only `exact`).
  bool proven = false;
  /// How far rounding moved a piece's corner (absolute, length units; `exact` only, else 0).
  double max_rounding = 0;
};

/// One option of a decomposition, as data: its key, what it means (with its unit), and the
/// member it sets.
struct DecompositionOptionRow {
  std::string_view key;
  std::string_view meaning;
  std::variant<int peers::HacdOptions::*, double peers::HacdOptions::*, bool peers::HacdOptions::*>
      member;
};

struct DecompositionInfo {
  std::string_view name;
  std::string_view description;
  /// The options it takes (none for hull and exact).
  std::span<const DecompositionOptionRow> options;
  /// Decomposes a validated closed mesh; `source` names it in errors. Throws std::runtime_error
  /// (exact::DecompositionError for `exact`) when it cannot.
  Decomposition (*decompose)(const TriangleMesh& mesh, std::string_view source,
                             const DecompositionOptions& options);
};

/// Every decomposition built into this binary, in a fixed order.
std::span<const DecompositionInfo> decompositions();
/// The decomposition of that name; throws std::invalid_argument listing the valid names.
const DecompositionInfo& decomposition_named(std::string_view name);
/// The valid names, comma-separated.
std::string decomposition_names();

/// Sets the option `key` of decomposition `d` from its text (an integer, a finite number, or
/// true/false), then checks the options' ranges. Throws std::invalid_argument naming the key:
/// unknown to `d` (listing its keys), unreadable, or out of range.
void set_decomposition_option(const DecompositionInfo& d, DecompositionOptions& options,
                              std::string_view key, std::string_view value);

/// The decomposition's name ("decomposition") and each of its options' values
/// ("decomposition.KEY"), as an archive's algorithm group records them.
std::vector<std::pair<std::string, std::string>> describe_decomposition(
    const DecompositionInfo& d, const DecompositionOptions& options);

/// The pieces as polytopes, for the queries.
std::vector<Polytope> piece_polytopes(const Decomposition& d);

}  // namespace gjklab::experiment
