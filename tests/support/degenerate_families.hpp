// The degenerate and near-contact families of experiments/studies/degeneracy.toml but its 10⁴–10⁵
// point clouds, as experiment-file text: exact contact of every type, ε = 1e-15 … 1e-3 of the
// size, parallel edges, flat, collinear and duplicate clouds, single points, slivers, scale
// disparity, offsets up to 1e9 and tiny shapes. Shared by the property tests that sample them.
#pragma once

namespace gjklab::testing {

/// [placement] and the [[family]] tables; a test adds the name, seed, cases and algorithms.
inline constexpr const char* kDegenerateFamilies = R"([placement]
mode = "mixed"
gap = [1e-15, 1e-3]
depth = [1e-15, 1e-3]
[[family]]
name = "touching"
shape = "contact"
contact = "any"
[family.placement]
mode = "touching"
[[family]]
name = "contact-eps"
shape = "contact"
contact = "any"
weight = 2
[[family]]
name = "parallel-edges"
shape = "contact"
contact = "parallel-edges"
angle = [1e-9, 1e-2]
[[family]]
name = "flat-vs-box"
shape_a = "flat_points"
shape_b = "box"
vertices_a = [3, 64]
rotate = "axes"
[[family]]
name = "flat-vs-flat"
shape = "flat_points"
vertices = [3, 64]
rotate = "axes"
[[family]]
name = "collinear-vs-box"
shape_a = "collinear_points"
shape_b = "box"
vertices_a = [2, 16]
rotate = "axes"
[[family]]
name = "collinear-vs-collinear"
shape = "collinear_points"
vertices = [2, 16]
rotate = "random"
[[family]]
name = "duplicates"
shape = "duplicate_points"
vertices = [4, 32]
[[family]]
name = "point-vs-sphere"
shape_a = "single_point"
shape_b = "sphere_points"
vertices_b = [4, 128]
[[family]]
name = "slivers"
shape = "sliver"
aspect = [10, 1e6]
[[family]]
name = "scale-disparity"
shape = "sphere_points"
vertices = [8, 64]
scale = 1e4
scale_b = 1e-8
[[family]]
name = "large-offsets"
shape = "sphere_points"
vertices = [8, 64]
offset = [1e3, 1e9]
[[family]]
name = "tiny"
shape = "cube_points"
vertices = [8, 64]
scale = 1e-9
)";

}  // namespace gjklab::testing
