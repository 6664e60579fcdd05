// An exact convex decomposition of a closed triangle mesh: convex pieces whose union is proven,
// in exact rational arithmetic, to be the solid the mesh bounds (CGAL's Nef polyhedra and
// convex_decomposition_3, behind this interface).
//
// The decomposition cuts the solid along planes through its reflex edges, so a piece's corners
// are rationals that are in general not doubles. The proof is made on those exact pieces:
//  1. each piece is convex: the solid it bounds has the same exact volume as the convex hull of
//     its corners, and lies in that hull, so the two are equal;
//  2. the union of the pieces (Nef polyhedra, exact Boolean operations) equals the solid.
// The queries then see each piece as the convex hull of its corners rounded to the nearest
// double: max_rounding bounds how far that moves any corner, so a query on the rounded pieces
// answers for a set within max_rounding of the solid (Hausdorff distance, length units).
// Nothing is returned without the proof: a mesh the decomposition fails on, or whose proof
// fails, is an error that says which step failed.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::exact {

/// Largest mesh accepted, in faces. The cost grows with the reflex edges: a 1 050-face anchor
/// (CGAL's data) decomposes into 481 pieces in about 11 s, and its proof takes 25 s more; a
/// 5 800-face cow does not finish within minutes.
inline constexpr std::size_t kMaxDecompositionFaces = 2'000;

struct ExactConvexDecomposition {
  /// Each piece's corners (the extreme points of its convex hull), rounded to the nearest double,
  /// in the mesh's frame; corners and pieces sorted lexicographically by coordinates, so that the
  /// same mesh gives the same list in every process.
  std::vector<std::vector<Vec3>> pieces;
  /// The largest Euclidean distance from an exact corner to its rounded double, rounded up
  /// (absolute, length units); 0 when every corner is a double (e.g. a convex mesh, one piece).
  double max_rounding = 0;
};

/// Why the exact decomposition of a mesh could not be had: too large, CGAL failed on it, or the
/// proof of the pieces failed (a CGAL defect: the pieces are then not returned).
class DecompositionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The proven decomposition of a closed mesh (closed, oriented, not self-intersecting: what
/// validate_closed_mesh checks; not checked again here). `source` names the mesh in errors.
/// Throws DecompositionError.
ExactConvexDecomposition exact_convex_decomposition(const TriangleMesh& mesh,
                                                    std::string_view source);

}  // namespace gjklab::exact
