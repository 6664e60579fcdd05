// The support-map contract and the adapters that compose support maps.
//
// A support map returns a point of a convex shape that maximises d·x for a direction d
// (d need not be unit length; for d = 0 any point of the shape is a valid answer).
#pragma once

#include <concepts>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

/// The scalar type of a shape's points: S::Scalar where the shape declares one (the clouds
/// of another precision, geometry/scalar_cloud.hpp), else double.
template <class S>
struct ShapeScalar {
  using type = double;
};
template <class S>
requires requires {
  typename S::Scalar;
}
struct ShapeScalar<S> {
  using type = typename S::Scalar;
};
template <class S>
using shape_scalar_t = typename ShapeScalar<S>::type;

template <class S>
concept SupportMap = requires(const S& s, const Vec3T<shape_scalar_t<S>>& d) {
  { s.support(d) } -> std::convertible_to<Vec3T<shape_scalar_t<S>>>;
};

/// A shape moved by a rigid pose; support is computed in the body frame and mapped back.
template <SupportMap S>
class Transformed {
 public:
  Transformed(const S& shape, const Pose& pose) : shape_(&shape), pose_(pose) {}
  Vec3 support(const Vec3& d) const {
    return pose_.apply(shape_->support(pose_.to_body_direction(d)));
  }
  const S& shape() const { return *shape_; }
  const Pose& pose() const { return pose_; }

 private:
  const S* shape_;
  Pose pose_;
};

/// The Minkowski difference A − B = {a − b}: support(d) = support_A(d) − support_B(−d).
template <SupportMap A, SupportMap B>
class MinkowskiDifference {
 public:
  MinkowskiDifference(const A& a, const B& b) : a_(&a), b_(&b) {}
  Vec3 support(const Vec3& d) const { return a_->support(d) - b_->support(-d); }
  const A& first() const { return *a_; }
  const B& second() const { return *b_; }

 private:
  const A* a_;
  const B* b_;
};

/// A shape swept by a sphere of the given radius (length units): support = core + r·d/‖d‖.
template <SupportMap S>
class SphereSwept {
 public:
  using Scalar = shape_scalar_t<S>;
  using Point = Vec3T<Scalar>;
  SphereSwept(const S& core, Scalar radius) : core_(&core), radius_(radius) {}
  Point support(const Point& d) const {
    const Scalar n = d.norm();
    return n > 0 ? Point(core_->support(d) + (radius_ / n) * d) : core_->support(d);
  }
  const S& core() const { return *core_; }
  Scalar radius() const { return radius_; }
  /// A point inside the swept shape, when the core offers one (the core's vertex mean lies in
  /// the core, hence in the swept shape): lets queries that start from centres use it.
  Point vertex_mean() const requires requires(const S& s) {
    { s.vertex_mean() } -> std::convertible_to<Point>;
  }
  { return core_->vertex_mean(); }

 private:
  const S* core_;
  Scalar radius_;
};

}  // namespace gjklab
