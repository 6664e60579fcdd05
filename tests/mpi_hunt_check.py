#!/usr/bin/python3
"""`gjklab hunt` on 2 MPI ranks (ctest test `mpi_hunt`).

Usage: mpi_hunt_check.py GJKLAB MPIEXEC SOURCE_DIR   (MPIEXEC "" when the build has no MPI: skipped)

Checks:
  1. `mpirun -n 2 gjklab hunt` writes one FOUND.jsonl and one summary: the budget is the one
     asked for, split over the ranks, failures_found counts the lines, and ranks is 2;
  2. every found line fails again: `gjklab query` gives libccd-gjk's boolean different from the
     exact one;
  3. the job is deterministic: a second run writes the same files.
Exit status 0 on success, 77 when skipped (ctest's SKIP_RETURN_CODE), 1 on a failure.
"""
import json
import os
import subprocess
import sys
import tempfile

EXPERIMENT = """
name = "hunt"
seed = 3
cases = 100
[placement]
mode = "mixed"
gap = [1e-6, 1e-1]
depth = [1e-6, 1e-1]
[[family]]
name = "near-contact"
shape = "contact"
contact = "any"
[[family]]
name = "parallel-edges"
shape = "contact"
contact = "parallel-edges"
angle = [1e-9, 1e-2]
[[algorithm]]
name = "libccd-gjk"
"""
QUERIES = 2000


def mpirun(mpiexec, n):
    cmd = [mpiexec, "--oversubscribe", "-n", str(n)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


def fail(message):
    print("mpi_hunt_check: " + message, file=sys.stderr)
    sys.exit(1)


def hunt(gjklab, mpiexec, directory, name):
    found = os.path.join(directory, name + ".jsonl")
    cmd = mpirun(mpiexec, 2) + [gjklab, "hunt", os.path.join(directory, "hunt.toml"),
                                "--algorithm", "libccd-gjk", "--queries", str(QUERIES),
                                "--out", found]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        fail(f"{' '.join(cmd)} exited {result.returncode}: {result.stderr[-2000:]}")
    with open(found) as f:
        lines = f.read()
    with open(os.path.join(directory, name + ".summary.json")) as f:
        summary = json.loads(f.read())
    return found, lines, summary


def main():
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    gjklab, mpiexec = sys.argv[1], sys.argv[2]
    if not mpiexec:
        print("mpi_hunt_check: skipped (this build has no MPI)")
        return 77
    with tempfile.TemporaryDirectory(prefix="gjklab-mpi-hunt-") as directory:
        with open(os.path.join(directory, "hunt.toml"), "w") as f:
            f.write(EXPERIMENT)
        found, lines, summary = hunt(gjklab, mpiexec, directory, "first")
        count = lines.count("\n")
        if summary.get("ranks") != 2:
            fail(f"summary ranks {summary.get('ranks')}, expected 2")
        if summary["queries"] != QUERIES or summary["random_queries"] != QUERIES:
            fail(f"budget {summary['queries']} / {summary['random_queries']}, expected {QUERIES}")
        if summary["failures_found"] != count or count < 2:
            fail(f"failures_found {summary['failures_found']} for {count} lines")
        query = subprocess.run([gjklab, "query", "--cases", found, "--algorithms",
                                "libccd-gjk,exact"], capture_output=True, text=True, timeout=300)
        if query.returncode != 0:
            fail("gjklab query on the found cases: " + query.stderr[-2000:])
        answers = {}
        for line in query.stdout.splitlines():
            answer = json.loads(line)
            answers.setdefault(answer["id"], {})[answer["algorithm"]] = answer["intersect"]
        if len(answers) != count:
            fail(f"{len(answers)} answered cases for {count} lines")
        for case_id, by_algorithm in answers.items():
            if by_algorithm["libccd-gjk"] == by_algorithm["exact"]:
                fail(f"found case {case_id} does not fail again: {by_algorithm}")
        _, lines_again, summary_again = hunt(gjklab, mpiexec, directory, "second")
        if lines_again != lines or summary_again != summary:
            fail("a second 2-rank hunt with the same seed wrote different files")
    print(f"mpi_hunt_check: {count} failures found on 2 ranks, each fails again; deterministic")
    return 0


if __name__ == "__main__":
    sys.exit(main())
