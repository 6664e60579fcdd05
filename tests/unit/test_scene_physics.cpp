// Scene physics: the checks of the classic demo's scene as tests. Energy never grows without
// restitution, momentum is conserved in free collisions, a stack of ten boxes stays at rest,
// and a small scene stays finite for 10⁴ frames.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/geometry/shapes.hpp"
#include "gjklab/scene/world.hpp"

using namespace gjklab;
using namespace gjklab::scene;

namespace {

std::shared_ptr<const ConvexShape> shape_of(const Polytope& p) {
  return make_convex_shape({p.vertices().begin(), p.vertices().end()});
}

/// A static ground: a 40 × 40 × 1 box whose top face is the plane z = 0.
void add_ground(World& world) {
  world.add(
      make_static_body(shape_of(shapes::box(Vec3(40, 40, 1))), Quat::Identity(), Vec3(0, 0, -0.5)));
}

Quat random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  return Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
}

}  // namespace

TEST_CASE("scene physics: energy never grows with restitution 0", "[unit][scene]") {
  // Unit cubes (isotropic inertia, so the rotation update conserves their kinetic energy
  // exactly) dropped at random orientations onto the ground and onto each other.
  WorldSettings s;
  s.broad_phase = BroadPhaseKind::grid;
  World world(s);
  add_ground(world);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto cube = shape_of(shapes::box());
  for (int i = 0; i < 12; ++i) {
    RigidBody b = make_dynamic_body(cube, 1000, random_rotation(rng),
                                    Vec3(1.6 * (i % 3) - 1.6, 1.6 * ((i / 3) % 2), 1 + 1.2 * i));
    b.velocity = Vec3(u(rng), u(rng), u(rng));
    b.angular_velocity = Vec3(u(rng), u(rng), u(rng));
    world.add(b);
  }
  const double scale = 1000 * 9.81 * 1.0;  // m g L of one cube (J)
  double energy = world.kinetic_energy() + world.potential_energy();
  const double initial = energy;
  double worst_growth = 0;
  std::size_t contacts_seen = 0;
  for (int frame = 0; frame < 600; ++frame) {
    const StepStats st = world.step();
    contacts_seen += st.contacts;
    const double now = world.kinetic_energy() + world.potential_energy();
    worst_growth = std::max(worst_growth, now - energy);
    energy = now;
  }
  INFO("largest growth in one frame: " << worst_growth << " J");
  // The positional correction lifts penetrating bodies by at most baumgarte · depth per step;
  // that potential energy (a few mJ here) is the only source, far below 10⁻³ m g L.
  CHECK(worst_growth < 1e-3 * scale);
  CHECK(energy < initial);
  CHECK(contacts_seen > 1000);
  CHECK(world.finite());
}

TEST_CASE("scene physics: momentum is conserved in free two-body collisions", "[unit][scene]") {
  WorldSettings s;
  s.gravity = Vec3::Zero();
  const auto cone = shape_of(shapes::cone());
  const auto box = shape_of(shapes::box(Vec3(1, 0.6, 0.8)));
  for (double restitution : {0.0, 0.5, 1.0}) {
    for (int correction : {0, 4}) {
      s.position_iterations = correction;
      World world(s);
      std::mt19937_64 rng(11);
      RigidBody a = make_dynamic_body(cone, 700, random_rotation(rng), Vec3(-2, 0.1, 0.05));
      RigidBody b = make_dynamic_body(box, 1500, random_rotation(rng), Vec3(2, -0.1, -0.1));
      a.velocity = Vec3(3, 0, 0.2);
      b.velocity = Vec3(-2, 0.1, 0);
      a.angular_velocity = Vec3(0, 1, 2);
      a.restitution = b.restitution = restitution;
      world.add(a);
      world.add(b);
      const Vec3 p0 = world.linear_momentum();
      const Vec3 l0 = world.angular_momentum();
      std::size_t contacts = 0;
      for (int frame = 0; frame < 240; ++frame)
        contacts += world.step().contacts;
      INFO("restitution " << restitution << ", position iterations " << correction);
      CHECK(contacts > 0);
      // The bodies must have exchanged momentum (they did collide) …
      CHECK((world.bodies()[0].velocity - Vec3(3, 0, 0.2)).norm() > 0.5);
      // … and the totals are kept to rounding (kg·m/s, kg·m²/s).
      CHECK((world.linear_momentum() - p0).norm() < 1e-9 * p0.norm() + 1e-9);
      // Impulses act in equal and opposite pairs at one point and the rotation update keeps
      // I ω, so angular momentum about the origin is kept to rounding too. The positional
      // correction moves centres of mass without changing velocities, which changes x × m v:
      // bounded by the (small) distance it moves them.
      const double bound = correction == 0 ? 1e-9 : 1e-3;
      CHECK((world.angular_momentum() - l0).norm() < bound * (l0.norm() + p0.norm()));
    }
  }
}

