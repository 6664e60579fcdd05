// Adapter from gjklab's clouds to FCL 0.7's GJK solvers (see peers/fcl.hpp).
#include "gjklab/peers/fcl.hpp"

#include <fcl/config.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/detail/gjk_solver_indep.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace gjklab::peers {

struct FclShape::Impl {
  std::shared_ptr<const std::vector<fcl::Vector3d>> vertices;
  std::shared_ptr<const std::vector<int>> faces;
  std::unique_ptr<fcl::Convexd> convex;
};

FclShape::FclShape(const Polytope& cloud) : FclShape(exact::hull_features(cloud.vertices())) {}

FclShape::FclShape(const exact::HullFeatures& hull) : impl_(std::make_unique<Impl>()) {
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  vertices->reserve(hull.vertices.size());
  for (const Vec3& v : hull.vertices)
    vertices->emplace_back(v.x(), v.y(), v.z());
  // FCL's face encoding: for each face its vertex count, then its indices (counter-clockwise
  // seen from outside).
  auto faces = std::make_shared<std::vector<int>>();
  for (const std::vector<int>& loop : hull.faces) {
    faces->push_back(static_cast<int>(loop.size()));
    faces->insert(faces->end(), loop.begin(), loop.end());
  }
  impl_->vertices = vertices;
  impl_->faces = faces;
  impl_->convex =
      std::make_unique<fcl::Convexd>(impl_->vertices, static_cast<int>(hull.faces.size()),
                                     impl_->faces, /*throw_if_invalid=*/false);
}

FclShape::~FclShape() = default;
FclShape::FclShape(FclShape&&) noexcept = default;
FclShape& FclShape::operator=(FclShape&&) noexcept = default;

namespace {

void validate(const FclOptions& o) {
  if (o.max_iterations < 1 || o.epa_max_iterations < 1 || o.epa_max_faces < 1 ||
      o.epa_max_vertices < 1)
    throw std::invalid_argument("fcl: iteration, face and vertex bounds must be >= 1");
}

Vec3 to_vec(const fcl::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

/// Every reported number is finite. FCL can return NaN closest points with a finite distance
/// (a vertex near 1e154, whose square overflows), so each number is checked, not only the
/// distance and the depth.
bool all_finite(const PenetrationResult& r) {
  return std::isfinite(r.distance) && std::isfinite(r.depth) && r.normal.allFinite() &&
         r.witness_a.allFinite() && r.witness_b.allFinite();
}

template <class Solver>
PenetrationResult query(const Solver& solver, const fcl::Convexd& a, const fcl::Convexd& b,
                        bool indep) {
  const fcl::Transform3d identity = fcl::Transform3d::Identity();
  PenetrationResult r;
  std::vector<fcl::ContactPointd> contacts;
  r.intersect = solver.shapeIntersect(a, identity, b, identity, &contacts);
  if (r.intersect) {
    if (!contacts.empty()) {
      const fcl::ContactPointd& c = contacts.front();
      // FCL 0.7 reports the depth with a negative sign for the indep solver.
      r.depth = std::abs(c.penetration_depth);
      const Vec3 n = to_vec(c.normal);
      if (const double len = n.norm(); len > 0 && std::isfinite(len)) r.normal = n / len;
      r.witness_a = r.witness_b = to_vec(c.pos);
    }
    return r;
  }
  double distance = -1;
  fcl::Vector3d pa, pb;
  if (solver.shapeDistance(a, identity, b, identity, &distance, &pa, &pb) && distance >= 0) {
    r.distance = distance;
    r.witness_a = to_vec(pa);
    r.witness_b = to_vec(pb);
    const Vec3 ab = r.witness_b - r.witness_a;
    if (const double len = ab.norm(); len > 0 && std::isfinite(len)) r.normal = ab / len;
  } else {
    r.distance = 0;
    if (indep) r.termination = Termination::step_limit;
  }
  return r;
}

/// Largest coordinate magnitude (length units) given to FCL. Its libccd-based GJK takes triple
/// products, cubic in the coordinates, which overflow beyond about 1e102; on such a pair (a
/// vertex at 1e300) its assertion "A is not in region 1" fired and, as Debian's FCL keeps its
/// assertions, aborted the whole program. And its collide path runs libccd's MPR with FCL's
/// own support function, whose loops take no iteration bound (gjklab cannot count its steps as
/// it does for libccd itself): beside features of size 1 it never returned on vertices at
/// 5.9e68 and, below an earlier bound of 1e30, at 9.9e19 (both found by fuzzing). The bound is
/// empirical, not a proof that MPR ends below it: far below every known hang and above every
/// scale the experiments use (the scale study goes to 1e9); at 1e12 the spacing of doubles is
/// already about 1e-4 length units. Beyond it FCL is not called (invalid input).
constexpr double kMaxFclCoordinate = 1e12;

bool within_fcl_range(const fcl::Convexd& c) {
  for (const fcl::Vector3d& v : c.getVertices())
    if (!(v.cwiseAbs().maxCoeff() <= kMaxFclCoordinate)) return false;
  return true;
}

/// The query, with any non-finite answer reported as a numerical failure (never as converged).
template <class Solver>
PenetrationResult run(const Solver& solver, const fcl::Convexd& a, const fcl::Convexd& b,
                      bool indep) {
  PenetrationResult r = query(solver, a, b, indep);
  if (!all_finite(r)) r.termination = Termination::numerical_failure;
  return r;
}

}  // namespace

PenetrationResult fcl_query(const FclShape& a, const FclShape& b, FclSolver solver,
                            const FclOptions& options) {
  validate(options);
  const fcl::Convexd& ca = *a.impl().convex;
  const fcl::Convexd& cb = *b.impl().convex;
  if (!within_fcl_range(ca) || !within_fcl_range(cb)) {
    PenetrationResult r;
    r.termination = Termination::invalid_input;
    return r;
  }
  if (solver == FclSolver::libccd) {
    fcl::detail::GJKSolver_libccdd s;
    s.max_collision_iterations = static_cast<unsigned>(options.max_iterations);
    s.max_distance_iterations = static_cast<unsigned>(options.max_iterations);
    return run(s, ca, cb, false);
  }
  fcl::detail::GJKSolver_indepd s;
  s.gjk_max_iterations = static_cast<unsigned>(options.max_iterations);
  s.epa_max_iterations = static_cast<unsigned>(options.epa_max_iterations);
  s.epa_max_face_num = static_cast<unsigned>(options.epa_max_faces);
  s.epa_max_vertex_num = static_cast<unsigned>(options.epa_max_vertices);
  return run(s, ca, cb, true);
}

std::string fcl_version() {
  return FCL_VERSION;
}

std::string fcl_settings() {
  const fcl::detail::GJKSolver_libccdd l;
  const fcl::detail::GJKSolver_indepd i;
  std::ostringstream s;
  s.precision(17);
  s << "libccd: collision_tolerance=" << l.collision_tolerance
    << " distance_tolerance=" << l.distance_tolerance
    << "; indep: gjk_tolerance=" << i.gjk_tolerance << " epa_tolerance=" << i.epa_tolerance;
  return s.str();
}

}  // namespace gjklab::peers
