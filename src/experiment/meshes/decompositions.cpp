#include "gjklab/experiment/meshes/decompositions.hpp"

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "gjklab/exact/convex_decomposition.hpp"

namespace gjklab::experiment {

namespace {

Decomposition hull(const TriangleMesh& mesh, std::string_view, const DecompositionOptions&) {
  return {"hull", {mesh.vertices}, false, 0};
}

Decomposition exact_pieces(const TriangleMesh& mesh, std::string_view source,
                           const DecompositionOptions&) {
  exact::ExactConvexDecomposition d = exact::exact_convex_decomposition(mesh, source);
  return {"exact", std::move(d.pieces), true, d.max_rounding};
}

#ifdef GJKLAB_HAVE_HACD
/// Largest mesh HACD is given, in faces: its cost grows fast with them (a few seconds at
/// 5 600 faces, nine minutes and 1.4 GB at 75 000; peers/hacd.hpp).
constexpr std::size_t kMaxApproximateFaces = 20'000;

Decomposition approximate(const TriangleMesh& mesh, std::string_view source,
                          const DecompositionOptions& options) {
  if (mesh.faces.size() > kMaxApproximateFaces)
    throw std::runtime_error(
        std::string(source) + ": approximate decomposition: " + std::to_string(mesh.faces.size()) +
        " faces, more than the " + std::to_string(kMaxApproximateFaces) + " it accepts");
  return {"approximate", peers::hacd_decomposition(mesh, options.hacd), false, 0};
}
#endif

constexpr std::array kDecompositions = {
    DecompositionInfo{"hull", "one piece: the convex hull of the mesh's vertices", hull},
    DecompositionInfo{"exact",
                      "CGAL's convex decomposition, its union proven equal to the solid "
                      "(at most 2 000 faces)",
                      exact_pieces},
#ifdef GJKLAB_HAVE_HACD
    DecompositionInfo{
        "approximate",
        "Bullet's HACD, what engines ship: not proven to cover the solid (at most 20 000 "
        "faces)",
        approximate},
#endif
};

}  // namespace

std::span<const DecompositionInfo> decompositions() {
  return kDecompositions;
}

std::string decomposition_names() {
  std::string names;
  for (const DecompositionInfo& d : decompositions())
    names += (names.empty() ? "" : ", ") + std::string(d.name);
  return names;
}

const DecompositionInfo& decomposition_named(std::string_view name) {
  for (const DecompositionInfo& d : decompositions())
    if (d.name == name) return d;
  throw std::invalid_argument("unknown decomposition '" + std::string(name) +
                              "'; valid names: " + decomposition_names());
}

std::vector<Polytope> piece_polytopes(const Decomposition& d) {
  std::vector<Polytope> out;
  out.reserve(d.pieces.size());
  for (const std::vector<Vec3>& piece : d.pieces)
    out.emplace_back(piece);
  return out;
}

}  // namespace gjklab::experiment
