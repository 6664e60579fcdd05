#include "gjklab/experiment/cases/families.hpp"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "experiment/cases/contacts.hpp"
#include "experiment/cases/random_stream.hpp"
#include "experiment/cases/sampling.hpp"
#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/experiment/cases/nonconvex_pairs.hpp"
#include "gjklab/experiment/cases/seeded_random.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/geometry/shapes.hpp"

namespace gjklab::experiment {

namespace {

// ---- seeding ----
//
// GSL's generators take 32-bit seeds (gsl_rng_mt19937 keeps the low 32 bits of its seed). A
// 64-bit hash of (seed, case id) truncated to 32 bits would give two cases of one experiment
// the same stream with probability ~n²/2³³ (even odds at 77 000 cases). Instead the
// experiment seed is mixed into a 64-bit key with splitmix64, and the case id goes through a
// bijection of 32-bit integers keyed by it: within an experiment, case ids below 2³² get
// pairwise different generator seeds, and the seeds of consecutive ids look unrelated.

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// MurmurHash3's finaliser: a bijection of 32-bit integers with full avalanche.
std::uint32_t fmix32(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bU;
  h ^= h >> 13;
  h *= 0xc2b2ae35U;
  h ^= h >> 16;
  return h;
}

}  // namespace

std::uint32_t case_stream_seed(std::uint64_t seed, std::uint64_t case_id) {
  const std::uint64_t key = splitmix64(seed);
  const auto lo = static_cast<std::uint32_t>(key);
  const auto hi = static_cast<std::uint32_t>(key >> 32);
  return fmix32(fmix32(static_cast<std::uint32_t>(case_id) + lo) ^ hi);
}

namespace {

std::size_t draw_family(gsl_rng* r, const std::vector<FamilySpec>& families) {
  // Weights are relative: scaled by the largest, so that their sum cannot overflow (two
  // weights of 1e308 once summed to infinity and sent every case to the last family). The
  // scaling is by a power of two, which leaves the draws of ordinary weights bit for bit.
  double largest = 0;
  for (const FamilySpec& f : families)
    largest = std::max(largest, f.weight);
  const double unit = largest > 0x1p1000 ? std::exp2(std::floor(std::log2(largest))) : 1.0;
  double total = 0;
  for (const FamilySpec& f : families)
    total += f.weight / unit;
  const double target = uniform(r) * total;
  double cumulative = 0;
  for (std::size_t i = 0; i < families.size(); ++i) {
    cumulative += families[i].weight / unit;
    if (target < cumulative) return i;
  }
  return families.size() - 1;
}

Vec3 vertex_mean(const std::vector<Vec3>& cloud) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : cloud)
    sum += p;
  return sum / static_cast<double>(cloud.size());
}