TEST_CASE("scene physics: a stack of 10 boxes stays at rest", "[unit][scene]") {
  // A tall stack is the sequential-impulse solver's hardest case (the impulses must travel
  // ten bodies down in one step): a short step and enough passes let it converge.
  WorldSettings s;
  s.dt = 1.0 / 480;
  s.solver_iterations = 50;
  World world(s);
  add_ground(world);
  const double size = 1.0;  // box side (m)
  const auto cube = shape_of(shapes::box(Vec3(size, size, size)));
  std::vector<std::uint32_t> ids;
  for (int i = 0; i < 10; ++i)
    ids.push_back(
        world.add(make_dynamic_body(cube, 500, Quat::Identity(), Vec3(0, 0, size * (0.5 + i)))));
  const Vec3 top0 = world.bodies()[ids.back()].pose.translation;
  double worst_penetration = 0;
  const int frames = static_cast<int>(std::lround(2.0 / s.dt));  // 2 s simulated
  for (int frame = 0; frame < frames; ++frame) {
    world.step();
    worst_penetration = std::max(worst_penetration, world.max_penetration());
  }
  const Vec3 top = world.bodies()[ids.back()].pose.translation;
  INFO("max penetration " << worst_penetration << " m, top drift " << (top - top0).norm() << " m");
  CHECK(worst_penetration < 0.01 * size);
  CHECK((top - top0).norm() < 0.01 * size);
  CHECK(world.contacts().size() >= 40);  // four points on each of the ten faces in contact
  for (std::uint32_t id : ids)
    CHECK(world.bodies()[id].velocity.norm() < 0.01);
}

TEST_CASE("scene physics: no NaN after 10^4 frames of a small scene", "[unit][scene]") {
  WorldSettings s;
  s.solver_iterations = 8;
  World world(s);
  add_ground(world);
  std::mt19937_64 rng(3);
  const std::vector<std::shared_ptr<const ConvexShape>> kinds = {
      shape_of(shapes::box()), shape_of(shapes::cone()), shape_of(shapes::cylinder(16)),
      shape_of(shapes::uv_sphere(42))};
  for (int i = 0; i < 8; ++i) {
    RigidBody b = make_dynamic_body(kinds[i % 4], 800, random_rotation(rng),
                                    Vec3(0.3 * (i % 2), 0.2 * (i % 3), 1 + 1.3 * i));
    b.restitution = 0.3;
    world.add(b);
  }
  double worst_penetration = 0;
  std::size_t failed = 0;
  for (int frame = 0; frame < 10000; ++frame) {
    const StepStats st = world.step();
    failed += st.failed_queries;
    worst_penetration = std::max(worst_penetration, world.max_penetration());
    if (!world.finite()) FAIL("non-finite state at frame " << frame);
  }
  INFO("failed queries " << failed << ", worst penetration " << worst_penetration);
  CHECK(world.finite());
  CHECK(worst_penetration < 0.1);
  CHECK(world.kinetic_energy() < 1.0);  // everything has come to rest on the ground (J)
}

