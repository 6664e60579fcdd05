#include "gjklab/experiment/run/judging.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gjklab/exact/witness.hpp"

namespace gjklab::experiment {

ContactClass contact_class(const exact::OracleAnswer& answer, double band) {
  if (!answer.intersect)
    return answer.distance <= band ? ContactClass::touching_band : ContactClass::separated;
  if (answer.depth && *answer.depth <= band) return ContactClass::touching_band;
  return ContactClass::intersecting;
}

ExactRecord exact_record(const exact::OracleAnswer& a, double band) {
  ExactRecord r;
  r.intersect = a.intersect;
  r.distance = a.distance;
  r.distance2_num = a.distance_squared.numerator();
  r.distance2_den = a.distance_squared.denominator();
  if (a.depth) r.depth = *a.depth;
  r.hull_vertices_a = a.hull_vertices_a;
  r.hull_vertices_b = a.hull_vertices_b;
  r.contact = contact_class(a, band);
  r.method = a.method;
  r.depth_method = a.depth_method;
  return r;
}

AlgorithmRecord algorithm_record(const Outcome& o) {
  AlgorithmRecord r;
  r.intersect = o.intersect;
  if (o.distance) r.distance = *o.distance;
  if (o.depth) r.depth = *o.depth;
  if (o.lower_bound) r.lower_bound = *o.lower_bound;
  if (o.upper_bound) r.upper_bound = *o.upper_bound;
  r.iterations = o.iterations;
  r.support_calls = o.support_calls;
  r.termination = o.termination;
  return r;
}

void judge(AlgorithmRecord& r, const Outcome& o, const ExactRecord& exact, double size) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  r.abs_error = o.distance ? std::abs(*o.distance - exact.distance) : kNaN;
  r.rel_error = r.abs_error / size;
  r.boolean_correct =
      exact.contact == ContactClass::touching_band || o.intersect == exact.intersect;
  const bool depths = o.depth && o.intersect && exact.intersect && !std::isnan(exact.depth);
  r.depth_abs_error = depths ? std::abs(*o.depth - exact.depth) : kNaN;
  r.depth_rel_error = r.depth_abs_error / size;
}

void add_witnesses(AlgorithmRecord& r, const Outcome& o, const exact::OracleAnswer* exact,
                   std::span<const Vec3> a, std::span<const Vec3> b) {
  if (!o.witness_a || !o.witness_b) return;
  r.witness_a = *o.witness_a;
  r.witness_b = *o.witness_b;
  if (!exact || exact->swept || !r.witness_a.allFinite() || !r.witness_b.allFinite()) return;
  r.witness_error_a = exact::distance_to_hull(a, r.witness_a);
  r.witness_error_b = exact::distance_to_hull(b, r.witness_b);
  if (!o.intersect)
    r.witness_distance_error =
        exact::distance_difference(r.witness_a, r.witness_b, exact->distance_squared);
}

bool needs_exact_depth(const exact::OracleAnswer& answer,
                       std::span<const AlgorithmRecord> records) {
  if (!answer.intersect || answer.depth) return false;
  return std::any_of(records.begin(), records.end(), [](const AlgorithmRecord& r) {
    return !r.intersect && r.termination != Termination::step_limit;
  });
}

bool worth_keeping(const CaseResult& r, double relative_band) {
  for (const AlgorithmRecord& a : r.algorithms) {
    if (!a.boolean_correct || a.termination != Termination::converged) return true;
    if (!std::isnan(a.rel_error) && a.rel_error > relative_band) return true;
  }
  return false;
}

}  // namespace gjklab::experiment
