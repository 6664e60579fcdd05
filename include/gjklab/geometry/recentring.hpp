// Exact re-centring of a pair of shapes far from the origin.
//
// GJK compares support values d·x. For shapes of size s placed at distance M ≫ s from the
// origin, each d·x is rounded at the magnitude of M (|error| ≤ 3u‖d‖M, u = 2^-53): vertices
// whose support values differ by less than that are confused, and the answer's error grows to
// the order of u·M instead of u·s. Translating both shapes by the same vector leaves every
// distance, depth and intersection unchanged; done exactly, it leaves the clouds themselves
// unchanged too, only nearer the origin, where support values are compared at the scale of
// the pair.
//
// The rule, per axis i, on the bounding box [lo, hi] of both clouds: t_i = lo when
// 0 < lo and hi ≤ 2·lo; t_i = hi when hi < 0 and lo ≥ 2·hi; else t_i = 0. Every coordinate x
// of that axis then satisfies t_i/2 ≤ x ≤ 2·t_i (mirrored for t_i < 0), so x − t_i is exact
// (Sterbenz's lemma) and the translated cloud is the same set of points, moved by −t. The
// translation is used only where it brings the largest |coordinate| of the pair down by a
// factor of 8 or more (three bits): pairs near the origin are left alone, so their queries
// run on the very same doubles as without it.
#pragma once

#include <optional>

#include "gjklab/geometry/polytope.hpp"

namespace gjklab {

/// The translation t to subtract from both clouds (exactly, see the file comment), or nullopt
/// when the pair is near the origin already (t would gain less than three bits).
std::optional<Vec3> exact_recentring(const Polytope& a, const Polytope& b);

}  // namespace gjklab
