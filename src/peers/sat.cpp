#include "gjklab/peers/sat.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace gjklab::peers {

SatShape::SatShape(std::span<const Vec3> cloud) : features_(exact::hull_features(cloud)) {}
SatShape::SatShape(exact::HullFeatures features) : features_(std::move(features)) {}

namespace {

struct Interval {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
};

Interval project(std::span<const Vec3> vertices, const Vec3& axis) {
  Interval r;
  for (const Vec3& v : vertices) {
    const double x = axis.dot(v);
    r.lo = std::min(r.lo, x);
    r.hi = std::max(r.hi, x);
  }
  return r;
}

/// Runs the candidate axes through the test and keeps the answer.
class Tester {
 public:
  Tester(const exact::HullFeatures& a, const exact::HullFeatures& b, const SatOptions& options)
      : a_(a), b_(b), options_(options) {}

  /// Tests one axis (any length); false when the query may stop (separated with early exit,
  /// or a non-finite value).
  bool test(const Vec3& axis_in) {
    const double length = axis_in.norm();
    if (!(length > 0)) return true;  // parallel edges: no axis
    if (!std::isfinite(length)) return fail();
    const Vec3 axis = axis_in / length;
    ++result_.axes_tested;
    const Interval pa = project(a_.vertices, axis), pb = project(b_.vertices, axis);
    const double forward = pa.hi - pb.lo;   // moving B by +forward·axis separates
    const double backward = pb.hi - pa.lo;  // moving B by −backward·axis separates
    if (!std::isfinite(forward) || !std::isfinite(backward)) return fail();
    if (forward < 0 || backward < 0) {
      const double gap = forward < 0 ? -forward : -backward;
      if (!separated_ || gap > result_.separation) {
        result_.separation = gap;
        result_.normal = forward < 0 ? axis : Vec3(-axis);
      }
      separated_ = true;
      return !options_.early_exit;
    }
    if (!separated_) {
      const double overlap = std::min(forward, backward);
      if (overlap < best_overlap_) {
        best_overlap_ = overlap;
        result_.normal = forward <= backward ? axis : Vec3(-axis);
      }
    }
    return true;
  }

  SatResult finish() {
    result_.support_calls = 2 * result_.axes_tested;
    if (result_.termination != Termination::converged) {
      result_.intersect = false;
      return result_;
    }
    result_.intersect = !separated_;
    if (separated_) {
      result_.depth = 0;
    } else {
      result_.separation = 0;
      result_.depth = result_.axes_tested > 0 ? best_overlap_ : 0.0;
    }
    return result_;
  }

 private:
  bool fail() {
    result_.termination = Termination::numerical_failure;
    return false;
  }

  const exact::HullFeatures& a_;
  const exact::HullFeatures& b_;
  const SatOptions& options_;
  SatResult result_;
  bool separated_ = false;
  double best_overlap_ = std::numeric_limits<double>::infinity();
};

/// Adds the axes A − B needs when both shapes have dimension ≤ 2 (see sat.hpp).
bool test_low_dimensional_axes(Tester& t, const exact::HullFeatures& a,
                               const exact::HullFeatures& b) {
  // Candidate plane normals of A − B.
  std::vector<Vec3> planes;
  for (const exact::HullFeatures* s : {&a, &b})
    if (s->dimension == 2) planes.push_back(s->face_normals[0]);
  if (a.dimension == 1 && b.dimension == 1) {
    const Vec3 m = a.edge_directions[0].cross(b.edge_directions[0]);
    if (m.norm() > 0) planes.push_back(m.normalized());
  }
  for (const Vec3& m : planes) {
    if (!t.test(m)) return false;
    for (const exact::HullFeatures* s : {&a, &b})
      for (const Vec3& e : s->edge_directions)
        if (!t.test(m.cross(e))) return false;
  }
  // A − B may be a segment or a point: its direction and the orthogonal part of the offset.
  const Vec3 offset = a.vertices[0] - b.vertices[0];
  if (a.dimension + b.dimension <= 2) {
    for (const exact::HullFeatures* s : {&a, &b}) {
      if (s->dimension != 1) continue;
      const Vec3& e = s->edge_directions[0];
      if (!t.test(e)) return false;
      if (!t.test(offset - offset.dot(e) * e)) return false;
      // Any axis orthogonal to the line: overlap 0 when the segment A − B passes through the
      // origin, so the depth of such a pair is 0 like the exact one.
      int least = 0;
      for (int i = 1; i < 3; ++i)
        if (std::abs(e[i]) < std::abs(e[least])) least = i;
      if (!t.test(e.cross(Vec3::Unit(least)))) return false;
    }
    if (a.dimension == 0 && b.dimension == 0 && !t.test(offset)) return false;
  }
  return true;
}

}  // namespace

SatResult sat_query(const SatShape& sa, const SatShape& sb, const SatOptions& options) {
  const exact::HullFeatures& a = sa.features();
  const exact::HullFeatures& b = sb.features();
  Tester t(a, b, options);
  auto run = [&] {
    for (const Vec3& n : a.face_normals)
      if (!t.test(n)) return;
    for (const Vec3& n : b.face_normals)
      if (!t.test(n)) return;
    for (const Vec3& ea : a.edge_directions)
      for (const Vec3& eb : b.edge_directions)
        if (!t.test(ea.cross(eb))) return;
    if (a.dimension <= 2 && b.dimension <= 2) test_low_dimensional_axes(t, a, b);
  };
  run();
  return t.finish();
}

}  // namespace gjklab::peers