/// One of the 24 rotations that permute the axes and flip signs (determinant +1): exact in
/// double, so flat clouds stay exactly flat and dyadic coordinates stay exact.
Mat3 random_axis_rotation(gsl_rng* r) {
  static constexpr int kPermutations[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                              {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  const unsigned k = static_cast<unsigned>(gsl_rng_uniform_int(r, 6));
  const int parity = k < 3 ? 1 : -1;
  double signs[3];
  for (double& sgn : signs)
    sgn = gsl_rng_uniform_int(r, 2) ? 1.0 : -1.0;
  // The product of the signs must equal the permutation's parity for determinant +1.
  if (signs[0] * signs[1] * signs[2] != parity) signs[2] = -signs[2];
  Mat3 m = Mat3::Zero();
  for (int row = 0; row < 3; ++row)
    m(row, kPermutations[k][row]) = signs[row];
  return m;
}

/// The family's rotation of one shape (identity, uniform on SO(3), or a signed axis
/// permutation).
Mat3 draw_rotation(gsl_rng* r, Rotation mode) {
  switch (mode) {
    case Rotation::none:
      return Mat3::Identity();
    case Rotation::random:
      return random_rotation(r);
    case Rotation::axes:
      return random_axis_rotation(r);
  }
  return Mat3::Identity();
}

/// Generates one shape and moves it to the origin (vertex mean), rotates it there as the
/// family says, and scales it by `scale`.
std::vector<Vec3> make_shape(RandomStream& stream, ShapeKind kind, int n, const FamilySpec& family,
                             double scale) {
  gsl_rng* r = stream.gsl;
  const double aspect = kind == ShapeKind::sliver ? log_uniform(r, family.aspect) : 1.0;
  std::vector<Vec3> cloud = kind == ShapeKind::mesh
                                ? family.meshes[gsl_rng_uniform_int(r, family.meshes.size())]
                                : generate_shape(kind, n, stream, aspect);
  const Vec3 mean = vertex_mean(cloud);
  for (Vec3& p : cloud)
    p -= mean;
  if (family.rotation != Rotation::none) {
    const Mat3 rotation = draw_rotation(r, family.rotation);
    for (Vec3& p : cloud)
      p = rotation * p;
  }
  for (Vec3& p : cloud)
    p *= scale;
  return cloud;
}

constexpr ContactType kExactContacts[] = {ContactType::face_face,   ContactType::edge_edge,
                                          ContactType::vertex_face, ContactType::edge_face,
                                          ContactType::vertex_edge, ContactType::vertex_vertex};

std::vector<Vec3> points_of(const Polytope& p) {
  return {p.vertices().begin(), p.vertices().end()};
}

}  // namespace

namespace {

// The random clouds, n points each. Each draws its coordinates in a fixed order from r: a
// case is generated from (seed, id) alone, so the order is part of the reference archives.

std::vector<Vec3> sphere_cloud(int n, gsl_rng* r) {
  std::vector<Vec3> cloud;
  cloud.reserve(n);
  for (int i = 0; i < n; ++i)
    cloud.push_back(unit_vector(r));
  return cloud;
}

std::vector<Vec3> ball_cloud(int n, gsl_rng* r) {
  // Rejection from the cube [-1, 1)^3 (accepts π/6 ≈ 52%); the test is the same squared
  // norm Eigen computes, so every accepted point has norm ≤ 1 as Eigen reports it.
  std::vector<Vec3> cloud;
  cloud.reserve(n);
  while (static_cast<int>(cloud.size()) < n) {
    const Vec3 p(2 * uniform(r) - 1, 2 * uniform(r) - 1, 2 * uniform(r) - 1);
    if (p.squaredNorm() <= 1) cloud.push_back(p);
  }
  return cloud;
}

std::vector<Vec3> cube_cloud(int n, gsl_rng* r) {
  std::vector<Vec3> cloud;
  cloud.reserve(n);
  for (int i = 0; i < n; ++i)
    cloud.emplace_back(2 * uniform(r) - 1, 2 * uniform(r) - 1, 2 * uniform(r) - 1);
  return cloud;
}

std::vector<Vec3> gaussian_cloud(int n, gsl_rng* r) {
  std::vector<Vec3> cloud;
  cloud.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double x = gsl_ran_gaussian(r, 1.0);
    const double y = gsl_ran_gaussian(r, 1.0);
    const double z = gsl_ran_gaussian(r, 1.0);
    cloud.emplace_back(x, y, z);
  }
  return cloud;
}

/// Uniform in the unit disk of the plane z = 0.
std::vector<Vec3> disk_cloud(int n, gsl_rng* r) {
  std::vector<Vec3> cloud;
  cloud.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double radius = std::sqrt(uniform(r));
    const double angle = 2 * M_PI * uniform(r);
    cloud.emplace_back(radius * std::cos(angle), radius * std::sin(angle), 0.0);
  }
  return cloud;
}

/// Uniform on the segment [-1, 1] of the x axis.
std::vector<Vec3> segment_cloud(int n, gsl_rng* r) {
  std::vector<Vec3> cloud;
  cloud.reserve(n);
  for (int i = 0; i < n; ++i)
    cloud.emplace_back(2 * uniform(r) - 1, 0.0, 0.0);
  return cloud;
}

/// n points drawn from three distinct points of the unit sphere.
std::vector<Vec3> duplicate_cloud(int n, gsl_rng* r) {
  const Vec3 distinct[3] = {unit_vector(r), unit_vector(r), unit_vector(r)};
  std::vector<Vec3> cloud;
  cloud.reserve(n);
  for (int i = 0; i < n; ++i)
    cloud.push_back(distinct[gsl_rng_uniform_int(r, 3)]);
  return cloud;
}

}  // namespace

