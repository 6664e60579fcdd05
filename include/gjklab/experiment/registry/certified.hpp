// The exact oracle fed by gjklab's own floating-point queries: GJK's final simplex and EPA's
// final polytope become the hints that the certificates verify (exact/certificate.hpp), and
// the QP answers only what they cannot prove. Used by the experiment driver's oracle, by the
// registry's `exact` and by `gjk-certified`.
#pragma once

#include <optional>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/swept.hpp"

namespace gjklab::experiment {

/// An exact answer and the cost of the floating-point queries that hinted it.
struct CertifiedAnswer {
  exact::OracleAnswer answer;
  int iterations = 0;     ///< GJK's iterations, plus EPA's when it ran
  int support_calls = 0;  ///< both queries' support calls
  /// EPA's unit normal for an intersecting pair when EPA ran (the certified normal, when the
  /// depth was certified, is answer.depth_normal).
  std::optional<Vec3> epa_normal;
};

/// Runs gjk-johnson (default options) on the pair's cores and, when options.depth is set and
/// GJK finds contact, EPA; then the oracle with their final simplex and polytope as hints.
/// Every answer is exact whatever the hints (see exact::solve).
CertifiedAnswer solve_certified(const Polytope& a, const Polytope& b, const SweptRadii& radii,
                                const exact::OracleOptions& options);

}  // namespace gjklab::experiment
