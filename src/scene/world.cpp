#include "gjklab/scene/world.hpp"

#include "contact_manifold.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "gjklab/gjk/epa.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/subalgorithms.hpp"
#include "gjklab/scene/compound.hpp"

namespace gjklab::scene {

using detail::ManifoldPoint;

namespace {

using Clock = std::chrono::steady_clock;
std::int64_t nanoseconds_since(Clock::time_point t0) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0).count();
}

std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// The scene's own query (kDefaultNarrowPhase): from `warm` when not empty, else cold.
DistanceResult default_narrow_phase(const Polytope& a, const Polytope& b,
                                    std::span<const SimplexVertex> warm,
                                    const GjkDistanceOptions& options) {
  return warm.empty() ? gjk_distance_with<JohnsonSubAlgorithm>(a, b, options)
                      : gjk_distance_warm_with<JohnsonSubAlgorithm>(a, b, warm, options);
}

void check_settings(const WorldSettings& s) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  require(s.gravity.allFinite(), "gravity must be finite");
  require(s.dt > 0 && std::isfinite(s.dt), "dt must be positive and finite");
  require(s.solver_iterations >= 1 && s.solver_iterations <= 1000,
          "solver_iterations must be in [1, 1000]");
  require(s.position_iterations >= 0 && s.position_iterations <= 1000,
          "position_iterations must be in [0, 1000]");
  require(s.contact_margin >= 0 && std::isfinite(s.contact_margin),
          "contact_margin must be finite and ≥ 0");
  require(s.slop >= 0 && std::isfinite(s.slop), "slop must be finite and ≥ 0");
  require(s.baumgarte >= 0 && s.baumgarte <= 1, "baumgarte must be in [0, 1]");
  require(s.restitution_threshold >= 0 && std::isfinite(s.restitution_threshold),
          "restitution_threshold must be finite and ≥ 0");
  require(s.threads >= 1 && s.threads <= 1024, "threads must be in [1, 1024]");
}

}  // namespace

World::World(WorldSettings settings)
    : settings_(settings), broad_(settings.broad_phase, settings.grid_cell_size) {
  check_settings(settings_);
}

void World::set_threads(int threads) {
  WorldSettings s = settings_;
  s.threads = threads;
  check_settings(s);
  settings_.threads = threads;
}

std::uint32_t World::add(RigidBody body) {
  if (!body.shape) throw std::invalid_argument("a body needs a shape");
  if (body.compound && body.compound->envelope != body.shape)
    throw std::invalid_argument("a compound body's shape must be its envelope");
  bodies_.push_back(std::move(body));
  return static_cast<std::uint32_t>(bodies_.size() - 1);
}

void World::bounding_boxes(double margin, std::vector<Aabb>& out) const {
  out.resize(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const RigidBody& b = bodies_[i];
    const Polytope& p = b.shape->polytope;
    const Vec3 centre = 0.5 * (p.box_lower() + p.box_upper());
    const Vec3 half = 0.5 * (p.box_upper() - p.box_lower());
    // The rotated box's extent along each world axis: |R| times the half extents.
    const Vec3 world_half = b.pose.rotation.cwiseAbs() * half +
                            Vec3::Constant(b.shape->swept_radius + margin + sweep_distance(i));
    const Vec3 world_centre = b.pose.apply(centre);
    out[i] = {world_centre - world_half, world_centre + world_half};
  }
}

double World::sweep_distance(std::uint32_t i) const {
  // How far any point of the body can move in one step at its current velocity (length
  // units): the speculative reach that keeps fast bodies from passing into each other.
  const RigidBody& b = bodies_[i];
  const double reach =
      (b.velocity.norm() + b.angular_velocity.norm() * b.shape->radius) * settings_.dt;
  return std::isfinite(reach) ? reach : 0.0;
}

