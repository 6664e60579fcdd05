// libccd as a peer: its GJK and MPR intersection tests run on gjklab's own shapes.
//
// libccd reports an int and no iteration count, and its MPR loop has no iteration bound of its
// own; this adapter counts support calls, enforces max_iterations for both, and maps the
// outcome to gjklab's Termination vocabulary.
#pragma once

#include <string>

#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/result.hpp"

namespace gjklab::peers {

struct LibccdDefaults {
  static constexpr int max_iterations = 64;
};

struct LibccdOptions {
  /// Bound on libccd's main loop. libccd's own default is unbounded ((unsigned long)-1).
  int max_iterations = LibccdDefaults::max_iterations;
  /// libccd's epa/mpr tolerance (absolute, length units); libccd's default is 1e-4.
  double mpr_tolerance = 1e-4;
};

/// libccd's ccdGJKIntersect on the two polytopes (both in world coordinates).
BooleanResult libccd_gjk_intersect(const Polytope& a, const Polytope& b,
                                   const LibccdOptions& options = {});
/// libccd's ccdMPRIntersect on the two polytopes (both in world coordinates).
BooleanResult libccd_mpr_intersect(const Polytope& a, const Polytope& b,
                                   const LibccdOptions& options = {});

/// Version of libccd the adapter was built with (for provenance).
std::string libccd_version();

}  // namespace gjklab::peers
