#!/usr/bin/python3
"""A study on your own meshes: how accurate is each gjklab GJK variant on them?

Every pair of the given meshes (each with itself too) is turned by random rotations and placed
at gaps from far apart to grazing and penetrating; each variant's distance is compared with the
exact answer, relative to the pair's size. Prints one row per variant.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/own_meshes.py \\
        my_part.stl my_other_part.obj --poses 20
"""

import argparse
import itertools

import numpy as np
import pandas as pd

import gjklab

# Gaps relative to the pair's size: negative values overlap.
GAPS = [-0.1, -1e-3, -1e-9, 1e-9, 1e-3, 0.1, 1.0]


def random_rotation(rng):
    """Uniform on SO(3): the orthogonal factor of a Gaussian matrix, signs fixed."""
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def place(a, b, gap, rng):
    """B moved along a random direction so that it starts gap * size after A ends."""
    u = rng.normal(size=3)
    u /= np.linalg.norm(u)
    size = max(np.ptp(a, axis=0).max(), np.ptp(b, axis=0).max())
    return b + ((a @ u).max() - (b @ u).min() + gap * size) * u, size


def study(meshes, poses, seed):
    rng = np.random.default_rng(seed)
    variants = [name for name, info in gjklab.algorithms().items()
                if info["kind"] == "distance" and not info["peer"]]
    rows = []
    for (name_a, a), (name_b, b) in itertools.combinations_with_replacement(meshes.items(), 2):
        for _ in range(poses):
            a_turned = (a - a.mean(axis=0)) @ random_rotation(rng).T
            b_turned = (b - b.mean(axis=0)) @ random_rotation(rng).T
            for gap in GAPS:
                b_placed, size = place(a_turned, b_turned, gap, rng)
                truth = gjklab.exact(a_turned, b_placed).distance
                for variant in variants:
                    result = gjklab.query(a_turned, b_placed, variant)
                    rows.append({"pair": f"{name_a}/{name_b}", "gap": gap, "variant": variant,
                                 "rel_error": abs(result.distance - truth) / size,
                                 "iterations": result.iterations,
                                 "converged": result.termination == "converged"})
    return pd.DataFrame(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("meshes", nargs="+", help=".off, .obj, .ply, .stl or .xyz files")
    parser.add_argument("--poses", type=int, default=10, help="random rotations per pair")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    meshes = {path.rsplit("/", 1)[-1]: gjklab.read_points(path) for path in args.meshes}
    frame = study(meshes, args.poses, args.seed)
    table = frame.groupby("variant").agg(
        queries=("rel_error", "size"),
        median_rel_error=("rel_error", "median"),
        max_rel_error=("rel_error", "max"),
        mean_iterations=("iterations", "mean"),
        converged=("converged", "mean"))
    with pd.option_context("display.width", 120, "display.float_format", "{:.3g}".format):
        print(table.sort_values("max_rel_error").to_string())


if __name__ == "__main__":
    main()
