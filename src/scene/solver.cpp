// The world's contact solver: sequential impulses on the step's contacts (normal and friction),
// the position correction of what penetration remains, and the integration of the velocities.
#include <algorithm>
#include <cmath>
#include <vector>

#include "gjklab/scene/world.hpp"

namespace gjklab::scene {

namespace {

/// Effective mass denominator of an impulse along unit d at arms ra, rb (1/mass units).
double inverse_effective_mass(const RigidBody& a, const RigidBody& b, const Mat3& ia,
                              const Mat3& ib, const Vec3& ra, const Vec3& rb, const Vec3& d) {
  const Vec3 ca = ra.cross(d), cb = rb.cross(d);
  return a.inverse_mass + b.inverse_mass + ca.dot(ia * ca) + cb.dot(ib * cb);
}

/// Two unit tangents orthogonal to the unit normal n (and to each other).
void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const Vec3 helper = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : Vec3::UnitY();
  t1 = n.cross(helper).normalized();
  t2 = n.cross(t1);
}

/// Per-contact constants of one step's solve.
struct ContactRow {
  Vec3 ra, rb;  ///< arms from the centres of mass (world)
  Vec3 t[2];    ///< tangents
  double normal_mass;
  double tangent_mass[2];
  double target;  ///< normal relative velocity the impulse aims for (≥ this)
  double friction;
};

void apply_impulse(RigidBody& a, RigidBody& b, const Mat3& ia, const Mat3& ib, const Vec3& ra,
                   const Vec3& rb, const Vec3& p, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb) {
  va -= a.inverse_mass * p;
  wa -= ia * ra.cross(p);
  vb += b.inverse_mass * p;
  wb += ib * rb.cross(p);
}

}  // namespace

