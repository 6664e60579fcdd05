"""What the Python module's tests share: the command-line program to compare with, and
seeded pairs of point clouds."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

SOURCE_DIR = Path(os.environ.get("GJKLAB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BINARY = Path(os.environ.get("GJKLAB_BINARY", SOURCE_DIR / "build" / "release" / "gjklab"))


def run_cli(*args, stdin=None, check=True):
    """Runs the gjklab program; returns the CompletedProcess (text)."""
    done = subprocess.run([str(BINARY), *map(str, args)], input=stdin, capture_output=True,
                          text=True, timeout=600)
    if check and done.returncode != 0:
        raise AssertionError(f"gjklab {' '.join(map(str, args))} failed: {done.stderr}")
    return done


def is_collinear_pair(case_id):
    return int(case_id.split()[-1]) % 5 == 4


def cli_query(cases, *options):
    """`gjklab query --cases -` on [(id, a, b)]; returns its JSON lines, parsed."""
    text = "".join(json.dumps({"id": i, "a": a.tolist(), "b": b.tolist()}) + "\n"
                   for i, a, b in cases)
    done = run_cli("query", "--cases", "-", *options, stdin=text)
    return [json.loads(line) for line in done.stdout.splitlines()]


def random_pairs(count, seed):
    """Seeded pairs (id, a, b) covering what GJK meets: clouds of 1 to 200 points, flat and
    collinear clouds, scales from 1e-3 to 1e3, and B placed from far apart through grazing to
    overlap along a random direction, or centred on A (deep overlap). Case i's clouds are
    collinear when i % 5 == 4."""
    rng = np.random.default_rng(seed)
    pairs = []
    for i in range(count):
        clouds = []
        for _ in range(2):
            n = int(rng.choice([1, 2, 3, 4, 8, 32, 200]))
            cloud = rng.normal(size=(n, 3))
            kind = i % 5
            if kind == 3:
                cloud[:, 2] = 0.0  # flat: exactly coplanar
            elif kind == 4:
                cloud[:, 1:] = 0.0  # collinear
            clouds.append(cloud)
        a, b = clouds
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        gap = float(rng.choice([-2.0, -1.0, -1e-3, -1e-9, 0.0, 1e-9, 1e-3, 1.0, 10.0]))
        if i % 4 == 0:
            b = b - b.mean(axis=0) + a.mean(axis=0) + 0.1 * direction  # deep overlap
        else:
            extent_a = float((a @ direction).max())
            extent_b = float((b @ direction).min())
            b = b + (extent_a - extent_b + gap) * direction
        scale = 10.0 ** float(rng.integers(-3, 4))
        pairs.append((f"case {i}", a * scale, b * scale))
    return pairs


@pytest.fixture(scope="module")
def pairs():
    return random_pairs(300, seed=20)
