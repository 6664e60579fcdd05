"""gjklab.run writes the archive `gjklab run` writes; read_archive reads it into pandas."""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pandas as pd
import pytest

import gjklab
from conftest import run_cli

EXPERIMENT = """
name = "python-run"
seed = 5
cases = 60
threads = 2

[oracle]
depth = true

[[family]]
shape = "sphere_points"
vertices = [4, 64]

[[family]]
shape = "flat_points"

[[algorithm]]
name = "gjk-johnson"

[[algorithm]]
name = "gjk-bool"

[[algorithm]]
name = "epa"
"""


@pytest.fixture(scope="module")
def archives(tmp_path_factory):
    folder = tmp_path_factory.mktemp("run")
    (folder / "experiment.toml").write_text(EXPERIMENT)
    report = gjklab.run(EXPERIMENT, out=str(folder / "python.h5"), threads=1)
    run_cli("run", folder / "experiment.toml", "--out", folder / "cli.h5")
    return report, folder / "python.h5", folder / "cli.h5"


def test_run_reports_a_complete_archive(archives):
    report, path, _ = archives
    assert report.complete and report.cases == 60 and report.output == str(path)
    assert "gjk-johnson" in report.summary


def test_archive_frames_equal_the_cli_run(archives):
    _, python_path, cli_path = archives
    ours, theirs = gjklab.read_archive(python_path), gjklab.read_archive(cli_path)
    assert ours.complete and theirs.complete
    pd.testing.assert_frame_equal(ours.cases, theirs.cases)
    pd.testing.assert_frame_equal(ours.exact, theirs.exact)
    assert set(ours.algorithms) == {"gjk-johnson", "gjk-bool", "epa"}
    for name, frame in ours.algorithms.items():
        # Everything but the timing column (not timed: NaN in both).
        pd.testing.assert_frame_equal(frame, theirs.algorithms[name])


def test_archive_enums_are_categoricals(archives):
    _, path, _ = archives
    archive = gjklab.read_archive(path)
    assert len(archive.cases) == 60
    assert isinstance(archive.cases["shape_a"].dtype, pd.CategoricalDtype)
    assert set(archive.cases["shape_a"]) == {"sphere_points", "flat_points"}
    assert list(archive.cases["family"].cat.categories) == ["sphere_points", "flat_points"]
    johnson = archive.algorithms["gjk-johnson"]
    assert "converged" in list(johnson["termination"].cat.categories)
    assert set(archive.exact["method"]) <= {"certified", "qp"}
    assert johnson["rel_error"].max() < 1e-12
    # Witness points come as one column per coordinate.
    assert {"witness_a_x", "witness_a_y", "witness_a_z"} <= set(johnson.columns)
    # Exact rationals as decimal strings, consistent with the rounded distance.
    row = archive.exact.iloc[0]
    assert np.isclose(np.sqrt(int(row["distance2_num"]) / int(row["distance2_den"])),
                      row["distance"], rtol=1e-15, atol=0)


def test_run_errors_read_as_the_cli_prints_them(tmp_path):
    bad = EXPERIMENT.replace('shape = "flat_points"', 'shape = "flat_pointz"')
    (tmp_path / "bad.toml").write_text(bad)
    done = run_cli("run", tmp_path / "bad.toml", "--out", tmp_path / "x.h5", check=False)
    assert done.returncode == 2
    with pytest.raises(ValueError) as raised:
        gjklab.run(str(tmp_path / "bad.toml"), out=str(tmp_path / "x.h5"))
    assert "gjklab run: " + str(raised.value) == done.stderr.strip()
    assert "unknown shape 'flat_pointz'" in str(raised.value) or "flat_pointz" in str(raised.value)


def test_an_existing_archive_is_not_overwritten(archives):
    _, path, _ = archives
    with pytest.raises(Exception, match="exists"):
        gjklab.run(EXPERIMENT, out=str(path))


def test_families_list_every_shape_an_experiment_accepts(tmp_path):
    shapes = {f["shape"]: f["description"] for f in gjklab.families()}
    assert {"sphere_points", "box", "contact", "file", "mesh", "real_object"} <= set(shapes)
    for name in shapes:
        if name in ("contact", "file", "stream", "mesh", "real_object", "nonconvex"):
            continue  # they need more keys than a shape name (tested on their own)
        text = (f'name = "s"\nseed = 1\ncases = 2\n[[family]]\nshape = "{name}"\n'
                '[[algorithm]]\nname = "gjk-bool"\n')
        report = gjklab.run(text, out=str(tmp_path / f"{name}.h5"))
        assert report.complete and report.cases == 2
        assert set(gjklab.read_archive(tmp_path / f"{name}.h5").cases["shape_a"]) == {name}


def test_ctrl_c_stops_a_run_leaving_a_resumable_archive(tmp_path):
    # A long run in a child interpreter, interrupted as Ctrl-C would: KeyboardInterrupt in
    # Python, and an incomplete archive under its temporary name that read_archive reads.
    script = f"""
import gjklab, sys
text = 'name = "long"\\nseed = 1\\ncases = 10000000\\n[[family]]\\nshape = "sphere_points"\\n' \\
       '[[algorithm]]\\nname = "gjk-johnson"\\n'
print("started", flush=True)
try:
    gjklab.run(text, out={str(tmp_path / "long.h5")!r}, threads=1)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True,
                             env=os.environ)
    assert child.stdout.readline().strip() == "started"
    time.sleep(1.0)
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=60)
    assert out.strip() == "interrupted"
    assert not (tmp_path / "long.h5").exists()
    archive = gjklab.read_archive(tmp_path / "long.h5.tmp")
    assert not archive.complete and 0 < len(archive.cases) < 10_000_000
