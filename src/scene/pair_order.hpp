// The broad phases' common output order: pairs (i, j), i < j, sorted on i then j.
// Internal to src/scene/.
#pragma once

#include <cstdint>
#include <vector>

#include "gjklab/scene/broadphase.hpp"

namespace gjklab::scene::detail {

/// The pair with the smaller index first, without a branch: in a sweep the two indices come in
/// no particular order, and a branch here mispredicts about every other pair.
inline BodyPair ordered(std::uint32_t a, std::uint32_t b) {
  const std::uint32_t swap = (a ^ b) & (0u - static_cast<std::uint32_t>(b < a));
  return {a ^ swap, b ^ swap};
}

/// Sorts distinct pairs of indices below n in O(pairs + n): a counting sort on the second
/// index, then a stable one on the first. `tmp` and `count` are scratch kept by the caller.
inline void sort_pairs(std::vector<BodyPair>& pairs, std::uint32_t n, std::vector<BodyPair>& tmp,
                       std::vector<std::uint32_t>& count) {
  tmp.resize(pairs.size());
  auto pass = [&](const std::vector<BodyPair>& from, std::vector<BodyPair>& to, auto key) {
    count.assign(std::size_t{n} + 1, 0);
    for (const BodyPair& p : from)
      ++count[key(p) + 1];
    for (std::uint32_t k = 1; k <= n; ++k)
      count[k] += count[k - 1];
    for (const BodyPair& p : from)
      to[count[key(p)]++] = p;
  };
  pass(pairs, tmp, [](const BodyPair& p) { return p.second; });
  pass(tmp, pairs, [](const BodyPair& p) { return p.first; });
}

}  // namespace gjklab::scene::detail
