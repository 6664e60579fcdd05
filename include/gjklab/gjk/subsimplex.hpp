// The answer of a distance sub-algorithm on one simplex, shared by the sub-algorithms that
// are not Johnson's (signed volumes, Voronoi regions).
#pragma once

#include <array>
#include <cstdint>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// The sub-simplex whose convex hull holds the point of a simplex closest to the origin.
template <class T>
struct SubsimplexSolutionT {
  bool found = false;                   ///< false when the sub-algorithm could not decide
  std::uint8_t subset = 0;              ///< bitmask of the kept points (bit i ↔ y_i)
  std::array<T, 4> weights{};           ///< barycentric weights λ_i of the kept points; 0 outside
  Vec3T<T> closest = Vec3T<T>::Zero();  ///< v = Σ λ_i y_i
};
using SubsimplexSolution = SubsimplexSolutionT<double>;

}  // namespace gjklab