TEST_CASE("scene physics: the broad phases give the same simulation; warm starts save iterations",
          "[unit][scene]") {
  auto run = [](BroadPhaseKind kind, bool warm, std::vector<StepStats>& stats) {
    WorldSettings s;
    s.broad_phase = kind;
    s.warm_start = warm;
    s.measure_cold = true;
    World world(s);
    add_ground(world);
    std::mt19937_64 rng(5);
    const auto cone = shape_of(shapes::cone());
    const auto cyl = shape_of(shapes::cylinder(24));
    for (int i = 0; i < 12; ++i)
      world.add(make_dynamic_body(i % 2 ? cone : cyl, 900, random_rotation(rng),
                                  Vec3(0.4 * (i % 3), 0.3 * (i % 4), 0.8 + 1.1 * i)));
    for (int frame = 0; frame < 300; ++frame)
      stats.push_back(world.step());
    return world.bodies();
  };
  std::vector<StepStats> sa, sg, ss, cold;
  const auto a = run(BroadPhaseKind::all_pairs, true, sa);
  const auto g = run(BroadPhaseKind::grid, true, sg);
  const auto s = run(BroadPhaseKind::sweep_and_prune, true, ss);
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].pose.translation == g[i].pose.translation);
    CHECK(a[i].pose.translation == s[i].pose.translation);
  }
  double warm_iterations = 0, cold_iterations = 0;
  std::size_t queries = 0;
  for (const StepStats& st : sa) {
    CHECK(st.candidate_pairs == st.narrow_queries);
    warm_iterations += st.iterations_mean * static_cast<double>(st.narrow_queries);
    cold_iterations += st.iterations_cold_mean * static_cast<double>(st.narrow_queries);
    queries += st.narrow_queries;
  }
  INFO("mean GJK iterations: warm " << warm_iterations / queries << ", cold "
                                    << cold_iterations / queries);
  CHECK(queries > 1000);
  CHECK(warm_iterations < cold_iterations);
  // Cold runs with measure_cold count the same queries twice: both means are equal.
  run(BroadPhaseKind::all_pairs, false, cold);
  for (const StepStats& st : cold)
    CHECK(st.iterations_mean == st.iterations_cold_mean);
}

TEST_CASE("scene physics: settings out of range are refused", "[unit][scene]") {
  WorldSettings s;
  s.dt = 0;
  CHECK_THROWS_AS(World(s), std::invalid_argument);
  s = {};
  s.solver_iterations = 0;
  CHECK_THROWS_AS(World(s), std::invalid_argument);
  s = {};
  s.baumgarte = 2;
  CHECK_THROWS_AS(World(s), std::invalid_argument);
}

TEST_CASE("scene physics: the scene's own narrow phase is the registry's algorithm of its name",
          "[unit][scene]") {
  // The scene layer names one query, its default; the registry's entry of that name, supplied
  // as the narrow phase, must give the same simulation bit for bit, warm starts included.
  const experiment::AlgorithmInfo* info = experiment::find_algorithm(kDefaultNarrowPhase);
  REQUIRE(info != nullptr);
  REQUIRE(info->narrow_phase != nullptr);
  auto run = [](std::optional<NarrowQuery> query) {
    WorldSettings s;
    s.query = std::move(query);
    World world(s);
    add_ground(world);
    std::mt19937_64 rng(11);
    const auto cone = shape_of(shapes::cone());
    const auto box = shape_of(shapes::box());
    for (int i = 0; i < 8; ++i)
      world.add(make_dynamic_body(i % 2 ? cone : box, 900, random_rotation(rng),
                                  Vec3(0.3 * (i % 3), 0.2 * (i % 4), 0.8 + 1.1 * i)));
    std::size_t queries = 0;
    for (int frame = 0; frame < 200; ++frame)
      queries += world.step().narrow_queries;
    CHECK(queries > 100);
    return world.bodies();
  };
  const GjkDistanceOptions gjk{};
  const auto own = run(std::nullopt);
  const auto registry = run(NarrowQuery{
      std::string(info->name),
      [info, gjk](const Polytope& a, const Polytope& b, std::span<const SimplexVertex> warm) {
        return info->narrow_phase(a, b, warm, gjk);
      },
      true});
  REQUIRE(own.size() == registry.size());
  for (std::size_t i = 0; i < own.size(); ++i) {
    CHECK(own[i].pose.translation == registry[i].pose.translation);
    CHECK(own[i].pose.rotation == registry[i].pose.rotation);
  }
  // Exactly the GJK distance variants can be warm-started, so exactly they have the query.
  for (const experiment::AlgorithmInfo& a : experiment::algorithms())
    CHECK((a.narrow_phase != nullptr) == a.can.warm);
}

