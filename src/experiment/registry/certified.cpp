#include "gjklab/experiment/registry/certified.hpp"

#include "gjklab/gjk/epa.hpp"
#include "gjklab/gjk/gjk_distance.hpp"

namespace gjklab::experiment {

namespace {

exact::IndexPair index_pair(const SimplexVertex& v) {
  return {v.index_a, v.index_b};
}

exact::DistanceHint distance_hint(const DistanceResult& gjk) {
  exact::DistanceHint hint;
  for (const SimplexVertex& v : gjk.simplex.vertices())
    hint.simplex.push_back(index_pair(v));
  return hint;
}

/// EPA's final polytope: its vertices (every support point it took) and its live faces.
exact::DepthHint depth_hint(const EpaPolytope& ws) {
  exact::DepthHint hint;
  hint.vertices.reserve(ws.vertices.size());
  for (const SimplexVertex& v : ws.vertices)
    hint.vertices.push_back(index_pair(v));
  for (const EpaPolytope::Face& f : ws.faces)
    if (f.alive) hint.faces.push_back(f.v);
  return hint;
}

}  // namespace

CertifiedAnswer solve_certified(const Polytope& a, const Polytope& b, const SweptRadii& radii,
                                const exact::OracleOptions& options) {
  CertifiedAnswer out;
  exact::OracleHints hints;
  if (options.certificates) {
    const DistanceResult gjk = gjk_distance(a, b);
    out.iterations = gjk.iterations;
    out.support_calls = gjk.support_calls;
    hints.distance = distance_hint(gjk);
    if (options.depth && gjk.intersect) {
      thread_local EpaPolytope workspace;  // buffers reused across queries on this thread
      const EpaResult epa = epa_from_gjk(a, b, gjk, EpaOptions{}, workspace);
      out.iterations += epa.iterations;
      out.support_calls = epa.support_calls;  // counts GJK's too
      out.epa_normal = epa.normal;
      if (epa.faces > 0) hints.depth = depth_hint(workspace);
    }
  }
  out.answer = exact::solve_swept(a.vertices(), b.vertices(), radii.a, radii.b, options, hints);
  return out;
}

}  // namespace gjklab::experiment
