// The support-map contract and the adapters that compose support maps.
//
// A support map returns a point of a convex shape that maximises d·x for a direction d
// (d need not be unit length; for d = 0 any point of the shape is a valid answer).
#pragma once

#include <concepts>

#include "gjklab/geometry/types.hpp"

namespace gjklab {

template <class S>
concept SupportMap = requires(const S& s, const Vec3& d) {
  { s.support(d) } -> std::convertible_to<Vec3>;
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
  SphereSwept(const S& core, double radius) : core_(&core), radius_(radius) {}
  Vec3 support(const Vec3& d) const {
    const double n = d.norm();
    return n > 0 ? Vec3(core_->support(d) + (radius_ / n) * d) : core_->support(d);
  }
  const S& core() const { return *core_; }
  double radius() const { return radius_; }
  /// A point inside the swept shape, when the core offers one (the core's vertex mean lies in
  /// the core, hence in the swept shape): lets queries that start from centres use it.
  Vec3 vertex_mean() const requires requires(const S& s) {
    { s.vertex_mean() } -> std::convertible_to<Vec3>;
  }
  { return core_->vertex_mean(); }

 private:
  const S* core_;
  double radius_;
};

}  // namespace gjklab