namespace {

/// The family registry's generated shapes: one row each (the ShapeKind, what it makes, its
/// vertex count when the family gives none, its generator). A new generated shape is its
/// generator and one row here; family_shapes, generate_shape and the experiment parser follow.
/// Rows a family cannot name (prism, pyramid: parts of the contact families) come last. A row
/// ending in `…, nameable, body_cloud` differs from the defaults (nameable, not a body cloud):
/// `true, true` for the clouds a scene's bodies may draw too.
constexpr ShapeGenerator kShapeGenerators[] = {
    {ShapeKind::sphere_points, "points uniform on the unit sphere", 32,
     [](int n, RandomStream& r, double) { return sphere_cloud(n, r.gsl); }, true, true},
    {ShapeKind::ball_points, "points uniform in the unit ball", 32,
     [](int n, RandomStream& r, double) { return ball_cloud(n, r.gsl); }, true, true},
    {ShapeKind::cube_points, "points uniform in the cube [-1, 1]^3", 32,
     [](int n, RandomStream& r, double) { return cube_cloud(n, r.gsl); }, true, true},
    {ShapeKind::gaussian, "standard normal cloud", 32,
     [](int n, RandomStream& r, double) { return gaussian_cloud(n, r.gsl); }, true, true},
    {ShapeKind::box, "demo box (8 vertices)", 8,
     [](int, RandomStream&, double) { return points_of(shapes::box()); }},
    {ShapeKind::cone, "demo cone (apex and a ring)", 33,
     [](int n, RandomStream&, double) { return points_of(shapes::cone(std::max(n, 4))); }},
    {ShapeKind::cylinder, "demo cylinder (two rings)", 64,
     [](int n, RandomStream&, double) {
       return points_of(shapes::cylinder(std::max(n + (n & 1), 6)));
     }},
    {ShapeKind::uv_sphere, "demo UV sphere", 482,
     [](int n, RandomStream&, double) { return points_of(shapes::uv_sphere(std::max(n, 6))); }},
    {ShapeKind::flat_points,
     "points uniform in the unit disk of the plane z = 0 (exactly coplanar)", 32,
     [](int n, RandomStream& r, double) { return disk_cloud(n, r.gsl); }, true, true},
    {ShapeKind::collinear_points, "points uniform on the segment [-1, 1] of the x axis", 32,
     [](int n, RandomStream& r, double) { return segment_cloud(n, r.gsl); }, true, true},
    {ShapeKind::duplicate_points, "n points drawn from three distinct points on the unit sphere",
     32, [](int n, RandomStream& r, double) { return duplicate_cloud(n, r.gsl); }},
    {ShapeKind::single_point, "one point at the origin", 32,
     [](int, RandomStream&, double) { return std::vector<Vec3>{Vec3::Zero()}; }},
    {ShapeKind::sliver, "box of extents 1 x 1 x 1/aspect", 32,
     [](int, RandomStream&, double aspect) {
       return points_of(shapes::box(Vec3(1, 1, 1 / aspect)));
     },
     true, true},
    {ShapeKind::sphere, "sphere-swept point (a ball of the family's radius)", 32,
     [](int, RandomStream&, double) { return std::vector<Vec3>{Vec3::Zero()}; }},
    {ShapeKind::capsule, "sphere-swept segment (+-1, 0, 0)", 32,
     [](int, RandomStream&, double) {
       return std::vector<Vec3>{Vec3(-1, 0, 0), Vec3(1, 0, 0)};
     }},
    {ShapeKind::prism, "", 32,
     [](int, RandomStream&, double) { return contact_piece(ShapeKind::prism, 1); }, false, true},
    {ShapeKind::pyramid, "", 32,
     [](int, RandomStream&, double) { return contact_piece(ShapeKind::pyramid, 1); }, false, true},
    {ShapeKind::segment, "", 2,
     [](int, RandomStream&, double) { return contact_piece(ShapeKind::segment, 1); }, false},
    {ShapeKind::needle, "", 3,
     [](int, RandomStream&, double a) { return contact_piece(ShapeKind::needle, a); }, false},
    {ShapeKind::rod, "", 12,
     [](int, RandomStream&, double a) { return contact_piece(ShapeKind::rod, a); }, false},
    {ShapeKind::wedge, "", 6,
     [](int, RandomStream&, double a) { return contact_piece(ShapeKind::wedge, a); }, false},
    {ShapeKind::plate, "", 8,
     [](int, RandomStream&, double a) { return contact_piece(ShapeKind::plate, a); }, false},
};

}  // namespace

std::span<const ShapeGenerator> shape_generators() {
  return kShapeGenerators;
}