TEST_CASE("scene physics: the narrow phase in threads gives the same simulation bit for bit",
          "[unit][scene]") {
  // 48 mixed bodies dropped in a 3 m column: over a hundred candidate pairs per frame once they
  // pile up, so that up to four threads each get a block of pairs (16 or more).
  auto run = [](int threads, std::vector<Contact>& contacts, std::vector<StepStats>& stats) {
    WorldSettings s;
    s.threads = threads;
    s.measure_cold = true;
    World world(s);
    add_ground(world);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    const auto box = shape_of(shapes::box(Vec3(0.5, 0.5, 0.5)));
    const auto cone = shape_of(shapes::cone(12));
    const auto ball = make_swept_shape({Vec3::Zero()}, 0.25);
    for (int i = 0; i < 48; ++i)
      world.add(make_dynamic_body(i % 3 == 0   ? box
                                  : i % 3 == 1 ? cone
                                               : ball,
                                  700, random_rotation(rng), Vec3(u(rng), u(rng), 0.5 + 0.6 * i)));
    for (int frame = 0; frame < 240; ++frame)
      stats.push_back(world.step());
    contacts = world.contacts();
    return world.bodies();
  };
  std::vector<Contact> c1, c3;
  std::vector<StepStats> s1, s3;
  const auto b1 = run(1, c1, s1);
  const auto b3 = run(3, c3, s3);
  std::size_t most_pairs = 0;
  for (std::size_t f = 0; f < s1.size(); ++f) {
    most_pairs = std::max(most_pairs, s1[f].candidate_pairs);
    CHECK(s1[f].iterations_mean == s3[f].iterations_mean);
    CHECK(s1[f].iterations_cold_mean == s3[f].iterations_cold_mean);
    CHECK(s1[f].contacts == s3[f].contacts);
    CHECK(s1[f].failed_queries == s3[f].failed_queries);
  }
  CHECK(most_pairs >= 48);  // three blocks of 16 pairs: the threads did run
  for (std::size_t i = 0; i < b1.size(); ++i) {
    CHECK(b1[i].pose.translation == b3[i].pose.translation);
    CHECK(b1[i].orientation.coeffs() == b3[i].orientation.coeffs());
    CHECK(b1[i].angular_velocity == b3[i].angular_velocity);
  }
  REQUIRE(c1.size() == c3.size());
  for (std::size_t k = 0; k < c1.size(); ++k) {
    CHECK(c1[k].point == c3[k].point);
    CHECK(c1[k].normal_impulse == c3[k].normal_impulse);
  }
  WorldSettings bad;
  bad.threads = 0;
  CHECK_THROWS_AS(World(bad), std::invalid_argument);
}

// A box of the funnel scene (seed 18, frame 447) pushed 0.25 m into a funnel slab thinner than
// itself: GJK and EPA find the whole depth, and the contact must carry it (the clipped
// manifold measured against the slab's face used to report 9 % of it, then less, for frames).
TEST_CASE("scene physics: funnel slab 10 with box 36 at frame 447 reports the EPA depth",
          "[unit][scene][regression]") {
  WorldSettings s;
  s.contact_margin = 0.01;
  World world(s);
  const std::vector<Vec3> slab = {{-1.1086554390135441, -0.4592201188381076, 2.0},
                                  {-1.2934313455158013, -0.5357568053111255, 2.0},
                                  {-4.15745789630079, -1.7220754456429035, 6.0},
                                  {-4.342233802803048, -1.7986121321159214, 6.0},
                                  {-0.8485281374238572, -0.8485281374238569, 2.0},
                                  {-0.9899494936611667, -0.9899494936611664, 2.0},
                                  {-3.1819805153394647, -3.181980515339464, 6.0},
                                  {-3.3234018715767744, -3.323401871576773, 6.0}};
  const auto slab_shape = make_convex_shape(slab);
  world.add(make_static_body(slab_shape, Quat::Identity(), -slab_shape->input_origin));
  const Quat q(0.2035520422229035, 0.0875156452104908, -0.6191831207455827, -0.7533391274413125);
  world.add(make_dynamic_body(shape_of(shapes::box(Vec3(0.5, 0.5, 0.5))), 600, q,
                              Vec3(-1.9627316709621034, -1.3659558164320347, 3.745621624977689)));
  world.step();
  // The exact depth of this pair is 0.2545 m (EPA's answer, certified by the oracle).
  CHECK(world.max_penetration() == Approx(0.2545).margin(0.002));
}