const Polytope& World::world_hull(std::uint32_t i) {
  if (world_hull_step_[i] != step_count_ + 1 || !world_hulls_[i]) {
    world_hulls_[i].emplace(bodies_[i].shape->polytope.transformed(bodies_[i].pose));
    world_hull_step_[i] = step_count_ + 1;
  }
  return *world_hulls_[i];
}

std::optional<Penetration> World::penetration(const Polytope& pa, const Polytope& pb,
                                              const DistanceResult& r) const {
  if (settings_.depth) return settings_.depth->run(pa, pb);
  // EPA starts from a GJK simplex that encloses the origin: the query's own, or a cold
  // gjk-johnson's when the supplied query keeps none.
  DistanceResult start;
  const bool own_simplex = !settings_.query || settings_.query->warm_startable;
  if (!own_simplex) {
    start = default_narrow_phase(pa, pb, {}, settings_.gjk);
    if (!start.intersect) return std::nullopt;  // the two disagree: no simplex to start from
  }
  EpaPolytope ws;
  const EpaResult e = epa_from_gjk(pa, pb, own_simplex ? r : start, EpaOptions{}, ws);
  return Penetration{e.depth, e.normal, 0.5 * (e.witness_a + e.witness_b),
                     e.termination == Termination::converged};
}

DistanceResult World::narrow_query(const Polytope& pa, const Polytope& pb,
                                   std::span<const SimplexVertex> warm) const {
  return settings_.query ? settings_.query->run(pa, pb, warm)
                         : default_narrow_phase(pa, pb, warm, settings_.gjk);
}

void World::collide(std::uint32_t ia, std::uint32_t ib, std::vector<SimplexVertex>& simplex,
                    PairOutcome& out) const {
  out.a = ia;
  out.b = ib;
  if (bodies_[ia].compound || bodies_[ib].compound) {
    simplex.clear();  // piece pairs run cold: nothing to carry (compound.hpp)
    collide_pieces(ia, ib, out);
    return;
  }
  const Polytope& pa = *world_hulls_[ia];
  const Polytope& pb = *world_hulls_[ib];
  const bool warm_startable = !settings_.query || settings_.query->warm_startable;
  const std::span<const SimplexVertex> warm = settings_.warm_start && warm_startable
                                                  ? std::span<const SimplexVertex>(simplex)
                                                  : std::span<const SimplexVertex>();
  const DistanceResult r = narrow_query(pa, pb, warm);
  out.iterations = r.iterations;
  if (query_log_) {
    QueryRecord& q = out.query;
    q.a = ia;
    q.b = ib;
    q.warm_size = static_cast<int>(warm.size());
    for (std::size_t k = 0; k < warm.size() && k < 4; ++k) {
      q.warm_index_a[k] = warm[k].index_a;
      q.warm_index_b[k] = warm[k].index_b;
    }
    q.iterations = r.iterations;
    q.intersect = r.intersect;
    q.distance = r.distance;
  }
  if (settings_.measure_cold)
    out.iterations_cold = warm_startable ? narrow_query(pa, pb, {}).iterations
                                         : r.iterations;  // the query always runs cold
  if (r.termination != Termination::converged) ++out.failed;
  const auto kept = r.simplex.vertices();
  simplex.assign(kept.begin(), kept.end());
  convex_contacts(*bodies_[ia].shape, pa, *bodies_[ib].shape, pb, r, out);
}