const ShapeGenerator* find_shape_generator(ShapeKind kind) {
  for (const ShapeGenerator& g : kShapeGenerators)
    if (g.kind == kind) return &g;
  return nullptr;
}

const ShapeGenerator* find_shape_generator(std::string_view name) {
  // `ball` is a sphere-swept point in experiment files as in scene files; `sphere`, the name
  // the archives record for it, stays a synonym.
  if (name == "ball") return find_shape_generator(ShapeKind::sphere);
  for (const ShapeGenerator& g : kShapeGenerators)
    if (g.nameable && to_string(g.kind) == name) return &g;
  return nullptr;
}

const ShapeGenerator* find_body_cloud(std::string_view name) {
  for (const ShapeGenerator& g : kShapeGenerators)
    if (g.body_cloud && to_string(g.kind) == name) return &g;
  return nullptr;
}

std::vector<Vec3> generate_shape(ShapeKind kind, int n, RandomStream& stream, double aspect) {
  if (n < 1) throw std::invalid_argument("generate_shape: vertex count must be at least 1");
  if (kind == ShapeKind::from_file || kind == ShapeKind::mesh)
    throw std::invalid_argument("generate_shape: this shape's clouds come from the family's files");
  const ShapeGenerator* generator = find_shape_generator(kind);
  if (!generator) throw std::invalid_argument("generate_shape: unknown shape kind");
  return generator->generate(n, stream, aspect);
}

namespace {

/// Placement mode of one case (mixed draws overlapping with its fraction).
Placement draw_placement(gsl_rng* r, const PlacementSpec& placement) {
  switch (placement.mode) {
    case PlacementMode::separated:
      return Placement::separated;
    case PlacementMode::overlapping:
      return Placement::overlapping;
    case PlacementMode::touching:
      return Placement::touching;
    case PlacementMode::random:
      return Placement::random;
    case PlacementMode::mixed:
      return uniform(r) < placement.overlapping_fraction ? Placement::overlapping
                                                         : Placement::separated;
  }
  throw std::invalid_argument("generate_case: unknown placement mode " +
                              std::to_string(static_cast<int>(placement.mode)));
}

/// The drawn gap relative to size: > 0 separated, < 0 overlapping, 0 otherwise.
double draw_gap(gsl_rng* r, Placement mode, const PlacementSpec& placement) {
  if (mode == Placement::separated) return log_uniform(r, placement.gap);
  if (mode == Placement::overlapping) return -log_uniform(r, placement.depth);
  return 0;
}

/// A sphere-swept shape's radius in shape units (before scaling): 0 without a radius (no draw,
/// so families without radii keep their random streams), else log-uniform in the range.
double draw_radius(gsl_rng* r, const Interval& range) {
  return range.hi == 0 ? 0.0 : log_uniform(r, range);
}

/// Two generated shapes, B placed along a random axis by the drawn gap, or at random.
/// Sphere-swept shapes are placed by the extents of the swept shapes (cores grown by radii).
void place_generated_pair(RandomStream& stream, const FamilySpec& family, GeneratedCase& out) {
  gsl_rng* r = stream.gsl;
  CaseRecord& rec = out.record;
  const int n_a = log_uniform_count(r, family.vertices_a);
  const int n_b = log_uniform_count(r, family.vertices_b);
  const double ratio = log_uniform(r, family.scale_ratio);
  out.a = make_shape(stream, family.shape_a, n_a, family, family.scale);
  out.b = make_shape(stream, family.shape_b, n_b, family, family.scale * ratio);
  rec.radius_a = draw_radius(r, family.radius_a) * family.scale;
  rec.radius_b = draw_radius(r, family.radius_b) * family.scale * ratio;

  // Both vertex means are at the origin now; B moves along a random axis u.
  const PlacementSpec& placement = family.placement;
  const double size = pair_size(out.a, out.b, rec.radius_a, rec.radius_b);
  Vec3 translation = Vec3::Zero();
  const Placement mode = draw_placement(r, placement);
  if (mode == Placement::random) {
    const double half_width = placement.spread * size;
    for (int k = 0; k < 3; ++k)
      translation[k] = (2 * uniform(r) - 1) * half_width;
  } else {
    const Vec3 u = unit_vector(r);
    // gap > 0: B's extent along u starts gap·size after A's; gap < 0: they overlap by −gap·size.
    const double gap = draw_gap(r, mode, placement);
    const double shift = (max_projection(out.a, u) + rec.radius_a) + gap * size -
                         (min_projection(out.b, u) - rec.radius_b);
    translation = shift * u;
    rec.intended_gap = gap;
    out.direction = u;
  }
  for (Vec3& p : out.b)
    p += translation;
  rec.placement = mode;
}

/// A contact configuration, turned by a signed axis permutation (exact; the thin contacts as
/// the family's `rotate` says), B moved by ε·size along the contact normal as the placement
/// says, then scaled.
void place_contact_pair(gsl_rng* r, const FamilySpec& family, GeneratedCase& out) {
  CaseRecord& rec = out.record;
  const ContactType type = family.contact_any
                               ? kExactContacts[gsl_rng_uniform_int(r, std::size(kExactContacts))]
                               : family.contact;
  ContactPair pair = build_contact(type, r, family);
  rec.shape_a = pair.shape_a;
  rec.shape_b = pair.shape_b;
  // Scaling B about the contact point (the origin) keeps the contact.
  const double ratio = log_uniform(r, family.scale_ratio);
  for (Vec3& p : pair.b)
    p *= ratio;
  // The thin contacts turn as the family's `rotate` says (any rotation by default, so that
  // their needles lie in no coordinate plane); the others by an exact axis permutation.
  const bool thin = !exact_contact(type) && type != ContactType::parallel_edges;
  const Mat3 turn = thin ? draw_rotation(r, family.rotation) : random_axis_rotation(r);
  for (auto* cloud : {&pair.a, &pair.b})
    for (Vec3& p : *cloud)
      p = turn * p;
  const Vec3 normal = turn * Vec3::UnitZ();

  const Placement mode = draw_placement(r, family.placement);
  const double gap = draw_gap(r, mode, family.placement);
  const double shift = gap * pair_size(pair.a, pair.b);
  if (shift != 0)
    for (Vec3& p : pair.b)
      p += shift * normal;
  for (auto* cloud : {&pair.a, &pair.b})
    for (Vec3& p : *cloud)
      p *= family.scale;
  out.a = std::move(pair.a);
  out.b = std::move(pair.b);
  out.direction = normal;
  rec.placement = mode;
  rec.intended_gap = gap;
}

/// A pair from the family's cases file, exactly as stored.
void take_stored_pair(const FamilySpec& family, std::uint64_t case_id, GeneratedCase& out) {
  const StoredPair& pair = family.stored[case_id % family.stored.size()];
  out.a = pair.a;
  out.b = pair.b;
  out.record.radius_a = pair.radius_a;
  out.record.radius_b = pair.radius_b;
  out.warm = pair.warm;
  out.record.placement = Placement::as_given;
}

}  // namespace

