// The Voronoi-region distance sub-algorithm: the closest point of a segment, triangle or
// tetrahedron to the origin by testing the Voronoi regions of its vertices, edges and faces
// (Ericson, Real-Time Collision Detection, 2005, sections 5.1.2, 5.1.5 and 5.1.6, with the
// query point at the origin).
//
// - segment: t = (−a)·(b − a) / ‖b − a‖², clamped to [0, 1].
// - triangle (ClosestPtPointTriangle): the vertex regions, then the edge regions, then the
//   face, decided from the six dot products d1…d6 of the edges with the vectors to the origin
//   and the barycentric numerators va, vb, vc (Lagrange's identity).
// - tetrahedron (ClosestPtPointTetrahedron): every face whose plane has the origin and the
//   opposite vertex strictly on opposite sides is solved as a triangle and the closest answer
//   wins; if there is none, the origin is inside (weights from the signed volumes).
//
// Our additions for degenerate input: a flat tetrahedron (the opposite vertex on a face's
// plane) tests all four faces, since its hull is the union of its faces; a triangle that
// reaches the face case with va + vb + vc ≤ 0 (collinear, or rounding noise) is solved as its
// three edges; and points whose weight comes out exactly 0 are dropped from the kept
// sub-simplex (they do not contribute to the closest point).
#pragma once

#include <array>

#include "gjklab/gjk/subsimplex.hpp"

namespace gjklab {

/// The point of conv(y[0 … count−1]) (count in 1…4) closest to the origin by Voronoi regions.
/// Always found.
/// Defined for T = float, double and long double.
template <class T>
SubsimplexSolutionT<T> voronoi_closest_point(const std::array<Vec3T<T>, 4>& y, int count);

}  // namespace gjklab
