// A convex algorithm on a non-convex pair: the registered algorithm run over pairs of convex
// pieces (one of A's, one of B's), the answer being the union's: the pair intersects when some
// pair of pieces does, and its distance is the least over the pairs of pieces.
//
// Not every pair is run. Each piece's axis-aligned box gives a lower bound on its distance to
// the other's pieces; the pairs are run in order of that bound, the overlapping boxes first, and
// the search stops at the first intersecting pair, or (for distance algorithms) once the next
// bound exceeds the least distance found. Boolean algorithms run only the pairs whose boxes
// overlap: a pair with apart boxes cannot intersect.
#pragma once

#include <cstdint>
#include <span>

#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/polytope.hpp"

namespace gjklab::experiment {

struct PieceOutcome {
  /// The union's answer. intersect and distance as above; the witnesses, the exact answer (for
  /// `exact`) and the distance bracket's upper end are the deciding pair's; the bracket's lower
  /// end is the least over the pairs run (the pairs not run are farther apart than the answer);
  /// iterations and support calls are summed over the pairs run; termination is converged when
  /// every pair run converged, else the first other termination met. Penetration depths are
  /// not reported: the deepest pair of pieces says nothing of the solids' depth.
  Outcome outcome;
  std::uint64_t piece_pairs = 0;         ///< |pieces of A| × |pieces of B|
  std::uint64_t piece_pairs_tested = 0;  ///< the pairs the algorithm was run on
  /// The deciding pair of pieces: the intersecting one, or the nearest one run (−1: none run).
  std::int64_t piece_a = -1, piece_b = -1;
};

/// Runs the algorithm over the pairs of pieces, as above, in double on the pieces as given
/// (polytopes, no radii). Throws what run_algorithm throws; std::invalid_argument for an empty
/// list of pieces.
PieceOutcome run_on_pieces(const AlgorithmInfo& algorithm, std::span<const Polytope> a,
                           std::span<const Polytope> b, const AlgorithmOptions& options);

}  // namespace gjklab::experiment
