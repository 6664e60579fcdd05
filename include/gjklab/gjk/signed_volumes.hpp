// The signed-volumes distance sub-algorithm (Montanari, Petrinic and Barbieri 2017, "Improving
// the GJK algorithm for faster and more reliable distance queries between convex objects",
// ACM Trans. Graph. 36(3), section 4).
//
// Instead of Johnson's cofactor recursion over all subsets, it decides from signed volumes
// whether the origin's projection onto the affine hull of the simplex lies inside the simplex,
// and otherwise descends to the faces (or edges) that the origin lies beyond:
//
// - tetrahedron (S3D): M = [y_0 y_1 y_2 y_3; 1 1 1 1]; the cofactors C_j of the last row are
//   the signed volumes of the tetrahedra with y_j replaced by the origin, det M = Σ C_j. If
//   every C_j has the sign of det M the origin is inside: λ_j = C_j / det M. Otherwise S2D runs
//   on the face opposite each y_j whose C_j does not have that sign, and the closest of the
//   face answers wins.
// - triangle (S2D): the origin is projected onto the triangle's plane (p_0 = (y_0·n/‖n‖²) n,
//   n = (y_1 − y_0) × (y_2 − y_0)); the triangle and p_0 are projected onto the coordinate
//   plane where the triangle's signed area μ is largest in magnitude (the projection that loses
//   the least precision), and the signed areas C_j of the triangles with y_j replaced by p_0 are
//   compared with μ_max the same way, descending to edges (S1D).
// - segment (S1D): the same on the coordinate axis where the segment is longest.
//
// Signs are compared strictly ("compareSigns": both > 0 or both < 0), so a zero or NaN volume
// never passes. Our additions, for a sub-algorithm that must answer any simplex (the paper's
// versions assume y_0 is the newest point and skip the sub-simplices without it, which GJK's
// invariants allow): every failing face or edge is searched, not only those holding the newest
// point; S1D keeps whichever endpoint is nearer when the projection falls outside; and a
// degenerate simplex (det M = 0, μ_max = 0, or coincident segment ends) falls through to its
// faces, edges or first point, so the answer always exists.
//
// As in the paper, the areas and volumes are evaluated from the raw coordinates, so their
// rounding grows with ‖y‖² rather than with the simplex's extent. On pairs far apart compared
// with their size, or on finely tessellated curved shapes, gjk-sv's distances carry errors of
// up to a few 1e-14 of the pair's size (1.7e-13 on one of the property test's 2000 pairs)
// where Johnson's sub-algorithm, which works on differences of points, stays near 1e-15;
// in exchange it ended fewer queries on rounding (no_progress, degenerate_simplex) than the
// other sub-algorithms in experiments/studies/variants.toml.
#pragma once

#include <array>

#include "gjklab/gjk/subsimplex.hpp"

namespace gjklab {

/// The point of conv(y[0 … count−1]) (count in 1…4) closest to the origin by signed volumes.
/// Always found (a degenerate simplex reduces to its faces, edges or points).
/// Defined for T = float, double and long double.
template <class T>
SubsimplexSolutionT<T> signed_volumes_closest_point(const std::array<Vec3T<T>, 4>& y, int count);

}  // namespace gjklab