namespace {

/// Moves or scales the whole pair by a geometry-sweep value: the same base pair is run once
/// per value. The offset direction is drawn from the base pair's own generator.
void apply_geometry_sweep(const GeometrySweep& sweep, double value, gsl_rng* r,
                          GeneratedCase& out) {
  if (sweep.parameter == "offset") {
    const Vec3 t = value * unit_vector(r);
    for (auto* cloud : {&out.a, &out.b})
      for (Vec3& p : *cloud)
        p += t;
  } else {
    for (auto* cloud : {&out.a, &out.b})
      for (Vec3& p : *cloud)
        p *= value;
    out.record.scale *= value;
    out.record.radius_a *= value;
    out.record.radius_b *= value;
  }
}

/// A nonconvex family's pair: its meshes, scaled, with their vertices as the clouds (the pair
/// is posed by its kind: placement random, no intended gap).
void draw_mesh_pair(RandomStream& stream, const FamilySpec& family, GeneratedCase& out) {
  MeshPair pair = draw_nonconvex_pair(*family.nonconvex, family.closed_meshes, stream);
  for (TriangleMesh* mesh : {&pair.a, &pair.b})
    for (Vec3& v : mesh->vertices)
      v *= family.scale;
  out.a = pair.a.vertices;
  out.b = pair.b.vertices;
  out.mesh_a = std::move(pair.a);
  out.mesh_b = std::move(pair.b);
  out.record.placement = Placement::random;
  out.record.intended_gap = std::numeric_limits<double>::quiet_NaN();
}

/// The posed meshes must still bound solids: rounding the posed coordinates could make a
/// nearly touching part of the surface cross itself, and the truth would then not be a solid's.
void validate_case_meshes(const GeneratedCase& out, std::uint64_t case_id) {
  const std::string id = "generate_case " + std::to_string(case_id);
  exact::validate_closed_mesh(*out.mesh_a, id + ", mesh A");
  exact::validate_closed_mesh(*out.mesh_b, id + ", mesh B");
}

}  // namespace

