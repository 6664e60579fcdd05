#!/usr/bin/python3
"""A 2-rank MPI run against the threaded run of the same experiment (ctest test `mpi`).

Usage: mpi_check.py GJKLAB MPIEXEC SOURCE_DIR   (MPIEXEC "" when the build has no MPI: skipped)

Checks, each archive against the threaded one with tools/compare-archives (timing aside):
  1. `mpirun -n 2 gjklab run` writes one complete archive equal to it;
  2. a 2-rank run stopped part-way (--stop-after) resumes on 1 rank, and a 1-process run
     stopped part-way resumes on 2 ranks, into equal archives;
  3. SIGTERM to one rank only stops the whole job, leaving FILE.tmp marked incomplete, which a
     2-rank --resume finishes into an equal archive; after a SIGKILL to one rank (mpirun then
     ends the job) a 1-rank --resume does.
Exit status 0 on success, 77 when skipped (ctest's SKIP_RETURN_CODE), 1 on a failure.
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

import h5py

# Traces and kept geometry are in it, so every part of a result crosses between the ranks.
EXPERIMENT = """
name = "mpi-check"
seed = 17
cases = 600
threads = 2
output = "unused.h5"

[oracle]
enabled = true

[timing]
enabled = false

[trace]
mode = "failing"

[placement]
mode = "mixed"
overlapping_fraction = 0.5
gap = [1e-13, 1.0]
depth = [1e-13, 1.0]

[[family]]
shape = "sphere_points"
vertices = [4, 64]

[[family]]
name = "grazing"
shape = "gaussian"
vertices = [8, 32]

[family.placement]
gap = [1e-14, 1e-9]
depth = [1e-14, 1e-9]

[[algorithm]]
name = "gjk-johnson"

[[algorithm]]
name = "libccd-gjk"

