#!/usr/bin/python3
"""What a query costs from Python: gjklab.query on NumPy arrays against `gjklab bench`.

`gjklab bench --suite random` times each query in C++ on prebuilt shapes (n points on the unit
sphere, B moved along a random axis so that the extents are 0.1 apart or overlap by 0.1). This
script times gjklab.query on inputs drawn the same way, twice: from NumPy arrays, each call
checking and copying both arrays and building both shapes, and from gjklab.Shape objects built
once (what bench times: shapes built before the clock starts), and prints both per query with
their ratios to bench. Times are the calling thread's CPU time, as bench's are. The fixed part of a
call is measured on one-point clouds (the query itself is then a few nanoseconds).

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_overhead.py \\
        --binary build/release/gjklab
"""

import argparse
import json
import statistics
import subprocess
import tempfile
import time

import numpy as np

import gjklab

SIZES = [8, 32, 128, 512, 2048, 8192]
GAP = 0.1
CONFIGURATIONS = 8


def sphere_points(rng, n):
    p = rng.normal(size=(n, 3))
    return p / np.linalg.norm(p, axis=1, keepdims=True)


def random_pair(rng, n, overlap):
    a, b = sphere_points(rng, n), sphere_points(rng, n)
    u = sphere_points(rng, 1)[0]
    shift = (a @ u).max() - (b @ u).min() + (-GAP if overlap else GAP)
    return a, b + shift * u


def ns_per_call(call, pairs, samples, batch_seconds=5e-3):
    """Median over samples of thread CPU ns per call, each sample a batch over all pairs."""
    def batch(repetitions):
        start = time.thread_time_ns()
        for _ in range(repetitions):
            for a, b in pairs:
                call(a, b)
        return time.thread_time_ns() - start
    batch(1)  # warm-up
    once = max(batch(1), 1)
    repetitions = max(1, int(batch_seconds * 1e9 / once))
    return statistics.median(batch(repetitions) / (repetitions * len(pairs))
                             for _ in range(samples))


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
    parser.add_argument("--samples", type=int, default=15)
    args = parser.parse_args()

    point = np.zeros((1, 3))
    call = lambda a, b: gjklab.query(a, b, args.algorithm)  # noqa: E731
    fixed = ns_per_call(call, [(point, point)], args.samples)
    shape = gjklab.Shape(point)
    fixed_shapes = ns_per_call(call, [(shape, shape)], args.samples)
    print(f"fixed cost of a call on one-point clouds: arrays {fixed:.0f} ns, "
          f"shapes {fixed_shapes:.0f} ns")
    bench = bench_medians(args.binary, args.algorithm, args.samples)
    rng = np.random.default_rng(1)
    print(f"{'n':>6} {'placement':>10} {'iterations':>11} {'bench ns':>9} "
          f"{'arrays ns':>10} {'ratio':>6} {'shapes ns':>10} {'ratio':>6} {'shapes - bench':>15}")
    for n in SIZES:
        for placement in ("overlap", "separated"):
            pairs = [random_pair(rng, n, placement == "overlap") for _ in range(CONFIGURATIONS)]
            arrays = ns_per_call(lambda a, b: gjklab.query(a, b, args.algorithm), pairs,
                                 args.samples)
            shapes = [(gjklab.Shape(a), gjklab.Shape(b)) for a, b in pairs]
            built = ns_per_call(lambda a, b: gjklab.query(a, b, args.algorithm), shapes,
                                args.samples)
            record = bench.get((f"n={n}", placement))
            if record is None:
                continue
            native = record["ns_median"]
            # Mean iterations of both samples: the inputs are drawn alike, not bit for bit.
            iterations = np.mean([gjklab.query(a, b, args.algorithm).iterations
                                  for a, b in pairs])
            print(f"{n:>6} {placement:>10} {iterations:>5.1f}/{record['iterations_mean']:<5.1f} "
                  f"{native:>9.0f} {arrays:>10.0f} {arrays / native:>6.2f} {built:>10.0f} "
                  f"{built / native:>6.2f} {built - native:>15.0f}")


if __name__ == "__main__":
    main()