void World::convex_contacts(const ConvexShape& sa, const Polytope& pa, const ConvexShape& sb,
                            const Polytope& pb, const DistanceResult& r, PairOutcome& out) const {
  const std::uint32_t ia = out.a, ib = out.b;
  // Contacts within the margin plus the distance the pair can close in this step; those
  // beyond the margin are speculative (negative depth, see the solver's target). Swept shapes:
  // GJK measured their cores, whose surfaces lie `radii` (length units) closer together.
  const double margin = settings_.contact_margin + sweep_distance(ia) + sweep_distance(ib);
  const double ra = sa.swept_radius, rb = sb.swept_radius;
  const double radii = ra + rb;
  if (!r.intersect && !(r.distance < margin + radii)) return;
  Vec3 normal;
  ManifoldPoint single;
  if (r.intersect) {
    const std::optional<Penetration> p = penetration(pa, pb, r);
    ++out.epa;
    if (!p || !p->converged) ++out.failed;
    if (!p) return;  // no depth for this pair: no contact rather than a guessed one
    normal = p->normal;
    single = {p->point + 0.5 * (ra - rb) * normal, p->depth + radii};
  } else {
    const Vec3 ab = r.witness_b - r.witness_a;
    const double n = ab.norm();
    // A zero distance that GJK did not call contact: fall back to the centres' direction.
    normal =
        n > 0 ? Vec3(ab / n) : Vec3(bodies_[ib].pose.translation - bodies_[ia].pose.translation);
    single = {0.5 * (r.witness_a + r.witness_b), radii - r.distance};
    if (radii > 0 && n > 0) single.point += 0.5 * (ra - rb) * normal;
  }
  if (!normal.allFinite() || !(normal.norm() > 0) || !single.point.allFinite() ||
      !std::isfinite(single.depth))
    return;  // a failed query gives no contact rather than a NaN impulse
  normal.normalize();
  out.normal = normal;
  out.points = detail::clip_manifold(sa, pa, bodies_[ia].pose.rotation, sb, pb,
                                     bodies_[ib].pose.rotation, out.normal, margin);
  // The clipped points measure depth against one face. When the deepest is shallower than the
  // pair's GJK/EPA depth by more than the slop (length units), that face does not carry the
  // contact (a body pushed through a slab thinner than itself, past the face's plane) and the
  // manifold would hide the penetration: the single GJK/EPA point is used instead.
  double deepest = -std::numeric_limits<double>::infinity();
  for (const ManifoldPoint& m : out.points)
    deepest = std::max(deepest, m.depth);
  if (out.points.empty() || deepest < single.depth - settings_.slop) {
    out.points.assign(1, single);
    out.normal = normal;
  }
}

void World::merge(const PairOutcome& out, PairCache& cache, StepStats& stats, double& iterations,
                  double& iterations_cold) {
  stats.narrow_queries += out.queries;
  iterations += out.iterations;
  iterations_cold += out.iterations_cold;
  stats.failed_queries += out.failed;
  stats.epa_queries += out.epa;
  if (query_log_ && !out.compound) query_log_->push_back(out.query);
  if (out.points.empty()) {
    cache.points.clear();
    return;
  }
  const std::size_t first = contacts_.size();
  for (std::size_t k = 0; k < out.points.size(); ++k) {
    const ManifoldPoint& m = out.points[k];
    Contact c;
    c.a = out.a;
    c.b = out.b;
    c.point = m.point;
    c.normal = out.normals.empty() ? out.normal : out.normals[k];
    c.depth = m.depth;
    contacts_.push_back(c);
  }
  warm_start_impulses(first, out.points.size(), cache);
  pair_ranges_.push_back({pair_key(out.a, out.b), {first, out.points.size()}});
}

void World::warm_start_impulses(std::size_t first, std::size_t count, const PairCache& cache) {
  // A new point inherits the impulses of the old point nearest to it in a's body frame, when
  // that is within 5 % of a's size: the same contact feature, moved a little.
  const RigidBody& a = bodies_[contacts_[first].a];
  const double tolerance = 0.05 * a.shape->size;
  for (std::size_t k = first; k < first + count; ++k) {
    Contact& c = contacts_[k];
    const Vec3 local = a.pose.rotation.transpose() * (c.point - a.pose.translation);
    const CachedPoint* match = nullptr;
    double best = tolerance * tolerance;
    for (const CachedPoint& p : cache.points) {
      const double d = (p.local_a - local).squaredNorm();
      if (d <= best) best = d, match = &p;
    }
    if (match) {
      c.normal_impulse = match->normal_impulse;
      c.tangent_impulse[0] = match->tangent_impulse[0];
      c.tangent_impulse[1] = match->tangent_impulse[1];
    }
  }
}