std::span<const FamilyShapeInfo> family_shapes() {
  // The pair sources: families whose pairs are built or read whole, not drawn shape by shape.
  static constexpr FamilyShapeInfo kPairSources[] = {
      {"contact",
       "pairs built in exact contact (face-face, edge-edge, ...), then moved by epsilon"},
      {"file", "the pairs of a JSON-lines cases file (path)"},
      {"stream", "the narrow-phase queries a scene archive recorded (path; cold, as queried)"},
      {"mesh", "the vertices of mesh files (path: one .off/.obj/.ply/.stl file or a folder)"},
      {"real_object",
       "convex hulls of the real meshes of Debian's libcgal-demo (objects: names or \"all\"), "
       "at unit size"},
      {"nonconvex",
       "pairs of closed non-convex meshes queried as solids (pair: rings, peg-in-hole, "
       "ball-in-cup, l-in-l, stars, nested, box-in-notch, meshes)"},
  };
  static const std::vector<FamilyShapeInfo> shapes = [] {
    std::vector<FamilyShapeInfo> out;
    for (const ShapeGenerator& g : kShapeGenerators)
      if (g.nameable) out.push_back({to_string(g.kind), g.description});
    out.insert(out.end(), std::begin(kPairSources), std::end(kPairSources));
    return out;
  }();
  return shapes;
}

void RandomStreamFree::operator()(RandomStream* stream) const {
  delete stream;
}

OwnedRandomStream case_stream(std::uint64_t seed, std::uint64_t id) {
  return OwnedRandomStream(new RandomStream(case_stream_seed(seed, id)));
}

GeneratedCase generate_case(const ExperimentConfig& config, std::uint64_t case_id) {
  if (config.families.empty())
    throw std::invalid_argument("generate_case: the experiment has no families");
  // With a geometry sweep, row case_id is base pair case_id / n under value case_id % n.
  const std::uint64_t n_values = config.geometry_sweep ? config.geometry_sweep->values.size() : 1;
  const std::uint64_t base_id = case_id / n_values;
  const std::uint64_t value_index = case_id % n_values;
  const OwnedRandomStream stream = case_stream(config.seed, base_id);
  gsl_rng* r = stream->gsl;

  GeneratedCase out;
  CaseRecord& rec = out.record;
  rec.case_id = case_id;
  const std::size_t family_index = draw_family(r, config.families);
  const FamilySpec& family = config.families[family_index];
  rec.family = static_cast<std::uint32_t>(family_index);
  rec.shape_a = family.shape_a;
  rec.shape_b = family.shape_b;
  rec.scale = family.scale;

  if (family.nonconvex) {
    draw_mesh_pair(*stream, family, out);
  } else if (!family.stored.empty()) {
    take_stored_pair(family, base_id, out);
  } else if (family.contact != ContactType::none) {
    place_contact_pair(r, family, out);
  } else {
    place_generated_pair(*stream, family, out);
  }
  // Large offsets: the whole pair moves, which changes no exact answer but every rounding.
  if (family.offset.hi > 0) {
    const Vec3 t = log_uniform(r, family.offset) * unit_vector(r);
    for (auto* cloud : {&out.a, &out.b})
      for (Vec3& p : *cloud)
        p += t;
  }

  if (config.geometry_sweep) {
    apply_geometry_sweep(*config.geometry_sweep, config.geometry_sweep->values[value_index], r,
                         out);
    rec.family = static_cast<std::uint32_t>(family_index * n_values + value_index);
  }

  rec.vertices_a = static_cast<std::int32_t>(out.a.size());
  rec.vertices_b = static_cast<std::int32_t>(out.b.size());
  rec.size = pair_size(out.a, out.b, rec.radius_a, rec.radius_b);
  for (const auto* cloud : {&out.a, &out.b})
    if (const std::string problem = describe_invalid_cloud(*cloud); !problem.empty())
      throw std::runtime_error("generate_case " + std::to_string(case_id) + ": " + problem);
  if (out.mesh_a) validate_case_meshes(out, case_id);
  return out;
}

}  // namespace gjklab::experiment
