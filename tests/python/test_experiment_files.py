"""Every committed file under experiments/ is read by the program it is for, from the folder it
lies in: each study runs one case (`gjklab run`), each scene two frames (`gjklab simulate`), the
hunt file a few queries (`gjklab hunt`) and the bench config one small case (`gjklab bench
--config`). A relative path inside a file (`base`, a family's `path`: `../data/...`,
`../../tests/...`, a scene's `../../examples/l_prism.off`) is relative to that file's folder, so
a file moved, or a file it names moved, without its paths following fails here rather than in a
user's run.

The files run in a temporary copy of the folders they name (experiments/, examples/,
tests/data/, tests/regression/data/ and an empty build/), as the docs' examples do, so that
nothing is written into the source tree; `stream_funnel.toml` reads the queries its scene records
into build/scene_funnel.h5, which the copy gets first, as the study's own header says.
"""

import shutil
import subprocess

import pytest

from conftest import BINARY, SOURCE_DIR

EXPERIMENTS = SOURCE_DIR / "experiments"
FOLDERS = {"studies", "scenes", "bench", "hunt", "data"}
FILES = sorted(EXPERIMENTS.glob("*/*.toml"))


def command(folder, name, out):
    """The arguments that run the file `folder/name` briefly, writing into the folder `out`."""
    path = f"experiments/{folder}/{name}"
    if folder == "studies":
        return ["run", path, "--cases", "1", "--threads", "1", "--out", out / "run.h5"]
    if folder == "scenes":
        return ["simulate", path, "--frames", "2", "--out", out / "scene.h5"]
    if folder == "hunt":
        return ["hunt", path, "--algorithm", "gjk-johnson", "--queries", "4", "--no-random",
                "--out", out / "found.jsonl"]
    if folder == "bench":
        return ["bench", "--config", path, "--suite", "seed", "--cases", "box-cone",
                "--algorithms", "gjk-johnson", "--samples", "1", "--configurations", "1",
                "--batch-us", "10", "--quiet"]
    raise AssertionError(f"experiments/{folder}/{name}: no program reads files of {folder}/")


def run(workspace, args):
    done = subprocess.run([str(BINARY), *map(str, args)], cwd=workspace, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, f"gjklab {' '.join(map(str, args))}:\n{done.stderr[-3000:]}"


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    root = tmp_path_factory.mktemp("repository")
    for part in ("experiments", "examples", "tests/data", "tests/regression/data"):
        shutil.copytree(SOURCE_DIR / part, root / part)
    (root / "build").mkdir()
    # queries_every = 120: frame 120's queries are the stream's cases.
    run(root, ["simulate", "experiments/scenes/scene_funnel.toml", "--frames", "121",
               "--out", "build/scene_funnel.h5"])
    return root


def test_experiments_holds_its_folders_only():
    """studies/, scenes/, bench/, hunt/ and data/, and the format's README beside them."""
    assert {p.name for p in EXPERIMENTS.iterdir()} == FOLDERS | {"README.md"}
    assert {p.parent.name for p in FILES} == FOLDERS - {"data"}


@pytest.mark.parametrize("path", FILES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_file_runs_from_its_folder(workspace, tmp_path, path):
    run(workspace, command(path.parent.name, path.name, tmp_path))
