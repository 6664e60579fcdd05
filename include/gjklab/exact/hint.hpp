// What a floating-point query tells the exact oracle: index sets into the two clouds, never a
// GJK type. A hint is only a suggestion. The oracle verifies it in exact arithmetic, and a
// hint that cannot be verified (wrong indices, a perturbed simplex, a face that does not
// support A − B) makes it fall back to the quadratic program; it never changes an answer.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "gjklab/geometry/enum_names.hpp"

namespace gjklab::exact {

/// The point a_i − b_j of the Minkowski difference A − B, by its vertex indices in A and B.
struct IndexPair {
  std::int32_t a = -1;
  std::int32_t b = -1;
  friend bool operator==(const IndexPair&, const IndexPair&) = default;
};

/// A distance (or intersection) hint: the final simplex of a GJK run, up to four points of
/// A − B whose hull holds, or nearly holds, the point of A − B closest to the origin.
struct DistanceHint {
  std::vector<IndexPair> simplex;
};

/// A penetration-depth hint: the final polytope of an EPA run. Its vertices are points of
/// A − B; each face lists three vertex indices (into `vertices`), counter-clockwise seen from
/// outside. The polytope must be closed and convex for the certificate to apply.
struct DepthHint {
  std::vector<IndexPair> vertices;
  std::vector<std::array<int, 3>> faces;
};

/// How the oracle obtained an answer.
enum class AnswerMethod : std::uint8_t {
  certified,  ///< a floating-point hint, verified by an exact certificate
  qp,         ///< the exact quadratic program (CGAL), or the exact Minkowski hull for depth
  none,       ///< not computed (a depth that was not asked for, or of a separated pair)
  /// the exact truth of two closed meshes (exact/mesh_truth.hpp): exact triangle tests and
  /// distances, culled by proven bounds
  mesh_truth,
};

inline constexpr auto kAnswerMethodNames = std::to_array<EnumName<AnswerMethod>>({
    {AnswerMethod::certified, "certified"},
    {AnswerMethod::qp, "qp"},
    {AnswerMethod::none, "none"},
    {AnswerMethod::mesh_truth, "mesh_truth"},
});
static_assert(in_value_order(kAnswerMethodNames) &&
              ends_at(kAnswerMethodNames, AnswerMethod::mesh_truth));

constexpr std::string_view to_string(AnswerMethod m) {
  return name_of(kAnswerMethodNames, m);
}

}  // namespace gjklab::exact