[[algorithm]]
name = "epa"
"""

# The same cases, each query timed many times over: slow enough to be signalled mid-run.
SLOW = EXPERIMENT.replace("[timing]\nenabled = false", "[timing]\nenabled = true\nrepetitions = 300")


def mpirun(mpiexec, n):
    cmd = [mpiexec, "--oversubscribe", "-n", str(n)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


def run(cmd, expect=0):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    if p.returncode != expect:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {p.returncode} (expected {expect})\n"
                 f"{p.stdout}\n{p.stderr}")
    return p


def complete(path):
    with h5py.File(path, "r") as f:
        return int(f.attrs.get("complete", 0)) == 1


def check_equal(compare, reference, path, what):
    if not os.path.exists(path) or not complete(path):
        sys.exit(f"FAIL: {what}: no complete archive {path}")
    p = subprocess.run([compare, "--strict", reference, path], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"FAIL: {what}: the archive differs from the threaded run's\n{p.stdout}{p.stderr}")
    print(f"ok: {what}")


def rank_pids(mpirun_pid):
    """The processes mpirun started, by rank (read from their environment)."""
    ranks = {}
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/stat") as f:
                parent = int(f.read().rsplit(")", 1)[1].split()[1])
            if parent != mpirun_pid:
                continue
            with open(f"/proc/{pid}/environ", "rb") as f:
                env = dict(kv.split(b"=", 1) for kv in f.read().split(b"\0") if b"=" in kv)
            if b"OMPI_COMM_WORLD_RANK" in env:
                ranks[int(env[b"OMPI_COMM_WORLD_RANK"])] = int(pid)
        except (OSError, ValueError, IndexError):
            continue
    return ranks


def rows(path):
    """Cases in an archive being written (0 while it cannot be read)."""
    try:
        with h5py.File(path, "r", locking=False) as f:
            return int(f.attrs.get("checkpoint_cases", 0))
    except (OSError, KeyError):
        return 0


def signal_one_rank(gjklab, mpiexec, compare, reference, folder, signum, resume_ranks):
    """Signals rank 1 of a 2-rank run part-way, then resumes the archive on resume_ranks."""
    slow = os.path.join(folder, "slow.toml")
    with open(slow, "w") as f:
        f.write(SLOW)
    name = signal.Signals(signum).name
    out = os.path.join(folder, f"signalled-{name}.h5")
    cmd = mpirun(mpiexec, 2) + [gjklab, "run", slow, "--out", out, "--threads", "1",
                                "--checkpoint", "32"]
    job = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    ranks = {}
    # Signalled once the archive holds a round and both ranks are up; every wait is bounded.
    while time.monotonic() < deadline and job.poll() is None:
        ranks = rank_pids(job.pid)
        if len(ranks) == 2 and rows(out + ".tmp") >= 32:
            break
        time.sleep(0.05)
    if job.poll() is not None or len(ranks) != 2:
        job.kill()
        sys.exit(f"FAIL: the slow 2-rank run ended before it could be signalled\n"
                 f"{job.communicate()[1]}")
    os.kill(ranks[1], signum)
    try:
        _, err = job.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        job.kill()
        sys.exit(f"FAIL: the job did not stop after {name} to rank 1")
    if not os.path.exists(out + ".tmp") or complete(out + ".tmp") or os.path.exists(out):
        sys.exit(f"FAIL: {name} on rank 1 left no incomplete {out}.tmp\n{err}")
    # A SIGKILL leaves the file as of its last checkpoint (the copy if a write was cut short).
    written = rows(out + ".tmp") or rows(out + ".tmp.checkpoint")
    if not 0 < written < 600:
        sys.exit(f"FAIL: the run signalled with {name} wrote {written} of 600 cases")
    print(f"ok: {name} to rank 1 stopped the job at {written} cases, marked incomplete")
    run(mpirun(mpiexec, resume_ranks) + [gjklab, "run", "--resume", out + ".tmp", "--threads", "1"])
    check_equal(compare, reference, out,
                f"2-rank run stopped by {name} on rank 1, resumed on {resume_ranks} rank"
                + ("s" if resume_ranks > 1 else ""))


def main(gjklab, mpiexec, source):
    if not mpiexec:
        print("skipped: this build has no MPI (install libopenmpi-dev and openmpi-bin)")
        return 77
    compare = os.path.join(source, "tools", "compare-archives")
    with tempfile.TemporaryDirectory() as folder:
        experiment = os.path.join(folder, "check.toml")
        with open(experiment, "w") as f:
            f.write(EXPERIMENT)
        reference = os.path.join(folder, "threaded.h5")
        run([gjklab, "run", experiment, "--out", reference, "--threads", "2"])

        two = os.path.join(folder, "two.h5")
        run(mpirun(mpiexec, 2) + [gjklab, "run", experiment, "--out", two, "--threads", "1",
                                  "--checkpoint", "64"])
        check_equal(compare, reference, two, "2-rank run")

        part = os.path.join(folder, "part.h5")
        run(mpirun(mpiexec, 2) + [gjklab, "run", experiment, "--out", part, "--checkpoint", "64",
                                  "--stop-after", "200"])
        run(mpirun(mpiexec, 1) + [gjklab, "run", "--resume", part + ".tmp"])
        check_equal(compare, reference, part, "2-rank run stopped, resumed on 1 rank")

        single = os.path.join(folder, "single.h5")
        run([gjklab, "run", experiment, "--out", single, "--checkpoint", "100",
             "--stop-after", "300"])
        run(mpirun(mpiexec, 2) + [gjklab, "run", "--resume", single + ".tmp", "--threads", "1",
                                  "--checkpoint", "50"])
        check_equal(compare, reference, single, "1-process run stopped, resumed on 2 ranks")

        signal_one_rank(gjklab, mpiexec, compare, reference, folder, signal.SIGTERM, 2)
        signal_one_rank(gjklab, mpiexec, compare, reference, folder, signal.SIGKILL, 1)
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
