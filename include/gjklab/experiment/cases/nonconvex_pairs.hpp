// Pairs of closed non-convex meshes for the `nonconvex` families: configurations built to expose
// what a convex stand-in gets wrong (the hull's false positives above all), each posed at random
// around its nominal placement, from clearly apart to overlapping, so that many cases are near
// contact. Every mesh is validated as a closed, oriented, self-intersection-free solid after it
// is posed (rounding the posed coordinates could in principle break that; a case that does is
// refused with its id, never queried).
//
// Lengths: every pair has size about 1 to 4 (world units, the shapes' own units times the
// family's scale).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/geometry/enum_names.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"

namespace gjklab::experiment {

struct RandomStream;

/// Which configuration a `nonconvex` family builds (`pair = "NAME"`).
enum class NonconvexPair : std::uint8_t {
  rings,        ///< two linked tori (major radius 1, minor 0.22), B upright and moved by ≤ 0.45
  peg_in_hole,  ///< a peg (radius 0.3) through a tube (hole radius 0.5), tilted and moved
  ball_in_cup,  ///< a ball (radius 0.5) in a cup (radius 1, wall 0.15), moved by ≤ 0.45
  l_in_l,       ///< an L prism in the notch of another L turned by a half turn
  stars,        ///< two star-shaped non-convex meshes (radii 0.45–1), centres 0.9–1.9 apart
  nested,       ///< a small star (size 0.3) inside a ball of radius 1, or through its surface
  /// a cube (side 0.5) in an L prism's notch at an exact gap g from both inner walls (the
  /// distance is g to rounding of 1 + g; |g| log-uniform in [1e-12, 0.25], half of the cases
  /// overlapping by |g|), axis-aligned: inside the L's hull, so the hull says "intersect"
  box_in_notch,
  meshes,  ///< two closed meshes of the family's list, turned at random, centres 0.6–1.8 apart
};

inline constexpr auto kNonconvexPairNames = std::to_array<EnumName<NonconvexPair>>({
    {NonconvexPair::rings, "rings"},
    {NonconvexPair::peg_in_hole, "peg-in-hole"},
    {NonconvexPair::ball_in_cup, "ball-in-cup"},
    {NonconvexPair::l_in_l, "l-in-l"},
    {NonconvexPair::stars, "stars"},
    {NonconvexPair::nested, "nested"},
    {NonconvexPair::box_in_notch, "box-in-notch"},
    {NonconvexPair::meshes, "meshes"},
});
static_assert(in_value_order(kNonconvexPairNames) &&
              ends_at(kNonconvexPairNames, NonconvexPair::meshes));

constexpr std::string_view to_string(NonconvexPair p) {
  return name_of(kNonconvexPairNames, p);
}
inline std::optional<NonconvexPair> nonconvex_pair_from_string(std::string_view name) {
  return value_named(kNonconvexPairNames, name);
}

/// The packaged meshes (Debian's libcgal-demo) a `pair = "meshes"` family uses when it names no
/// `path`: non-convex closed meshes whose exact decomposition is proven in seconds (a cross, a
/// five-pointed star, a tripod, a pipe, a U and a blob).
inline constexpr std::array<std::string_view, 6> kPackagedNonconvexMeshes = {
    "cross.off", "star.off", "tripod.off", "pipe.off", "u.off", "blob-closed.off"};

/// A closed mesh centred on its bounding box and scaled so that its farthest vertex is at
/// distance 1 (as the real_object family scales its hulls).
TriangleMesh unit_size(TriangleMesh mesh);

struct MeshPair {
  TriangleMesh a, b;
};

/// The pair of one case, drawn from `stream`. `meshes` (the `meshes` kind's list, unit size,
/// at least one) is unused by the other kinds. The meshes are not yet validated.
MeshPair draw_nonconvex_pair(NonconvexPair kind, std::span<const TriangleMesh> meshes,
                             RandomStream& stream);

}  // namespace gjklab::experiment
