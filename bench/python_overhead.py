#!/usr/bin/python3
"""What a query costs from Python: gjklab.query on NumPy arrays against `gjklab bench`.

`gjklab bench --suite random` times each query in C++ on prebuilt shapes: for n = 8 … 8192
points per shape, eight pairs of clouds of n points on the unit sphere, B moved along a random
axis so that the extents are 0.1 apart (separated) or overlap by 0.1 (overlap). This script
draws the same clouds, bit for bit (bench's seeded generator, std::mt19937_64 with its own
conversions and glibc's log and cos, is reproduced below; the mean iteration count of the eight
pairs, printed beside bench's, checks it), and times gjklab.query on them:

  arrays  from NumPy arrays: each call checks the arrays and builds both shapes from them;
  shapes  from gjklab.Shape objects built once (what bench times: shapes built before the clock).

Times are the calling thread's CPU time, as bench's are: timeit with time.thread_time, each
sample a batch of calls over the eight pairs, the median over the samples. The fixed part of a
call is measured on one-point clouds (the query itself then costs a few nanoseconds).

The target: an array query costs at most 2 × bench + the fixed part, the fixed part below 2 µs.
The column `conversion` is what building a shape from an array costs per point beyond the
fixed part: (arrays − shapes − (fixed arrays − fixed shapes)) / (2n − 2). Building reads 24
bytes per point and writes 48 (the vertices and the scan's blocks); GB/s is of the 24 bytes
read. It is printed from 512 points on: below, it is within the noise of the fixed part.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_overhead.py \\
        --binary build/release/gjklab
"""

import argparse
import json
import math
import statistics
import subprocess
import tempfile
import time
import timeit

import numpy as np

import gjklab

SIZES = [8, 32, 128, 512, 2048, 8192]
GAP = 0.1  # bench's kRandomGap
CONFIGURATIONS = 8  # bench's default --configurations
SEED = 1  # bench's default --seed
# Below this, the conversion's share of a call is within the noise of the fixed part.
MIN_CONVERSION_POINTS = 512


class Mt19937_64:
    """std::mt19937_64, whose output sequence the C++ standard fixes, with numpy doing a whole
    state (312 words) at a time."""

    N, M = 312, 156
    MATRIX = np.uint64(0xB5026F5AA96619E9)
    UPPER, LOWER = np.uint64(0xFFFFFFFF80000000), np.uint64(0x7FFFFFFF)

    def __init__(self, seed):
        mask = (1 << 64) - 1
        mt = [seed & mask]
        for i in range(1, self.N):
            mt.append((6364136223846793005 * (mt[-1] ^ (mt[-1] >> 62)) + i) & mask)
        self.mt = np.array(mt, dtype=np.uint64)
        self.out, self.next = None, self.N

    def _mix(self, i, j, k):
        """New words i from old i, j (next) and k (i + M), elementwise."""
        x = (self.mt[i] & self.UPPER) | (self.mt[j] & self.LOWER)
        odd = (x & np.uint64(1)).astype(bool)
        return self.mt[k] ^ (x >> np.uint64(1)) ^ np.where(odd, self.MATRIX, np.uint64(0))

    def _twist(self):
        n, m = self.N, self.M
        i = np.arange(n - m)  # words 0 … 155 read only old words
        self.mt[i] = self._mix(i, i + 1, i + m)
        i = np.arange(n - m, n - 1)  # words 156 … 310 read new words i + m − n
        self.mt[i] = self._mix(i, i + 1, i + m - n)
        i = np.array([n - 1])  # word 311 reads new words 0 and 155
        self.mt[i] = self._mix(i, np.array([0]), np.array([m - 1]))
        y = self.mt.copy()
        y ^= (y >> np.uint64(29)) & np.uint64(0x5555555555555555)
        y ^= (y << np.uint64(17)) & np.uint64(0x71D67FFFEDA60000)
        y ^= (y << np.uint64(37)) & np.uint64(0xFFF7EEE000000000)
        y ^= y >> np.uint64(43)
        self.out, self.next = [int(v) for v in y], 0

    def __call__(self):
        if self.next == self.N:
            self._twist()
        self.next += 1
        return self.out[self.next - 1]


class BenchRng:
    """bench.cpp's Rng: uniform, normal (Box–Muller) and unit vectors, bit for bit."""

    def __init__(self, seed):
        self.engine = Mt19937_64(seed)

    def uniform(self):
        return (self.engine() >> 11) * 2.0**-53

    def normal(self):
        u = 1.0 - self.uniform()
        return math.sqrt(-2 * math.log(u)) * math.cos(2 * math.pi * self.uniform())

    def unit_vector(self):
        while True:
            # Vec3(normal(), normal(), normal()): GCC evaluates the arguments last to first.
            z = self.normal()
            y = self.normal()
            x = self.normal()
            n = math.sqrt((x * x + y * y) + z * z)  # Eigen's norm(), in its order
            if n > 1e-9:
                return [x / n, y / n, z / n]


