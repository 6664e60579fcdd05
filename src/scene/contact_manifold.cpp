// Contact manifolds of two convex shapes by face clipping (see world.hpp, step 2).
#include "contact_manifold.hpp"

#include <algorithm>

namespace gjklab::scene::detail {

namespace {

/// Cosine of the largest angle (about 11°) between the contact normal and a face normal for
/// which the face still counts as the contact feature (manifold by clipping); below it the
/// contact is an edge or a vertex and gets the single GJK/EPA point.
constexpr double kFaceAlignment = 0.98;
/// Points per manifold: four span any face-on-face contact's support polygon well enough.
constexpr std::size_t kMaxManifoldPoints = 4;

/// Sutherland–Hodgman: the part of the polygon `poly` on the side (x − p)·m ≤ 0.
std::vector<Vec3> clip(const std::vector<Vec3>& poly, const Vec3& p, const Vec3& m) {
  std::vector<Vec3> out;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& x = poly[i];
    const Vec3& y = poly[(i + 1) % n];
    const double sx = (x - p).dot(m), sy = (y - p).dot(m);
    if (sx <= 0) out.push_back(x);
    if ((sx <= 0) != (sy <= 0)) out.push_back(x + (sx / (sx - sy)) * (y - x));
  }
  return out;
}

/// Keeps at most four points: the deepest, the one farthest from it, the one farthest from
/// their line, and the one that adds the most area (a greedy cover of the contact polygon).
std::vector<ManifoldPoint> reduce_points(std::vector<ManifoldPoint> pts) {
  if (pts.size() <= kMaxManifoldPoints) return pts;
  std::vector<ManifoldPoint> kept;
  auto take = [&](auto score) {
    std::size_t best = 0;
    double best_score = -1;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double s = score(pts[i].point, pts[i].depth);
      if (s > best_score) best_score = s, best = i;
    }
    kept.push_back(pts[best]);
    pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(best));
  };
  take([](const Vec3&, double d) { return d + 1e300; });
  take([&](const Vec3& x, double) { return (x - kept[0].point).squaredNorm(); });
  take([&](const Vec3& x, double) {
    return (kept[1].point - kept[0].point).cross(x - kept[0].point).squaredNorm();
  });
  // The area x adds to the triangle: the parts of the triangles it forms with the edges it
  // lies outside of (signed areas against the triangle's own orientation).
  const Vec3 up = (kept[1].point - kept[0].point).cross(kept[2].point - kept[0].point);
  take([&](const Vec3& x, double) {
    double added = 0;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = kept[k].point;
      const Vec3& q = kept[(k + 1) % 3].point;
      added += std::max(0.0, -(q - p).cross(x - p).dot(up));
    }
    return added;
  });
  return kept;
}

/// The face of `shape` (posed by `rotation`) whose world normal is most aligned with d.
std::size_t best_face(const ConvexShape& shape, const Mat3& rotation, const Vec3& d,
                      double& alignment) {
  const Vec3 body_d = rotation.transpose() * d;
  std::size_t best = 0;
  alignment = -2;
  for (std::size_t f = 0; f < shape.face_normals.size(); ++f) {
    const double a = shape.face_normals[f].dot(body_d);
    if (a > alignment) alignment = a, best = f;
  }
  return best;
}

}  // namespace

// See contact_manifold.hpp.
std::vector<ManifoldPoint> clip_manifold(const ConvexShape& sa, const Polytope& wa, const Mat3& ra,
                                         const ConvexShape& sb, const Polytope& wb, const Mat3& rb,
                                         Vec3& normal, double margin) {
  if (sa.face_normals.empty() && sb.face_normals.empty()) return {};
  double align_a = 0, align_b = 0;
  const std::size_t fa = best_face(sa, ra, normal, align_a);
  const std::size_t fb = best_face(sb, rb, -normal, align_b);
  if (std::max(align_a, align_b) < kFaceAlignment) return {};
  // Prefer a's face on near ties so the choice does not flicker between steps.
  const bool a_is_reference = align_a + 1e-3 >= align_b;
  const ConvexShape& rs = a_is_reference ? sa : sb;
  const ConvexShape& is = a_is_reference ? sb : sa;
  const Polytope& rw = a_is_reference ? wa : wb;
  const Polytope& iw = a_is_reference ? wb : wa;
  const Mat3& rr = a_is_reference ? ra : rb;
  const auto& ref_loop = rs.faces[a_is_reference ? fa : fb];
  const Vec3 nr = rr * rs.face_normals[a_is_reference ? fa : fb];  // out of the reference body
  // The incident feature: its face, or all of a faceless core (a swept point or segment, whose
  // alignment of −2 never makes it the reference).
  std::vector<Vec3> poly;
  if (is.faces.empty())
    poly.assign(iw.vertices().begin(), iw.vertices().end());
  else
    for (int v : is.faces[a_is_reference ? fb : fa])
      poly.push_back(iw.vertices()[v]);
  const std::size_t m = ref_loop.size();
  for (std::size_t k = 0; k < m && !poly.empty(); ++k) {
    const Vec3& p = rw.vertices()[ref_loop[k]];
    const Vec3& q = rw.vertices()[ref_loop[(k + 1) % m]];
    poly = clip(poly, p, (q - p).cross(nr));  // side plane, outward for a loop CCW about nr
  }
  const Vec3 on_plane = rw.vertices()[ref_loop[0]];
  const double r_ref = rs.swept_radius, r_inc = is.swept_radius;
  std::vector<ManifoldPoint> pts;
  for (const Vec3& x : poly) {
    const double s = (x - on_plane).dot(nr);  // the cores' separation above the reference face
    // Surfaces: the reference face moved out by r_ref, the incident point in by r_inc.
    if (s - r_ref - r_inc <= margin)
      pts.push_back({x - 0.5 * (s - r_ref + r_inc) * nr, r_ref + r_inc - s});
  }
  normal = a_is_reference ? nr : Vec3(-nr);
  return reduce_points(std::move(pts));
}

}  // namespace gjklab::scene::detail
