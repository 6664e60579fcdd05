// The exact convex decomposition (gjklab/exact/convex_decomposition.hpp): CGAL's
// convex_decomposition_3 on the mesh's Nef polyhedron, then the proof of its pieces. The only
// translation unit that includes the Nef polyhedra (the slowest CGAL headers to compile).
//
// CGAL_DEBUG keeps CGAL's own checks on in this file although the build defines NDEBUG: Debian's
// CGAL 5.5.1 has known decomposition defects, and a check that throws is an error we can report
// where one compiled out could be a crash or a wrong piece.
#define CGAL_DEBUG 1

#include "gjklab/exact/convex_decomposition.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/convex_decomposition_3.h>
#include <CGAL/convex_hull_3.h>
#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "exact/arithmetic/gmp_support.hpp"

namespace gjklab::exact {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_3;
using Exact = Kernel::Exact_kernel::FT;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;
using Nef = CGAL::Nef_polyhedron_3<Kernel>;

[[maybe_unused]] mpq_srcptr as_mpq(const CGAL::Gmpq& q) {
  return q.mpq();
}
[[maybe_unused]] mpq_srcptr as_mpq(const mpq_class& q) {
  return q.get_mpq_t();
}

[[noreturn]] void fail(std::string_view source, const std::string& problem) {
  throw DecompositionError(std::string(source) + ": exact convex decomposition: " + problem);
}

/// The mesh as a polyhedral surface with exact points (every double is a rational).
Polyhedron to_polyhedron(const TriangleMesh& mesh) {
  std::vector<Point> points;
  points.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices)
    points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::vector<std::size_t>> faces;
  faces.reserve(mesh.faces.size());
  for (const MeshFace& f : mesh.faces)
    faces.push_back({f[0], f[1], f[2]});
  Polyhedron surface;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, surface);
  return surface;
}

/// Six times the signed volume the closed surface bounds (the sum over its facets, each fanned
/// from its first corner, of the triple products of the corners; exact).
Exact six_volume(const Polyhedron& p) {
  Exact sum = 0;
  const Point origin = CGAL::ORIGIN;
  for (auto f = p.facets_begin(); f != p.facets_end(); ++f) {
    auto h = f->facet_begin();
    const Point& first = h->vertex()->point();
    ++h;
    for (auto next = std::next(h); next != f->facet_begin(); h = next, ++next)
      sum += CGAL::exact(CGAL::determinant(first - origin, h->vertex()->point() - origin,
                                           next->vertex()->point() - origin));
  }
  return sum;
}