void World::store_impulses(PairCache& cache, std::size_t first, std::size_t count) const {
  cache.points.clear();
  for (std::size_t k = first; k < first + count; ++k) {
    const Contact& c = contacts_[k];
    const RigidBody& a = bodies_[c.a];
    cache.points.push_back({a.pose.rotation.transpose() * (c.point - a.pose.translation),
                            c.normal_impulse,
                            {c.tangent_impulse[0], c.tangent_impulse[1]}});
  }
}

CarriedState World::carried_state() const {
  CarriedState out;
  out.time = time_;
  out.steps = step_count_;
  for (const auto& [key, cache] : cache_) {
    PairState p;
    p.a = static_cast<std::uint32_t>(key >> 32);
    p.b = static_cast<std::uint32_t>(key & 0xffffffffu);
    p.simplex = cache.simplex;
    for (const CachedPoint& c : cache.points) {
      p.local_a.push_back(c.local_a);
      p.impulses.push_back({c.normal_impulse, c.tangent_impulse[0], c.tangent_impulse[1]});
    }
    out.pairs.push_back(std::move(p));
  }
  std::sort(out.pairs.begin(), out.pairs.end(), [](const PairState& x, const PairState& y) {
    return pair_key(x.a, x.b) < pair_key(y.a, y.b);
  });
  return out;
}

void World::restore(const CarriedState& state) {
  cache_.clear();
  for (const PairState& p : state.pairs) {
    if (p.a >= bodies_.size() || p.b >= bodies_.size() || p.local_a.size() != p.impulses.size())
      throw std::invalid_argument("a saved pair names a body the world does not have");
    PairCache& cache = cache_[pair_key(p.a, p.b)];
    cache.simplex = p.simplex;
    for (std::size_t k = 0; k < p.local_a.size(); ++k)
      cache.points.push_back(
          {p.local_a[k], p.impulses[k][0], {p.impulses[k][1], p.impulses[k][2]}});
    // The pairs of the last step carry its number (narrow_phase drops the others).
    cache.step = state.steps;
  }
  time_ = state.time;
  step_count_ = state.steps;
}

void World::narrow_phase(const std::vector<BodyPair>& pairs, StepStats& stats) {
  contacts_.clear();
  pair_ranges_.clear();
  double iterations = 0, iterations_cold = 0;
  // Serial preparation: every pair's cache entry and both world hulls exist before the
  // queries, which then only read shared state (and write their own pair's simplex).
  std::vector<PairCache*> caches;
  caches.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    PairCache& cache = cache_[pair_key(i, j)];
    cache.step = step_count_ + 1;
    caches.push_back(&cache);
    for (std::uint32_t k : {i, j}) {
      if (bodies_[k].compound)
        world_pieces(k);
      else
        world_hull(k);
    }
  }
  std::vector<PairOutcome> outcomes(pairs.size());
  auto run = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
      collide(pairs[k].first, pairs[k].second, caches[k]->simplex, outcomes[k]);
  };
  const std::size_t n_threads =
      std::min<std::size_t>(static_cast<std::size_t>(settings_.threads), pairs.size() / 16 + 1);
  if (n_threads <= 1) {
    run(0, pairs.size());
  } else {
    // Contiguous blocks, one per thread; the merge below is in pair order whatever the split.
    std::vector<std::thread> workers;
    const std::size_t block = (pairs.size() + n_threads - 1) / n_threads;
    for (std::size_t t = 1; t < n_threads; ++t)
      workers.emplace_back(run, std::min(pairs.size(), t * block),
                           std::min(pairs.size(), (t + 1) * block));
    run(0, std::min(pairs.size(), block));
    for (std::thread& w : workers)
      w.join();
  }
  for (std::size_t k = 0; k < pairs.size(); ++k)
    merge(outcomes[k], *caches[k], stats, iterations, iterations_cold);
  // Pairs that left the broad phase lose their simplex and impulses.
  std::erase_if(cache_, [&](const auto& kv) { return kv.second.step != step_count_ + 1; });
  if (stats.narrow_queries > 0) {
    stats.iterations_mean = iterations / static_cast<double>(stats.narrow_queries);
    stats.iterations_cold_mean = iterations_cold / static_cast<double>(stats.narrow_queries);
  }
}

