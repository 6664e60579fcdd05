"""The scripts in examples/python run and print what they promise."""

import subprocess
import sys

import gjklab
from conftest import SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples" / "python"
MESHES = SOURCE_DIR / "tests" / "data" / "meshes"


def run_example(name, *args):
    done = subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_own_meshes_study():
    out = run_example("own_meshes.py", MESHES / "tetrahedron.off", MESHES / "cube.stl",
                      MESHES / "wedge.ply", "--poses", "2")
    lines = out.splitlines()
    assert lines[0].split()[:3] == ["queries", "median_rel_error", "max_rel_error"]
    variants = {line.split()[0] for line in lines[2:]}
    assert {"gjk-johnson", "gjk-sv", "gjk-voronoi"} <= variants
    # 6 pairs x 2 poses x 7 gaps per variant; every error is small.
    for line in lines[2:]:
        fields = line.split()
        assert int(fields[1]) == 84
        assert float(fields[3]) < 1e-6


def test_archive_figure(tmp_path):
    experiment = ('name = "figure"\nseed = 2\ncases = 40\n[[family]]\nshape = "box"\n'
                  '[[family]]\nshape = "sphere_points"\n'
                  '[[algorithm]]\nname = "gjk-johnson"\n[[algorithm]]\nname = "gjk-sv"\n'
                  '[[algorithm]]\nname = "gjk-bool"\n')
    gjklab.run(experiment, out=str(tmp_path / "figure.h5"))
    out = run_example("archive_figure.py", tmp_path / "figure.h5", tmp_path / "figure.png")
    assert "gjk-johnson" in out and "gjk-bool" not in out  # boolean-only: no distance error
    assert "sphere_points" in out and "box" in out
    image = (tmp_path / "figure.png").read_bytes()
    assert image.startswith(b"\x89PNG") and len(image) > 10_000