def dot(points, u):
    """Eigen's p.dot(u) row by row: (x·ux + y·uy) + z·uz, each operation rounded."""
    return (points[:, 0] * u[0] + points[:, 1] * u[1]) + points[:, 2] * u[2]


def bench_pairs(n, overlap):
    """The pairs of case "n=… separated|overlap" of `gjklab bench --suite random`."""
    case_index = 2 * SIZES.index(n) + (1 if overlap else 0)
    rng = BenchRng(SEED * 2000003 + case_index)
    gap = -GAP if overlap else GAP
    pairs = []
    for _ in range(CONFIGURATIONS):
        a = np.array([rng.unit_vector() for _ in range(n)])
        b = np.array([rng.unit_vector() for _ in range(n)])
        u = rng.unit_vector()
        shift = (dot(a, u).max() - dot(b, u).min() + gap) * np.array(u)
        pairs.append((a, b + shift))
    return pairs


def ns_per_call(call, pairs, samples, batch_seconds=5e-3):
    """Median over samples of thread CPU ns per call, each sample a batch over all pairs."""
    def batch():
        for a, b in pairs:
            call(a, b)
    timer = timeit.Timer(batch, timer=time.thread_time)
    number, _ = timer.autorange()  # at least 0.2 s: also the warm-up
    number = max(1, int(number * batch_seconds / 0.2))
    times = timer.repeat(repeat=samples, number=number)
    return statistics.median(times) * 1e9 / (number * len(pairs))


def bench_medians(binary, algorithm, samples):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([binary, "bench", "--suite", "random", "--algorithms", algorithm,
                        "--reference", algorithm, "--samples", str(samples), "--json",
                        out.name, "--quiet"], check=True, capture_output=True)
        with open(out.name) as f:
            records = json.load(f)["records"]
    # Case names are "n=512 separated", "n=512 overlap".
    return {tuple(r["case"].split()): r for r in records if r["algorithm"] == algorithm}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary", default="build/release/gjklab")
    parser.add_argument("--algorithm", default="gjk-johnson")
    parser.add_argument("--samples", type=int, default=31)
    parser.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    args = parser.parse_args()

    def call(a, b):
        return gjklab.query(a, b, args.algorithm)

    point = np.zeros((1, 3))
    fixed = ns_per_call(call, [(point, point)], args.samples)
    shape = gjklab.Shape(point)
    fixed_shapes = ns_per_call(call, [(shape, shape)], args.samples)
    bench = bench_medians(args.binary, args.algorithm, args.samples)

    header = ["n", "placement", "iterations (bench)", "bench ns", "arrays ns", "ratio",
              "limit ns", "met", "shapes ns", "conversion ns/point", "GB/s"]
    rows = []
    for n in SIZES:
        for placement in ("separated", "overlap"):
            record = bench.get((f"n={n}", placement))
            if record is None:
                continue
            pairs = bench_pairs(n, placement == "overlap")
            arrays = ns_per_call(call, pairs, args.samples)
            shapes = ns_per_call(call, [(gjklab.Shape(a), gjklab.Shape(b)) for a, b in pairs],
                                 args.samples)
            native = record["ns_median"]
            iterations = np.mean([call(a, b).iterations for a, b in pairs])
            limit = 2 * native + fixed
            # Beyond what converting two one-point arrays costs (in the fixed part).
            per_point = (arrays - shapes - (fixed - fixed_shapes)) / (2 * n - 2)
            rows.append([n, placement, f"{iterations:.3f} ({record['iterations_mean']:.3f})",
                         f"{native:.0f}", f"{arrays:.0f}", f"{arrays / native:.2f}",
                         f"{limit:.0f}", "yes" if arrays <= limit else "no", f"{shapes:.0f}",
                         f"{per_point:.2f}" if n >= MIN_CONVERSION_POINTS else "-",
                         f"{24 / per_point:.0f}" if n >= MIN_CONVERSION_POINTS else "-"])
    print(f"fixed part of a call (one-point clouds): arrays {fixed:.0f} ns, "
          f"shapes {fixed_shapes:.0f} ns; limit = 2 × bench + {fixed:.0f} ns")
    if args.markdown:
        print("| " + " | ".join(header) + " |")
        print("|" + "|".join("---:" if k != 1 else ":---" for k in range(len(header))) + "|")
        for row in rows:
            print("| " + " | ".join(str(v) for v in row) + " |")
    else:
        widths = [max(len(str(r[k])) for r in rows + [header]) for k in range(len(header))]
        for row in [header] + rows:
            print("  ".join(str(v).rjust(w) for v, w in zip(row, widths)))


if __name__ == "__main__":
    main()
