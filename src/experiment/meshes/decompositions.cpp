#include "gjklab/experiment/meshes/decompositions.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "gjklab/exact/convex_decomposition.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"

namespace gjklab::experiment {

namespace {

/// HACD's parameters (peers/hacd.hpp says what each does and its range).
constexpr std::array<DecompositionOptionRow, 11> kHacdRows = {{
    {"min_clusters", "merging stops at this many clusters (a minimum, not a target)",
     &peers::HacdOptions::min_clusters},
    {"concavity",
     "largest concavity of a merged cluster (normalised length: 1/(2 scale) of the "
     "bounding-box diagonal)",
     &peers::HacdOptions::concavity},
    {"add_extra_distance_points", "also measure concavity through thin parts (quadratic cost)",
     &peers::HacdOptions::add_extra_distance_points},
    {"add_neighbours_distance_points", "also measure at the neighbouring clusters' points",
     &peers::HacdOptions::add_neighbours_distance_points},
    {"add_faces_points", "also measure concavity at each triangle's centroid",
     &peers::HacdOptions::add_faces_points},
    {"compacity_weight", "weight of the perimeter²/area shape term in the merge cost",
     &peers::HacdOptions::compacity_weight},
    {"volume_weight", "weight of the hull's volume in the merge cost (no effect in this HACD)",
     &peers::HacdOptions::volume_weight},
    {"max_hull_vertices", "at most this many vertices per piece (HACD may exceed it)",
     &peers::HacdOptions::max_hull_vertices},
    {"full_hulls", "each piece the full hull of its cluster, no vertex bound",
     &peers::HacdOptions::full_hulls},
    {"connect_distance", "link separate components closer than this (normalised length)",
     &peers::HacdOptions::connect_distance},
    {"scale", "half the bounding-box diagonal in HACD's frame (the unit of the lengths above)",
     &peers::HacdOptions::scale},
}};

/// The text as a value of the member's type, or nullopt.
std::optional<int> read_int(std::string_view text) {
  int v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return ec == std::errc() && end == text.data() + text.size() ? std::optional(v) : std::nullopt;
}
std::optional<double> read_double(std::string_view text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  const bool whole = ec == std::errc() && end == text.data() + text.size();
  return whole && std::isfinite(v) ? std::optional(v) : std::nullopt;
}
std::optional<bool> read_bool(std::string_view text) {
  if (text == "true" || text == "True") return true;
  if (text == "false" || text == "False") return false;
  return std::nullopt;
}

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
    DecompositionInfo{"hull", "one piece: the convex hull of the mesh's vertices", {}, hull},
    DecompositionInfo{"exact",
                      "CGAL's convex decomposition, its union proven equal to the solid "
                      "(at most 2 000 faces)",
                      {},
                      exact_pieces},
#ifdef GJKLAB_HAVE_HACD
    DecompositionInfo{
        "approximate",
        "Bullet's HACD, what engines ship: not proven to cover the solid (at most 20 000 "
        "faces)",
        kHacdRows, approximate},
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

void set_decomposition_option(const DecompositionInfo& d, DecompositionOptions& options,
                              std::string_view key, std::string_view value) {
  const DecompositionOptionRow* row = nullptr;
  std::string keys;
  for (const DecompositionOptionRow& r : d.options) {
    if (r.key == key) row = &r;
    keys += (keys.empty() ? "" : ", ") + std::string(r.key);
  }
  const std::string where = "decomposition '" + std::string(d.name) + "'";
  if (!row)
    throw std::invalid_argument(where + " takes no option '" + std::string(key) + "'" +
                                (keys.empty() ? "; it takes none" : "; its options: " + keys));
  const bool read = std::visit(
      [&](auto member) {
        using T = std::remove_reference_t<decltype(options.hacd.*member)>;
        std::optional<T> v;
        if constexpr (std::is_same_v<T, int>)
          v = read_int(value);
        else if constexpr (std::is_same_v<T, double>)
          v = read_double(value);
        else
          v = read_bool(value);
        if (v) options.hacd.*member = *v;
        return v.has_value();
      },
      row->member);
  if (!read)
    throw std::invalid_argument(where + " option '" + std::string(key) + "': cannot read '" +
                                std::string(value) + "'");
#ifdef GJKLAB_HAVE_HACD
  peers::validate(options.hacd);
#endif
}

std::vector<std::pair<std::string, std::string>> describe_decomposition(
    const DecompositionInfo& d, const DecompositionOptions& options) {
  std::vector<std::pair<std::string, std::string>> out{{"decomposition", std::string(d.name)}};
  for (const DecompositionOptionRow& row : d.options) {
    const std::string value = std::visit(
        [&](auto member) {
          const auto v = options.hacd.*member;
          if constexpr (std::is_same_v<decltype(v), const bool>) return std::string(v ? "true" : "false");
          else if constexpr (std::is_same_v<decltype(v), const int>) return std::to_string(v);
          else return round_trip(v);
        },
        row.member);
    out.emplace_back("decomposition." + std::string(row.key), value);
  }
  return out;
}

std::vector<Polytope> piece_polytopes(const Decomposition& d) {
  std::vector<Polytope> out;
  out.reserve(d.pieces.size());
  for (const std::vector<Vec3>& piece : d.pieces)
    out.emplace_back(piece);
  return out;
}

}  // namespace gjklab::experiment
