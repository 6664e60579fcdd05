// The sub-simplex solve of the GJK distance queries in double-word arithmetic, for the
// simplices whose solve in the query's own precision loses the answer: needle triangles,
// nearly parallel segments, flat tetrahedra.
//
// On such a simplex the quantities every sub-algorithm decides by (Johnson's cofactors, signed
// volumes and areas, Voronoi-region dot products) are small differences of products of the
// points' coordinates: two segments of length 1 at an angle of 1e-9 make a triangle of
// A − B whose squared area is about 1e-18 while each product in it is about 1, so in double
// (unit roundoff 1.1e-16) the sign and size of every cofactor are noise. The same recursion in
// double-word arithmetic (about 106 bits, geometry/double_word.hpp) on the same points resolves
// it: the squared area carries a relative error near 1e-14.
//
// The rule is Johnson's (johnson.hpp): the first subset X, by size then mask, with Δ(X) > 0,
// Δ_i(X) > 0 for i ∈ X and Δ_j(X ∪ {y_j}) ≤ 0 for j ∉ X; where rounding still leaves no subset
// passing, van den Bergen's backup (the subset with positive cofactors whose affine closest
// point is nearest). In exact arithmetic every sub-algorithm's answer is this one point (the
// point of a convex set closest to the origin is unique), so the GJK driver uses this solve
// for whichever sub-algorithm ran when its own answer could not be proven (gjk_distance.hpp).
// The points are scaled by a power of two first (exact, barring underflow), so that the
// degree-6 cofactors of any pair scale neither overflow nor underflow.
#pragma once

#include <array>

#include "gjklab/gjk/subsimplex.hpp"

namespace gjklab {

/// The point of conv(y[0 … count−1]) (count in 1…4) closest to the origin, with Johnson's
/// rule evaluated in double-word arithmetic (see the file comment): weights and the closest
/// point rounded to T from their double-word values. Not found only for non-finite points or
/// points whose scale the double-word cofactors cannot hold (coordinates beyond about 2^±150
/// after scaling, i.e. a simplex whose extent is below 2^-150 of its largest coordinate).
/// Defined for T = float, double and long double.
template <class T>
SubsimplexSolutionT<T> precise_closest_point(const std::array<Vec3T<T>, 4>& y, int count);

}  // namespace gjklab