void World::solve_velocities() {
  const std::size_t n = contacts_.size();
  std::vector<ContactRow> rows(n);
  std::vector<Mat3> inv_inertia(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    inv_inertia[i] = bodies_[i].inverse_inertia_world();
  const double dt = settings_.dt;
  for (std::size_t k = 0; k < n; ++k) {
    Contact& c = contacts_[k];
    RigidBody& a = bodies_[c.a];
    RigidBody& b = bodies_[c.b];
    ContactRow& row = rows[k];
    row.ra = c.point - a.pose.translation;
    row.rb = c.point - b.pose.translation;
    tangent_basis(c.normal, row.t[0], row.t[1]);
    const Mat3& ia = inv_inertia[c.a];
    const Mat3& ib = inv_inertia[c.b];
    row.normal_mass = 1.0 / inverse_effective_mass(a, b, ia, ib, row.ra, row.rb, c.normal);
    for (int t = 0; t < 2; ++t)
      row.tangent_mass[t] = 1.0 / inverse_effective_mass(a, b, ia, ib, row.ra, row.rb, row.t[t]);
    row.friction = std::sqrt(a.friction * b.friction);
    const double vn = (b.point_velocity(c.point) - a.point_velocity(c.point)).dot(c.normal);
    const double e = std::max(a.restitution, b.restitution);
    // Bounce when approaching fast enough to close the gap this step; otherwise a speculative
    // contact lets the bodies approach by the gap (−depth) and no further.
    if (e > 0 && vn < -settings_.restitution_threshold && c.depth > vn * dt)
      row.target = -e * vn;
    else
      row.target = c.depth < 0 ? c.depth / dt : 0.0;
    // Warm start: last step's impulses, applied once before the passes.
    const Vec3 p = c.normal_impulse * c.normal + c.tangent_impulse[0] * row.t[0] +
                   c.tangent_impulse[1] * row.t[1];
    apply_impulse(a, b, ia, ib, row.ra, row.rb, p, a.velocity, a.angular_velocity, b.velocity,
                  b.angular_velocity);
  }
  // Each pass: every non-penetration row, then every friction row (friction bounded by the
  // normal impulse just computed; Coulomb's cone approximated by a box in the tangent basis).
  for (int pass = 0; pass < settings_.solver_iterations; ++pass) {
    for (int phase = 0; phase < 2; ++phase) {
      for (std::size_t k = 0; k < n; ++k) {
        Contact& c = contacts_[k];
        RigidBody& a = bodies_[c.a];
        RigidBody& b = bodies_[c.b];
        const ContactRow& row = rows[k];
        const Mat3& ia = inv_inertia[c.a];
        const Mat3& ib = inv_inertia[c.b];
        auto relative = [&] {
          return Vec3(b.velocity + b.angular_velocity.cross(row.rb) - a.velocity -
                      a.angular_velocity.cross(row.ra));
        };
        if (phase == 0) {
          const double vn = relative().dot(c.normal);
          const double old = c.normal_impulse;
          c.normal_impulse = std::max(0.0, old + (row.target - vn) * row.normal_mass);
          apply_impulse(a, b, ia, ib, row.ra, row.rb, (c.normal_impulse - old) * c.normal,
                        a.velocity, a.angular_velocity, b.velocity, b.angular_velocity);
          continue;
        }
        const double limit = row.friction * c.normal_impulse;
        for (int t = 0; t < 2; ++t) {
          const double vt = relative().dot(row.t[t]);
          const double old = c.tangent_impulse[t];
          c.tangent_impulse[t] = std::clamp(old - vt * row.tangent_mass[t], -limit, limit);
          apply_impulse(a, b, ia, ib, row.ra, row.rb, (c.tangent_impulse[t] - old) * row.t[t],
                        a.velocity, a.angular_velocity, b.velocity, b.angular_velocity);
        }
      }
    }
  }
}

void World::correct_positions(std::vector<Vec3>& dv, std::vector<Vec3>& dw) {
  dv.assign(bodies_.size(), Vec3::Zero());
  dw.assign(bodies_.size(), Vec3::Zero());
  const std::size_t n = contacts_.size();
  std::vector<double> lambda(n, 0.0);
  std::vector<Mat3> inv_inertia(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    inv_inertia[i] = bodies_[i].inverse_inertia_world();
  for (int pass = 0; pass < settings_.position_iterations; ++pass) {
    for (std::size_t k = 0; k < n; ++k) {
      const Contact& c = contacts_[k];
      if (c.depth <= settings_.slop) continue;
      RigidBody& a = bodies_[c.a];
      RigidBody& b = bodies_[c.b];
      const Vec3 ra = c.point - a.pose.translation, rb = c.point - b.pose.translation;
      const Mat3& ia = inv_inertia[c.a];
      const Mat3& ib = inv_inertia[c.b];
      // Pseudo-velocity (length/s) that removes the fraction `baumgarte` of the excess depth.
      const double target = settings_.baumgarte * (c.depth - settings_.slop) / settings_.dt;
      const double vn = (dv[c.b] + dw[c.b].cross(rb) - dv[c.a] - dw[c.a].cross(ra)).dot(c.normal);
      const double mass = 1.0 / inverse_effective_mass(a, b, ia, ib, ra, rb, c.normal);
      const double old = lambda[k];
      lambda[k] = std::max(0.0, old + (target - vn) * mass);
      apply_impulse(a, b, ia, ib, ra, rb, (lambda[k] - old) * c.normal, dv[c.a], dw[c.a], dv[c.b],
                    dw[c.b]);
    }
  }
}

void World::integrate(const std::vector<Vec3>& dv, const std::vector<Vec3>& dw) {
  const double dt = settings_.dt;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    RigidBody& b = bodies_[i];
    if (b.is_static()) continue;
    b.pose.translation += (b.velocity + dv[i]) * dt;
    const Vec3 w = b.angular_velocity + dw[i];
    const Mat3 inertia_before =
        b.pose.rotation * b.inverse_inertia_body.inverse() * b.pose.rotation.transpose();
    const Quat spin(0, w.x(), w.y(), w.z());
    b.orientation.coeffs() += 0.5 * dt * (spin * b.orientation).coeffs();
    b.orientation.normalize();
    b.pose.rotation = b.orientation.toRotationMatrix();
    // Without torque the angular momentum I ω is constant in the world frame: the new
    // orientation's inertia gets the ω that keeps it (the gyroscopic motion, to first order).
    b.angular_velocity = b.inverse_inertia_world() * (inertia_before * b.angular_velocity);
  }
}

}  // namespace gjklab::scene
