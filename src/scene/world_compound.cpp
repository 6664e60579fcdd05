// The narrow phase of pairs with a compound body (compound.hpp): piece pair by piece pair.
#include <utility>
#include <vector>

#include "contact_manifold.hpp"
#include "gjklab/scene/compound.hpp"
#include "gjklab/scene/world.hpp"

namespace gjklab::scene {

namespace {

/// One convex part of a body as the narrow phase sees it: its shape (faces in the body frame)
/// and its world hull.
using Part = std::pair<const ConvexShape*, const Polytope*>;

/// True when the world boxes of p and q, each grown by `reach` (length units), overlap.
bool boxes_meet(const Polytope& p, const Polytope& q, double reach) {
  return ((p.box_lower().array() - reach) <= q.box_upper().array()).all() &&
         ((q.box_lower().array() - reach) <= p.box_upper().array()).all();
}

}  // namespace

const std::vector<Polytope>& World::world_pieces(std::uint32_t i) {
  if (world_hull_step_[i] != step_count_ + 1 || world_pieces_[i].empty()) {
    std::vector<Polytope>& out = world_pieces_[i];
    out.clear();
    for (const ConvexShape& piece : bodies_[i].compound->pieces)
      out.push_back(piece.polytope.transformed(bodies_[i].pose));
    world_hull_step_[i] = step_count_ + 1;
  }
  return world_pieces_[i];
}

void World::collide_pieces(std::uint32_t ia, std::uint32_t ib, PairOutcome& out) const {
  auto parts_of = [&](std::uint32_t i) {
    std::vector<Part> parts;
    if (const auto& c = bodies_[i].compound)
      for (std::size_t k = 0; k < c->pieces.size(); ++k)
        parts.emplace_back(&c->pieces[k], &world_pieces_[i][k]);
    else
      parts.emplace_back(bodies_[i].shape.get(), &*world_hulls_[i]);
    return parts;
  };
  out.compound = true;
  out.queries = 0;
  // The reach within which a piece pair can make a contact this step (convex_contacts' margin
  // plus the swept radii), in length units.
  const double margin = settings_.contact_margin + sweep_distance(ia) + sweep_distance(ib);
  for (const auto& [sa, pa] : parts_of(ia))
    for (const auto& [sb, pb] : parts_of(ib)) {
      if (!boxes_meet(*pa, *pb, margin + sa->swept_radius + sb->swept_radius)) continue;
      const DistanceResult r = narrow_query(*pa, *pb, {});
      ++out.queries;
      out.iterations += r.iterations;
      if (settings_.measure_cold) out.iterations_cold += r.iterations;  // it ran cold
      if (r.termination != Termination::converged) ++out.failed;
      PairOutcome piece;
      piece.a = ia;
      piece.b = ib;
      convex_contacts(*sa, *pa, *sb, *pb, r, piece);
      out.epa += piece.epa;
      out.failed += piece.failed;
      for (const detail::ManifoldPoint& m : piece.points) {
        out.points.push_back(m);
        out.normals.push_back(piece.normal);
      }
    }
}

}  // namespace gjklab::scene
