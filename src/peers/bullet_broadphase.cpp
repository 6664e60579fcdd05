// Bullet's btDbvtBroadphase as a broad-phase peer (see peers/bullet_broadphase.hpp). Compiled in
// every build; without Bullet it only reports that it is absent.
#include "gjklab/peers/bullet_broadphase.hpp"

#include <stdexcept>

#if defined(GJKLAB_HAVE_BULLET)
#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <LinearMath/btScalar.h>

#include <cstddef>
#include <type_traits>

static_assert(std::is_same_v<btScalar, double>, "the Bullet peer needs Bullet's double precision");
#endif

namespace gjklab::peers {

#if defined(GJKLAB_HAVE_BULLET)

namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

/// Finite and not inverted: what a tree volume can hold.
bool regular(const BroadphaseBox& b) {
  return b.lower.allFinite() && b.upper.allFinite() && (b.lower.array() <= b.upper.array()).all();
}

bool overlaps(const BroadphaseBox& a, const BroadphaseBox& b) {
  return (a.lower.array() <= b.upper.array()).all() && (b.lower.array() <= a.upper.array()).all();
}

btVector3 to_bt(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

/// The body index a proxy was created for (its user pointer).
std::uint32_t body_of(const btBroadphaseProxy* p) {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(p->m_clientObject));
}

/// The scene's output order (i, then j) by two counting sorts, O(pairs + n), as the scene's
/// broad phases produce it: the times then compare like for like.
void sort_pairs(std::vector<Pair>& pairs, std::uint32_t n, std::vector<Pair>& tmp,
                std::vector<std::uint32_t>& count) {
  tmp.resize(pairs.size());
  auto pass = [&](const std::vector<Pair>& from, std::vector<Pair>& to, auto key) {
    count.assign(std::size_t{n} + 1, 0);
    for (const Pair& p : from)
      ++count[key(p) + 1];
    for (std::uint32_t k = 1; k <= n; ++k)
      count[k] += count[k - 1];
    for (const Pair& p : from)
      to[count[key(p)]++] = p;
  };
  pass(pairs, tmp, [](const Pair& p) { return p.second; });
  pass(tmp, pairs, [](const Pair& p) { return p.first; });
}

}  // namespace

struct BulletDbvtBroadphase::Impl {
  btDbvtBroadphase tree;  // its own btHashedOverlappingPairCache, as in a default Bullet world
  std::vector<btBroadphaseProxy*> proxies;  // per box; null for a box kept out of the tree
  std::vector<BroadphaseBox> last;          // the boxes of the last call
  std::vector<std::uint32_t> outside;       // boxes kept out of the tree (not regular)
  std::vector<Pair> tmp;
  std::vector<std::uint32_t> count;

  ~Impl() { clear(); }
  void clear() {
    for (btBroadphaseProxy* p : proxies)
      if (p) tree.destroyProxy(p, nullptr);
    proxies.clear();
    last.clear();
  }
  void update(std::span<const BroadphaseBox> boxes);
};

void BulletDbvtBroadphase::Impl::update(std::span<const BroadphaseBox> boxes) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  if (proxies.size() != n) {
    clear();
    proxies.assign(n, nullptr);
    last.assign(n, BroadphaseBox{Vec3::Constant(NAN), Vec3::Constant(NAN)});
  }
  outside.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    const BroadphaseBox& b = boxes[i];
    if (!regular(b)) {
      if (proxies[i]) tree.destroyProxy(proxies[i], nullptr);
      proxies[i] = nullptr;
      outside.push_back(i);
    } else if (!proxies[i]) {
      proxies[i] = tree.createProxy(to_bt(b.lower), to_bt(b.upper), CONVEX_HULL_SHAPE_PROXYTYPE,
                                    reinterpret_cast<void*>(std::uintptr_t{i}),
                                    int(btBroadphaseProxy::DefaultFilter),
                                    int(btBroadphaseProxy::AllFilter), nullptr);
    } else if (b.lower != last[i].lower || b.upper != last[i].upper) {
      tree.setAabb(proxies[i], to_bt(b.lower), to_bt(b.upper), nullptr);
    }
    last[i] = b;
  }
  tree.calculateOverlappingPairs(nullptr);
}

BulletDbvtBroadphase::BulletDbvtBroadphase() : impl_(std::make_unique<Impl>()) {}
BulletDbvtBroadphase::~BulletDbvtBroadphase() = default;

void BulletDbvtBroadphase::find_pairs(std::span<const BroadphaseBox> boxes,
                                      std::vector<Pair>& out) {
  Impl& m = *impl_;
  m.update(boxes);
  out.clear();
  // The cache, filtered by the exact test on the boxes as given (closed: touching counts).
  const btBroadphasePairArray& cached = m.tree.getOverlappingPairCache()->getOverlappingPairArray();
  for (int k = 0; k < cached.size(); ++k) {
    const std::uint32_t i = body_of(cached[k].m_pProxy0), j = body_of(cached[k].m_pProxy1);
    if (overlaps(boxes[i], boxes[j])) out.emplace_back(std::min(i, j), std::max(i, j));
  }
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t big : m.outside)
    for (std::uint32_t j = 0; j < n; ++j)
      // Two boxes outside meet twice: reported when `big` is the smaller index.
      if (j != big && !(m.proxies[j] == nullptr && j < big) && overlaps(boxes[big], boxes[j]))
        out.emplace_back(std::min(big, j), std::max(big, j));
  sort_pairs(out, n, m.tmp, m.count);
}

bool bullet_broadphase_available() {
  return true;
}

#else  // no Bullet

struct BulletDbvtBroadphase::Impl {};

BulletDbvtBroadphase::BulletDbvtBroadphase() {
  throw std::runtime_error("Bullet's broad phase: gjklab was built without Bullet");
}
BulletDbvtBroadphase::~BulletDbvtBroadphase() = default;

void BulletDbvtBroadphase::find_pairs(std::span<const BroadphaseBox>,
                                      std::vector<std::pair<std::uint32_t, std::uint32_t> >&) {}

bool bullet_broadphase_available() {
  return false;
}

#endif

}  // namespace gjklab::peers
