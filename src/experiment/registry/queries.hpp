// The queries the registry's entries are made from (private to src/experiment/registry): the
// answers converted to Outcome, the GJK queries in float and long double, and the shapes
// prepared once per polytope for the peers. Included by algorithms.cpp alone.
#pragma once

#include <memory>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>

#include "gjklab/exact/hull_features.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/registry/certified.hpp"
#include "gjklab/geometry/scalar_cloud.hpp"
#include "gjklab/gjk/epa.hpp"
#include "gjklab/gjk/gjk_boolean.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/gjk_nesterov.hpp"
#include "gjklab/gjk/subalgorithms.hpp"
#include "gjklab/peers/libccd.hpp"
#include "gjklab/peers/sat.hpp"
#ifdef GJKLAB_HAVE_FCL
#include "gjklab/peers/fcl.hpp"
#endif
#ifdef GJKLAB_HAVE_BULLET
#include "gjklab/peers/bullet.hpp"
#endif

namespace gjklab::experiment::registry_parts {

/// A penetration answer: distance and closest points for separated pairs, depth and normal
/// (and the deepest points, when the algorithm reports them) for intersecting ones.
inline Outcome from_penetration(const PenetrationResult& r, bool deepest_points) {
  Outcome o;
  o.intersect = r.intersect;
  o.distance = r.intersect ? 0.0 : r.distance;
  if (r.intersect) {
    o.depth = r.depth;
    o.normal = r.normal;
  }
  if (!r.intersect || deepest_points) {
    o.witness_a = r.witness_a;
    o.witness_b = r.witness_b;
  }
  o.iterations = r.iterations;
  o.support_calls = r.support_calls;
  o.termination = r.termination;
  return o;
}

/// A peer's depth answer (libccd's penetration queries, SAT): the boolean, and the depth and
/// normal where it says intersecting; no distance. `iterations` as the peer counts them.
template <class DepthResult>
Outcome from_depth_answer(const DepthResult& r, int iterations) {
  Outcome o;
  o.intersect = r.intersect;
  if (r.intersect) {
    o.depth = r.depth;
    o.normal = r.normal;
  }
  o.iterations = iterations;
  o.support_calls = r.support_calls;
  o.termination = r.termination;
  return o;
}

// Shapes prepared for an algorithm (exact hull features, a library's own shape object) are
// built once per polytope and thread and reused, keyed by Polytope::id(): a query on the same
// polytope (or a copy) finds its preparation in constant time, so a benchmark that cycles over
// many shapes times the queries and not the preparation. The experiment driver runs every
// algorithm once before timing it. The cache forgets everything when it reaches kEntries, which
// bounds its memory in long runs (each case brings new polytopes).
template <class Prepared, class Make>
std::shared_ptr<const Prepared> prepared(const Polytope& shape, Make&& make) {
  constexpr std::size_t kEntries = 1024;
  thread_local std::unordered_map<std::uint64_t, std::shared_ptr<const Prepared>> cache;
  if (const auto found = cache.find(shape.id()); found != cache.end()) return found->second;
  if (cache.size() >= kEntries) cache.clear();
  auto made = make(shape);
  cache.emplace(shape.id(), made);
  return made;
}

/// The exact hull features of a cloud (shared by SAT and FCL).
inline std::shared_ptr<const exact::HullFeatures> hull_of(const Polytope& shape) {
  return prepared<exact::HullFeatures>(shape, [](const Polytope& p) {
    return std::make_shared<const exact::HullFeatures>(exact::hull_features(p.vertices()));
  });
}

inline std::shared_ptr<const peers::SatShape> sat_shape(const Polytope& shape) {
  return prepared<peers::SatShape>(shape, [](const Polytope& p) {
    return std::make_shared<const peers::SatShape>(*hull_of(p));
  });
}

#ifdef GJKLAB_HAVE_FCL
inline std::shared_ptr<const peers::FclShape> fcl_shape(const Polytope& shape) {
  return prepared<peers::FclShape>(shape, [](const Polytope& p) {
    return std::make_shared<const peers::FclShape>(*hull_of(p));
  });
}
#endif

#ifdef GJKLAB_HAVE_BULLET
inline std::shared_ptr<const peers::BulletShape> bullet_shape(const Polytope& shape) {
  return prepared<peers::BulletShape>(
      shape, [](const Polytope& p) { return std::make_shared<const peers::BulletShape>(p); });
}
#endif

/// The oracle options of `gjk-certified`: a depth where one is asked (o.oracle.depth, as for
/// `exact`), certificates on, no hull counts.
inline exact::OracleOptions certified_query_options(const AlgorithmOptions& o) {
  exact::OracleOptions options = o.oracle;
  options.certificates = true;
  options.hull_vertices = false;
  return options;
}

/// A libccd adapter: the two polytopes, the options and the radii it sweeps them by; it answers
/// a boolean (BooleanResult) or a penetration (LibccdPenetration).
template <class Result>
using LibccdQuery = Result (*)(const Polytope&, const Polytope&, const peers::LibccdOptions&,
                               const SweptRadii&);

/// Whether the adapter answers a penetration (with a depth) rather than a boolean.
template <class Result>
constexpr bool reports_depth(LibccdQuery<Result>) {
  return std::is_same_v<Result, peers::LibccdPenetration>;
}

// ---- the GJK queries in float and long double (AlgorithmOptions::precision) ---------------
//
// The same queries, run on the clouds rounded to T (ScalarCloud<T>); their answers are
// converted to double for the records. Sphere-swept shapes: the radii are rounded to T too; the
// distance variants and epa shift the cores' answer by them in double (gjk/swept.hpp), the
// boolean walks the swept support map in T.

/// A distance variant as a type whose query takes shapes of any precision, traced or not: the
/// one core query from which the registry makes its plain, traced, sphere-swept,
/// other-precision and benchmark forms (swept shapes: the query runs on the cores and its
/// answer is shifted by the radii, see gjk/swept.hpp).
template <class Sub>
struct SubAlgorithmQuery {
  template <class S, class Observer>
  static auto run(const S& a, const S& b, const AlgorithmOptions& o, Observer&& observer) {
    return gjk_distance_with<Sub>(a, b, o.gjk_distance, observer);
  }
};
struct NesterovQuery {
  template <class S, class Observer>
  static auto run(const S& a, const S& b, const AlgorithmOptions& o, Observer&& observer) {
    return gjk_nesterov(a, b, o.gjk_nesterov, observer);
  }
};
struct PolyakQuery {
  template <class S, class Observer>
  static auto run(const S& a, const S& b, const AlgorithmOptions& o, Observer&& observer) {
    return gjk_polyak(a, b, o.gjk_distance, observer);
  }
};

template <class Prepared, class Make>
std::shared_ptr<const Prepared> prepared(const Polytope& shape, Make&& make);

/// The cloud rounded to T, made once per polytope and thread (see prepared() below), so that
/// repeated and timed queries on a shape do not pay for the conversion.
template <class T>
std::shared_ptr<const ScalarCloud<T>> rounded(const Polytope& shape) {
  return prepared<ScalarCloud<T>>(shape, [](const Polytope& p) {
    return std::make_shared<const ScalarCloud<T>>(p.vertices());
  });
}

/// The radii rounded to T (and back to double, exactly).
template <class T>
SweptRadii rounded_radii(const SweptRadii& r) {
  return {static_cast<double>(static_cast<T>(r.a)), static_cast<double>(static_cast<T>(r.b))};
}

template <class Query, class T>
Outcome distance_in(const Polytope& a, const Polytope& b, const SweptRadii& r,
                    const AlgorithmOptions& o, TraceRecorder* trace) {
  const auto pa = rounded<T>(a), pb = rounded<T>(b);
  const ScalarCloud<T>&ca = *pa, &cb = *pb;
  DistanceResult d = trace ? to_double(Query::run(ca, cb, o, *trace))
                           : to_double(Query::run(ca, cb, o, NoTrace{}));
  if (r.any()) d = swept_distance(d, rounded_radii<T>(r));
  return from_distance(d);
}

template <class T>
Outcome gjk_bool_in(const Polytope& a, const Polytope& b, const SweptRadii& r,
                    const AlgorithmOptions& o, TraceRecorder* trace) {
  const auto pa = rounded<T>(a), pb = rounded<T>(b);
  const ScalarCloud<T>&ca = *pa, &cb = *pb;
  auto query = [&](const auto& sa, const auto& sb) {
    return trace ? gjk_intersect(sa, sb, o.gjk_boolean, *trace)
                 : gjk_intersect(sa, sb, o.gjk_boolean);
  };
  if (!r.any()) return from_boolean(query(ca, cb));
  using Swept = SphereSwept<ScalarCloud<T>>;
  return from_boolean(query(Swept(ca, static_cast<T>(r.a)), Swept(cb, static_cast<T>(r.b))));
}

template <class T>
Outcome epa_in(const Polytope& a, const Polytope& b, const SweptRadii& r, const AlgorithmOptions& o,
               TraceRecorder*) {
  thread_local EpaPolytopeT<T> workspace;  // buffers reused across queries on this thread
  const auto pa = rounded<T>(a), pb = rounded<T>(b);
  const ScalarCloud<T>&ca = *pa, &cb = *pb;
  const EpaResult core = to_double(gjk_epa(ca, cb, o.gjk_distance, o.epa, workspace));
  Outcome out =
      from_penetration(r.any() ? swept_penetration(core, rounded_radii<T>(r)) : core, true);
  out.iterations = core.gjk_iterations + core.iterations;  // GJK's, then EPA's
  return out;
}

/// A request in float or long double: Run<float> or Run<long double> by options.precision,
/// on the clouds rounded to it.
template <template <class> class Run>
Outcome at_precision(const QueryRequest& q) {
  switch (q.options.precision) {
    case ScalarPrecision::single_float:
      return Run<float>::run(q.a, q.b, q.radii, q.options, q.trace);
    case ScalarPrecision::long_double:
      return Run<long double>::run(q.a, q.b, q.radii, q.options, q.trace);
    case ScalarPrecision::double_float:
      break;
  }
  throw std::logic_error("at_precision called for double");
}
template <class Query>
struct DistanceIn {
  template <class T>
  struct At {
    static Outcome run(const Polytope& a, const Polytope& b, const SweptRadii& r,
                       const AlgorithmOptions& o, TraceRecorder* trace) {
      return distance_in<Query, T>(a, b, r, o, trace);
    }
  };
};
template <class T>
struct GjkBoolIn {
  static Outcome run(const Polytope& a, const Polytope& b, const SweptRadii& r,
                     const AlgorithmOptions& o, TraceRecorder* trace) {
    return gjk_bool_in<T>(a, b, r, o, trace);
  }
};
template <class T>
struct EpaIn {
  static Outcome run(const Polytope& a, const Polytope& b, const SweptRadii& r,
                     const AlgorithmOptions& o, TraceRecorder* trace) {
    return epa_in<T>(a, b, r, o, trace);
  }
};

}  // namespace gjklab::experiment::registry_parts