StepStats World::step() {
  StepStats stats;
  world_hulls_.resize(bodies_.size());
  world_hull_step_.resize(bodies_.size(), 0);
  world_pieces_.resize(bodies_.size());
  auto t0 = Clock::now();
  bounding_boxes(settings_.contact_margin, boxes_);
  broad_.find_pairs(boxes_, pairs_);
  std::erase_if(pairs_, [&](const BodyPair& p) {
    return bodies_[p.first].is_static() && bodies_[p.second].is_static();
  });
  stats.candidate_pairs = pairs_.size();
  stats.broadphase_ns = nanoseconds_since(t0);

  t0 = Clock::now();
  narrow_phase(pairs_, stats);
  stats.contacts = contacts_.size();
  stats.narrowphase_ns = nanoseconds_since(t0);

  t0 = Clock::now();
  for (RigidBody& b : bodies_)
    if (!b.is_static()) b.velocity += settings_.gravity * settings_.dt;
  solve_velocities();
  for (const auto& [key, range] : pair_ranges_)
    store_impulses(cache_.at(key), range.first, range.second);
  std::vector<Vec3> dv, dw;
  correct_positions(dv, dw);
  integrate(dv, dw);
  stats.solver_ns = nanoseconds_since(t0);

  for (RigidBody& b : bodies_)
    b.touching = false;
  for (const Contact& c : contacts_)
    if (c.depth >= 0) bodies_[c.a].touching = bodies_[c.b].touching = true;
  time_ += settings_.dt;
  ++step_count_;
  return stats;
}

double World::max_penetration() const {
  double m = 0;
  for (const Contact& c : contacts_)
    m = std::max(m, c.depth);
  return m;
}

double World::kinetic_energy() const {
  double e = 0;
  for (const RigidBody& b : bodies_) {
    if (b.is_static()) continue;
    const Mat3 inertia =
        b.pose.rotation * b.inverse_inertia_body.inverse() * b.pose.rotation.transpose();
    e += 0.5 * b.mass * b.velocity.squaredNorm() +
         0.5 * b.angular_velocity.dot(inertia * b.angular_velocity);
  }
  return e;
}

double World::potential_energy() const {
  double e = 0;
  for (const RigidBody& b : bodies_)
    if (!b.is_static()) e -= b.mass * settings_.gravity.dot(b.pose.translation);
  return e;
}

Vec3 World::linear_momentum() const {
  Vec3 p = Vec3::Zero();
  for (const RigidBody& b : bodies_)
    if (!b.is_static()) p += b.mass * b.velocity;
  return p;
}

Vec3 World::angular_momentum() const {
  Vec3 l = Vec3::Zero();
  for (const RigidBody& b : bodies_) {
    if (b.is_static()) continue;
    const Mat3 inertia =
        b.pose.rotation * b.inverse_inertia_body.inverse() * b.pose.rotation.transpose();
    l += b.pose.translation.cross(b.mass * b.velocity) + inertia * b.angular_velocity;
  }
  return l;
}

bool World::finite() const {
  for (const RigidBody& b : bodies_)
    if (!b.pose.translation.allFinite() || !b.pose.rotation.allFinite() ||
        !b.velocity.allFinite() || !b.angular_velocity.allFinite())
      return false;
  return true;
}

}  // namespace gjklab::scene
