#include "gjklab/experiment/registry/answer_fields.hpp"

namespace gjklab::experiment {

namespace {

void add_exact(const exact::OracleAnswer& e, AnswerFields& f) {
  // For sphere-swept shapes the exact rationals are the cores' (the swept answers are
  // irrational in general), and their keys say so.
  const std::string prefix = e.swept ? "core_" : "";
  f.emplace_back(prefix + "distance2_num", e.distance_squared.numerator());
  f.emplace_back(prefix + "distance2_den", e.distance_squared.denominator());
  f.emplace_back("method", std::string(to_string(e.method)));
  if (e.hull_vertices_a >= 0) {
    f.emplace_back("hull_vertices_a", std::int64_t{e.hull_vertices_a});
    f.emplace_back("hull_vertices_b", std::int64_t{e.hull_vertices_b});
  }
  if (e.depth_squared) {
    f.emplace_back(prefix + "depth2_num", e.depth_squared->numerator());
    f.emplace_back(prefix + "depth2_den", e.depth_squared->denominator());
    f.emplace_back("depth_method", std::string(to_string(e.depth_method)));
  }
}

}  // namespace

AnswerFields answer_fields(std::string_view algorithm, const Outcome& o,
                           ScalarPrecision precision, double radius_a, double radius_b) {
  AnswerFields f;
  f.emplace_back("algorithm", std::string(algorithm));
  if (precision != ScalarPrecision::double_float)
    f.emplace_back("precision", std::string(to_string(precision)));
  if (radius_a != 0 || radius_b != 0) {
    f.emplace_back("radius_a", radius_a);
    f.emplace_back("radius_b", radius_b);
  }
  f.emplace_back("intersect", o.intersect);
  if (o.distance) f.emplace_back("distance", *o.distance);
  if (o.depth) f.emplace_back("depth", *o.depth);
  if (o.normal) f.emplace_back("normal", *o.normal);
  if (o.witness_a && o.witness_b) {
    f.emplace_back("witness_a", *o.witness_a);
    f.emplace_back("witness_b", *o.witness_b);
  }
  // The proven bracket of the distance (absent where nothing proved a bound).
  if (o.lower_bound) f.emplace_back("lower_bound", *o.lower_bound);
  if (o.upper_bound) f.emplace_back("upper_bound", *o.upper_bound);
  f.emplace_back("iterations", std::int64_t{o.iterations});
  f.emplace_back("support_calls", std::int64_t{o.support_calls});
  f.emplace_back("termination", std::string(to_string(o.termination)));
  if (o.exact) add_exact(*o.exact, f);
  return f;
}

}  // namespace gjklab::experiment