/// The solids of the decomposed Nef polyhedron (its marked volumes, the outer one skipped).
std::vector<Polyhedron> pieces_of(Nef& decomposed) {
  std::vector<Polyhedron> pieces;
  for (auto v = std::next(decomposed.volumes_begin()); v != decomposed.volumes_end(); ++v) {
    if (!v->mark()) continue;
    Polyhedron piece;
    decomposed.convert_inner_shell_to_polyhedron(v->shells_begin(), piece);
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

/// The corners of a piece's convex hull, and the proof that the piece is that hull: it lies in
/// the hull of its corners, so equal volumes make them equal (both are closures of their
/// interiors). Returns an empty list when the volumes differ.
std::vector<Point> proven_convex_corners(const Polyhedron& piece) {
  std::vector<Point> corners;
  for (auto v = piece.vertices_begin(); v != piece.vertices_end(); ++v)
    corners.push_back(v->point());
  Polyhedron hull;
  CGAL::convex_hull_3(corners.begin(), corners.end(), hull);
  Exact piece_volume = six_volume(piece), hull_volume = six_volume(hull);
  if (CGAL::abs(piece_volume) != CGAL::abs(hull_volume) || CGAL::is_zero(hull_volume)) return {};
  std::vector<Point> extreme;
  for (auto v = hull.vertices_begin(); v != hull.vertices_end(); ++v)
    extreme.push_back(v->point());
  return extreme;
}

/// The union of the pieces, joined pairwise (a balanced tree keeps the operands small).
Nef union_of(const std::vector<Polyhedron>& pieces) {
  std::vector<Nef> level;
  level.reserve(pieces.size());
  for (const Polyhedron& p : pieces)
    level.emplace_back(const_cast<Polyhedron&>(p));  // Nef's constructor takes a non-const ref
  while (level.size() > 1) {
    std::vector<Nef> next;
    for (std::size_t i = 0; i + 1 < level.size(); i += 2)
      next.push_back(level[i] + level[i + 1]);
    if (level.size() % 2 == 1) next.push_back(level.back());
    level.swap(next);
  }
  return level.empty() ? Nef(Nef::EMPTY) : level.front();
}

/// A corner rounded to the nearest double, and the distance it moved (rounded up).
std::pair<Vec3, double> rounded(const Point& p) {
  Vec3 out;
  double moved_squared = 0;
  for (int i = 0; i < 3; ++i) {
    const Exact x = CGAL::exact(p[i]);
    out[i] = detail::nearest_double(as_mpq(x));
    detail::Mpq error;
    detail::set_double(error.get(), out[i]);
    mpq_sub(error.get(), error.get(), as_mpq(x));
    const double e = std::nextafter(std::abs(detail::nearest_double(error.get())),
                                    std::numeric_limits<double>::infinity());
    moved_squared += e * e;
  }
  const double up = std::numeric_limits<double>::infinity();
  return {out, moved_squared == 0 ? 0 : std::nextafter(std::sqrt(moved_squared), up)};
}

/// Sorts each piece's corners and then the pieces, lexicographically by coordinates. CGAL lists
/// the same pieces in an order that changes from process to process (it follows memory
/// addresses), and archives must not.
void in_canonical_order(std::vector<std::vector<Vec3>>& pieces) {
  const auto before = [](const Vec3& p, const Vec3& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  };
  for (std::vector<Vec3>& piece : pieces)
    std::sort(piece.begin(), piece.end(), before);
  std::sort(pieces.begin(), pieces.end(), [&](const auto& p, const auto& q) {
    return std::lexicographical_compare(p.begin(), p.end(), q.begin(), q.end(), before);
  });
}

/// The decomposition and its proof (CGAL's checks may throw).
ExactConvexDecomposition decompose_and_prove(const TriangleMesh& mesh, std::string_view source) {
  Polyhedron surface = to_polyhedron(mesh);
  const Nef solid(surface);
  Nef decomposed = solid;
  CGAL::convex_decomposition_3(decomposed);
  const std::vector<Polyhedron> pieces = pieces_of(decomposed);
  if (pieces.empty()) fail(source, "CGAL returned no pieces");
  ExactConvexDecomposition out;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const std::vector<Point> corners = proven_convex_corners(pieces[i]);
    if (corners.empty())
      fail(source, "proof failed: piece " + std::to_string(i) + " of " +
                       std::to_string(pieces.size()) + " is not convex");
    std::vector<Vec3>& piece = out.pieces.emplace_back();
    for (const Point& c : corners) {
      auto [v, moved] = rounded(c);
      piece.push_back(v);
      out.max_rounding = std::max(out.max_rounding, moved);
    }
  }
  if (union_of(pieces) != solid)
    fail(source, "proof failed: the union of the " + std::to_string(pieces.size()) +
                     " pieces differs from the solid");
  in_canonical_order(out.pieces);
  return out;
}

}  // namespace

ExactConvexDecomposition exact_convex_decomposition(const TriangleMesh& mesh,
                                                    std::string_view source) {
  if (mesh.faces.size() > kMaxDecompositionFaces)
    fail(source, std::to_string(mesh.faces.size()) + " faces, more than the " +
                     std::to_string(kMaxDecompositionFaces) + " it accepts");
  try {
    return decompose_and_prove(mesh, source);
  } catch (const CGAL::Failure_exception& e) {
    fail(source, "CGAL failed (" + e.expression() + " in " + e.filename() + ":" +
                     std::to_string(e.line_number()) + ")");
  }
}

}  // namespace gjklab::exact
