// The FCL peers' options, apart from the adapter (fcl.hpp): they are plain numbers, declared
// whether or not FCL was built, so that the algorithm options and their schema have no
// configuration-dependent members (the registry lists the FCL algorithms only when built).
#pragma once

namespace gjklab::peers {

struct FclDefaults {
  static constexpr int max_iterations = 128;
  /// GJKSolver_indep's own defaults for its EPA.
  static constexpr int epa_max_iterations = 255;
  static constexpr int epa_max_faces = 128;
  static constexpr int epa_max_vertices = 64;
};

/// Options of the FCL peers. Tolerances are FCL's defaults (libccd solver: collision
/// tolerance eps^(7/8) ≈ 2.2e-14 as libccd's mpr_tolerance, absolute; distance tolerance
/// 1e-6, absolute; indep solver: GJK and EPA tolerances eps^(7/8), relative) and are recorded
/// in fcl_settings().
struct FclOptions {
  /// GJK iteration bound of both solvers (≥ 1); see fcl.hpp for what FCL bounds.
  int max_iterations = FclDefaults::max_iterations;
  /// fcl-indep's EPA bounds (≥ 1): iterations, faces and vertices of its polytope.
  int epa_max_iterations = FclDefaults::epa_max_iterations;
  int epa_max_faces = FclDefaults::epa_max_faces;
  int epa_max_vertices = FclDefaults::epa_max_vertices;
};

}  // namespace gjklab::peers
