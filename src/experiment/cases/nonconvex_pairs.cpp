#include "gjklab/experiment/cases/nonconvex_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "experiment/cases/random_stream.hpp"
#include "experiment/cases/sampling.hpp"

namespace gjklab::experiment {

namespace {

constexpr double kPi = std::numbers::pi;

/// Uniform in [lo, hi).
double uniform_in(gsl_rng* r, double lo, double hi) {
  return lo + (hi - lo) * uniform(r);
}

/// A vector of independent uniform coordinates in [lo, hi), drawn x first (one statement each:
/// the order of a call's arguments is unspecified, and the case must not depend on it).
Vec3 uniform_box(gsl_rng* r, double lo, double hi) {
  const double x = uniform_in(r, lo, hi);
  const double y = uniform_in(r, lo, hi);
  const double z = uniform_in(r, lo, hi);
  return {x, y, z};
}

/// A vector of independent uniform coordinates in [-h, h), scaled per axis.
Vec3 uniform_box(gsl_rng* r, double h, const Vec3& scale = Vec3::Ones()) {
  return uniform_box(r, -h, h).cwiseProduct(scale);
}

/// A turn by an angle uniform in [-max_angle, max_angle] (radians) about a uniform axis.
Mat3 small_rotation(gsl_rng* r, double max_angle) {
  const Vec3 axis = unit_vector(r);
  return Eigen::AngleAxisd(uniform_in(r, -max_angle, max_angle), axis).toRotationMatrix();
}

TriangleMesh posed(TriangleMesh mesh, const Mat3& rotation, const Vec3& translation) {
  for (Vec3& v : mesh.vertices)
    v = rotation * v + translation;
  return mesh;
}

/// A counter-clockwise circle of `points` points in the (r, z) half-plane.
std::vector<PlanePoint> circle(double centre_r, double radius, int points) {
  std::vector<PlanePoint> out;
  for (int k = 0; k < points; ++k) {
    const double t = 2 * kPi * k / points;
    out.push_back({centre_r + radius * std::cos(t), radius * std::sin(t)});
  }
  return out;
}

TriangleMesh torus(double major, double minor) {
  return lathe_mesh(circle(major, minor, 8), 12, true);
}

TriangleMesh tube(double inner, double outer, double half_height) {
  const std::vector<PlanePoint> profile = {
      {inner, -half_height}, {outer, -half_height}, {outer, half_height}, {inner, half_height}};
  return lathe_mesh(profile, 16, true);
}

TriangleMesh peg(double radius, double half_length) {
  const std::vector<PlanePoint> profile = {
      {0, -half_length}, {radius, -half_length}, {radius, half_length}, {0, half_length}};
  return lathe_mesh(profile, 12, false);
}

/// A polyhedral ball: the lathe of a half circle of 8 points (poles exactly on the axis).
TriangleMesh ball(double radius) {
  std::vector<PlanePoint> profile;
  for (int k = 0; k < 8; ++k) {
    const double t = -kPi / 2 + kPi * k / 7;
    profile.push_back({radius * std::cos(t), radius * std::sin(t)});
  }
  profile.front()[0] = profile.back()[0] = 0;
  return lathe_mesh(profile, 12, false);
}

TriangleMesh cup(double radius, double height, double wall) {
  const std::vector<PlanePoint> profile = {{0, 0},
                                           {radius, 0},
                                           {radius, height},
                                           {radius - wall, height},
                                           {radius - wall, wall},
                                           {0, wall}};
  return lathe_mesh(profile, 16, false);
}

TriangleMesh l_prism() {
  const std::vector<PlanePoint> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  return prism_mesh(l, 0, 1);
}

/// A star-shaped mesh (5 rings × 8 segments) with radii uniform in [0.45, 1] per vertex.
TriangleMesh star(gsl_rng* r, double size) {
  return star_mesh(5, 8, [&](const Vec3&) { return size * uniform_in(r, 0.45, 1.0); });
}

MeshPair rings(gsl_rng* r) {
  // B stands upright (a quarter turn about x) through A's hole.
  Mat3 upright;  // exactly: a quarter turn about x
  upright << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  const Mat3 turn = small_rotation(r, 0.25) * upright;
  return {torus(1.0, 0.22), posed(torus(1.0, 0.22), turn, Vec3(1, 0, 0) + uniform_box(r, 0.45))};
}

MeshPair peg_in_hole(gsl_rng* r) {
  const Mat3 tilt = small_rotation(r, 0.3);
  return {tube(0.5, 1.0, 0.25), posed(peg(0.3, 1.0), tilt, uniform_box(r, 0.3, {1, 1, 0.5}))};
}

MeshPair ball_in_cup(gsl_rng* r) {
  const Mat3 turn = small_rotation(r, kPi);
  return {cup(1.0, 1.2, 0.15), posed(ball(0.5), turn, Vec3(0, 0, 0.7) + uniform_box(r, 0.45))};
}

MeshPair l_in_l(gsl_rng* r) {
  // B is A turned by a half turn about z into A's notch, then moved and tilted a little.
  const Mat3 half_turn = Vec3(-1, -1, 1).asDiagonal();  // exactly
  const TriangleMesh turned = posed(l_prism(), half_turn, Vec3(3, 3, 0));
  const Mat3 tilt = small_rotation(r, 0.2);
  const Vec3 shift = uniform_box(r, -0.6, 0.3).cwiseProduct(Vec3(1, 1, 0.5));
  return {l_prism(), posed(turned, tilt, shift)};
}

MeshPair stars(gsl_rng* r) {
  TriangleMesh a = star(r, 1.0);
  TriangleMesh b = star(r, 1.0);
  const Mat3 turn = random_rotation(r);
  const double distance = uniform_in(r, 0.9, 1.9);
  const Vec3 centre = distance * unit_vector(r);
  return {std::move(a), posed(std::move(b), turn, centre)};
}

MeshPair nested(gsl_rng* r) {
  TriangleMesh small = star(r, 0.3);
  const Mat3 turn = random_rotation(r);
  return {ball(1.0), posed(std::move(small), turn, uniform_box(r, 0.85))};
}

MeshPair box_in_notch(gsl_rng* r) {
  const bool overlapping = uniform(r) < 0.5;
  const double gap = log_uniform(r, Interval{1e-12, 0.25}) * (overlapping ? -1 : 1);
  const double lo = 1 + gap, hi = lo + 0.5;
  const std::vector<PlanePoint> square = {{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}};
  return {l_prism(), prism_mesh(square, 0.25, 0.75)};
}

MeshPair two_meshes(gsl_rng* r, std::span<const TriangleMesh> meshes) {
  if (meshes.empty()) throw std::invalid_argument("a `meshes` pair needs at least one mesh");
  const TriangleMesh& a = meshes[gsl_rng_uniform_int(r, meshes.size())];
  const TriangleMesh& b = meshes[gsl_rng_uniform_int(r, meshes.size())];
  const Mat3 turn_a = random_rotation(r);
  const Mat3 turn_b = random_rotation(r);
  const double distance = uniform_in(r, 0.6, 1.8);
  const Vec3 centre = distance * unit_vector(r);
  return {posed(a, turn_a, Vec3::Zero()), posed(b, turn_b, centre)};
}

}  // namespace

TriangleMesh unit_size(TriangleMesh mesh) {
  if (mesh.vertices.empty()) return mesh;
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec3 centre = (lo + hi) / 2;
  double farthest = 0;
  for (const Vec3& v : mesh.vertices)
    farthest = std::max(farthest, (v - centre).norm());
  if (!(farthest > 0)) return mesh;
  for (Vec3& v : mesh.vertices)
    v = (v - centre) / farthest;
  return mesh;
}

MeshPair draw_nonconvex_pair(NonconvexPair kind, std::span<const TriangleMesh> meshes,
                             RandomStream& stream) {
  gsl_rng* r = stream.gsl;
  switch (kind) {
    case NonconvexPair::rings: return rings(r);
    case NonconvexPair::peg_in_hole: return peg_in_hole(r);
    case NonconvexPair::ball_in_cup: return ball_in_cup(r);
    case NonconvexPair::l_in_l: return l_in_l(r);
    case NonconvexPair::stars: return stars(r);
    case NonconvexPair::nested: return nested(r);
    case NonconvexPair::box_in_notch: return box_in_notch(r);
    case NonconvexPair::meshes: return two_meshes(r, meshes);
  }
  throw std::invalid_argument("unknown nonconvex pair");
}

}  // namespace gjklab::experiment
