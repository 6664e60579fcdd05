// Adapter from gjklab's clouds to Bullet's GJK pair detector and GjkEpa2 solver (see
// peers/bullet.hpp). Compiled with BT_USE_DOUBLE_PRECISION against Bullet's float64 libraries.
#include "gjklab/peers/bullet.hpp"

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <LinearMath/btScalar.h>

#include <cmath>
#include <type_traits>

static_assert(std::is_same_v<btScalar, double>, "the Bullet peer needs Bullet's double precision");

namespace gjklab::peers {

struct BulletShape::Impl {
  std::unique_ptr<btConvexHullShape> hull;
};

BulletShape::BulletShape(const Polytope& cloud) : impl_(std::make_unique<Impl>()) {
  impl_->hull = std::make_unique<btConvexHullShape>();
  for (const Vec3& v : cloud.vertices())
    impl_->hull->addPoint(btVector3(v.x(), v.y(), v.z()), false);
  impl_->hull->recalcLocalAabb();
  impl_->hull->setMargin(0);
}

BulletShape::~BulletShape() = default;
BulletShape::BulletShape(BulletShape&&) noexcept = default;
BulletShape& BulletShape::operator=(BulletShape&&) noexcept = default;

namespace {

Vec3 to_vec(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}

btTransform identity() {
  btTransform t;
  t.setIdentity();
  return t;
}

/// The one contact btGjkPairDetector reports: normal on B (pointing from B towards A), the
/// point on B, and the signed distance (negative: penetration).
struct Capture : btDiscreteCollisionDetectorInterface::Result {
  bool reported = false;
  btVector3 normal_on_b{0, 0, 0};
  btVector3 point_on_b{0, 0, 0};
  btScalar distance = 0;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3& normal, const btVector3& point, btScalar depth) override {
    reported = true;
    normal_on_b = normal;
    point_on_b = point;
    distance = depth;
  }
};

/// Sets normal from a vector (kept when it has no direction).
void set_normal(PenetrationResult& r, const Vec3& n) {
  if (const double len = n.norm(); len > 0 && std::isfinite(len)) r.normal = n / len;
}

bool all_finite(const PenetrationResult& r) {
  return std::isfinite(r.distance) && std::isfinite(r.depth) && r.witness_a.allFinite() &&
         r.witness_b.allFinite() && r.normal.allFinite();
}

}  // namespace

PenetrationResult bullet_gjk_query(const BulletShape& a, const BulletShape& b) {
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver penetration;
  btGjkPairDetector detector(a.impl().hull.get(), b.impl().hull.get(), &simplex, &penetration);
  btGjkPairDetector::ClosestPointInput input;
  input.m_transformA = identity();
  input.m_transformB = identity();
  Capture capture;
  detector.getClosestPoints(input, capture, nullptr);

  PenetrationResult r;
  r.iterations = detector.m_curIter;
  if (!capture.reported) {
    r.termination = Termination::degenerate_simplex;
    return r;
  }
  // A's point: B's point moved along the normal (towards A) by the signed distance.
  const Vec3 on_b = to_vec(capture.point_on_b);
  const Vec3 normal_on_b = to_vec(capture.normal_on_b);
  const double d = capture.distance;
  r.witness_b = on_b;
  r.witness_a = on_b + d * normal_on_b;
  if (d > 0) {
    r.distance = d;
    set_normal(r, -normal_on_b);  // from A towards B
  } else {
    r.intersect = true;
    r.depth = -d;
    set_normal(r, -normal_on_b);  // moving B away from A, against B's normal
  }
  if (r.iterations > 1000) r.termination = Termination::step_limit;
  if (!all_finite(r)) r.termination = Termination::numerical_failure;
  return r;
}

PenetrationResult bullet_epa2_query(const BulletShape& a, const BulletShape& b) {
  const btTransform t = identity();
  const btVector3 guess(1, 0, 0);
  btGjkEpaSolver2::sResults res;
  PenetrationResult r;
  if (btGjkEpaSolver2::Distance(a.impl().hull.get(), t, b.impl().hull.get(), t, guess, res)) {
    r.distance = res.distance;
    r.witness_a = to_vec(res.witnesses[0]);
    r.witness_b = to_vec(res.witnesses[1]);
    set_normal(r, r.witness_b - r.witness_a);
  } else if (res.status == btGjkEpaSolver2::sResults::Penetrating) {
    if (btGjkEpaSolver2::Penetration(a.impl().hull.get(), t, b.impl().hull.get(), t, guess, res,
                                     /*usemargins=*/false)) {
      r.intersect = true;
      r.witness_a = to_vec(res.witnesses[0]);
      r.witness_b = to_vec(res.witnesses[1]);
      r.depth = std::abs(res.distance);
      set_normal(r, r.witness_a - r.witness_b);
      if (r.depth == 0) set_normal(r, to_vec(res.normal));
    } else {
      r.termination = res.status == btGjkEpaSolver2::sResults::GJK_Failed
                          ? Termination::step_limit
                          : Termination::degenerate_simplex;
    }
  } else {
    r.termination = Termination::step_limit;  // GJK_Failed: GJK reached its iteration bound
  }
  if (!all_finite(r)) r.termination = Termination::numerical_failure;
  return r;
}

std::string bullet_version() {
  const int v = btGetVersion();
  return std::to_string(v / 100) + "." + std::to_string(v % 100) + " (double precision)";
}

}  // namespace gjklab::peers
