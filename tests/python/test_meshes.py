"""Closed meshes in Python: gjklab.read_closed_mesh and the exact truth for two solids,
gjklab.exact_mesh, against answers known in exact arithmetic."""

import os
from fractions import Fraction

import numpy as np
import pytest

import gjklab
from conftest import SOURCE_DIR, run_cli

BOX = SOURCE_DIR / "tests" / "data" / "meshes_closed" / "box.off"
BAD = SOURCE_DIR / "tests" / "data" / "meshes_bad"


def test_read_closed_mesh_gives_the_file_vertices_and_faces():
    vertices, faces = gjklab.read_closed_mesh(BOX)
    assert vertices.shape == (8, 3) and vertices.dtype == np.float64
    assert faces.shape == (12, 3) and faces.dtype == np.uint32
    assert sorted(map(tuple, vertices.tolist()))[0] == (0.0, 0.0, 0.0)


def test_exact_mesh_separated_by_an_exact_gap():
    vertices, faces = gjklab.read_closed_mesh(BOX)
    gap = 2.0**-40
    moved = vertices + np.array([1.0 + gap, 0.25, 0.5])
    answer = gjklab.exact_mesh(BOX, (moved, faces))
    assert not answer["intersect"]
    assert answer["contact"] == "separated"
    assert answer["distance_squared"] == Fraction(gap) ** 2
    assert answer["distance"] == gap
    assert answer["face_a"] >= 0 and answer["face_b"] >= 0


def test_exact_mesh_touching_and_contained():
    vertices, faces = gjklab.read_closed_mesh(BOX)
    touching = gjklab.exact_mesh((vertices, faces), (vertices + [1.0, 0.5, 0.5], faces))
    assert touching["intersect"] and touching["contact"] == "triangles_meet"
    assert touching["distance_squared"] == 0
    small = vertices * 0.25 + 0.375
    inside = gjklab.exact_mesh((vertices, faces), (small, faces))
    assert inside["intersect"] and inside["contact"] == "b_inside_a"
    assert inside["face_a"] == -1


@pytest.mark.parametrize("name, message", [
    ("open_box.off", "not closed"),
    ("box_inverted.off", "negative signed volume"),
    ("two_tetrahedra.off", "self-intersecting"),
])
def test_bad_meshes_are_refused_naming_the_file(name, message):
    with pytest.raises(ValueError) as refused:
        gjklab.exact_mesh(BAD / name, BOX)
    assert name in str(refused.value)
    assert message in str(refused.value)


def test_bad_arrays_are_refused():
    vertices, faces = gjklab.read_closed_mesh(BOX)
    with pytest.raises(ValueError, match="mesh b"):
        gjklab.exact_mesh(BOX, (vertices, faces[:-1]))  # one face missing: open
    with pytest.raises(ValueError, match="faces must be an m×3 array"):
        gjklab.exact_mesh(BOX, (vertices, faces[:, :2]))
    with pytest.raises(ValueError, match="face 0 has index -1"):
        gjklab.exact_mesh(BOX, (vertices, np.full((12, 3), -1)))


def l_prism():
    """An L: bar [0, 2] x [0, 1], arm [0, 1] x [1, 2], z in [0, 1] (volume 3)."""
    xy = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
    vertices = np.array([(x, y, z) for z in (0.0, 1.0) for x, y in xy], dtype=np.float64)
    faces = []
    for k in range(1, 5):
        faces += [(0, k + 1, k), (6, 6 + k, 7 + k)]
    for i in range(6):
        j = (i + 1) % 6
        faces += [(i, j, 6 + j), (i, 6 + j, 6 + i)]
    return vertices, np.array(faces)


def test_decompose_exact_l_is_proven_pieces_with_integer_corners():
    d = gjklab.decompose(l_prism(), "exact")
    assert d["method"] == "exact" and d["proven"] and d["max_rounding"] == 0
    assert len(d["pieces"]) >= 2
    for piece in d["pieces"]:
        # Cut along the planes of the reflex edge: integer corners inside the L's box.
        assert np.array_equal(piece, np.round(piece))
        assert piece.min() >= 0 and piece.max() <= 2


def test_decompose_hull_and_bad_names():
    vertices, faces = l_prism()
    d = gjklab.decompose((vertices, faces), "hull")
    assert len(d["pieces"]) == 1 and not d["proven"]
    assert np.array_equal(d["pieces"][0], vertices)
    with pytest.raises(ValueError, match="unknown decomposition 'nope'"):
        gjklab.decompose((vertices, faces), "nope")


def test_query_mesh_hull_false_positive_and_exact_pieces():
    l = l_prism()
    box_v, box_f = gjklab.read_closed_mesh(BOX)  # the unit cube
    notch = (box_v * 0.5 + [1.25, 1.25, 0.25], box_f)
    truth = gjklab.query_mesh(l, notch, "exact")
    assert not truth["intersect"] and truth["distance"] == 0.25
    assert truth["method"] == "mesh-truth"
    hull = gjklab.query_mesh(l, notch, "gjk-johnson", "hull")
    assert hull["intersect"] and hull["decomposition"] == "hull"
    pieces = gjklab.query_mesh(l, notch, "gjk-johnson", "exact", max_iterations=64)
    assert not pieces["intersect"]
    assert pieces["distance"] == pytest.approx(0.25, abs=1e-12)
    assert pieces["pieces_a"] >= 2 and pieces["piece_pairs_tested"] >= 1


def test_decompose_options_are_checked_and_reach_hacd():
    with pytest.raises(ValueError, match="takes no option 'concavity'"):
        gjklab.decompose(l_prism(), "exact", concavity=5)
    try:
        default = gjklab.decompose(l_prism(), "approximate")
    except ValueError as e:
        assert "unknown decomposition" in str(e)  # built without HACD
        return
    one = gjklab.decompose(l_prism(), "approximate", min_clusters=1)
    assert len(one["pieces"]) < len(default["pieces"])
    with pytest.raises(ValueError, match="min_clusters"):
        gjklab.decompose(l_prism(), "approximate", min_clusters=0)


def test_real_object_folder_holds_the_packaged_meshes_with_faces():
    folder = gjklab.real_object_folder()
    names = gjklab.real_objects()
    assert "cube" in names
    vertices, faces = gjklab.read_closed_mesh(os.path.join(folder, "cube.off"))
    assert faces.shape == (12, 3)
    d = gjklab.decompose((vertices, faces), "exact")
    assert len(d["pieces"]) == 1 and d["proven"]


def test_query_mesh_takes_the_mesh_peer_as_the_command_line_does():
    l = l_prism()
    notch = gjklab.prism_mesh([(1.25, 1.25), (1.75, 1.25), (1.75, 1.75), (1.25, 1.75)], 0.0, 1.0)
    names = run_cli("names", "--json").stdout
    if '"fcl-bvh"' not in names:
        with pytest.raises(ValueError):
            gjklab.query_mesh(l, notch, "fcl-bvh")
        return
    fcl, exact = gjklab.query_mesh(l, notch, ["fcl-bvh", "exact"])
    assert fcl["algorithm"] == "fcl-bvh" and not fcl["intersect"]
    assert fcl["distance"] == pytest.approx(exact["distance"], abs=1e-12)


def test_a_nonconvex_experiment_runs_and_reads_back_with_its_pieces(tmp_path):
    text = ('name = "nc"\nseed = 2\ncases = 6\n'
            '[[family]]\nshape = "nonconvex"\npair = "box-in-notch"\n'
            '[[algorithm]]\nname = "gjk-johnson"\ndecomposition = ["hull", "exact"]\n')
    report = gjklab.run(text, out=str(tmp_path / "nc.h5"))
    assert report.complete and report.cases == 6
    archive = gjklab.read_archive(tmp_path / "nc.h5")
    assert set(archive.exact["method"]) == {"mesh_truth"}
    assert set(archive.mesh_exact["contact"]) <= {"separated", "triangles_meet", "a_inside_b",
                                                  "b_inside_a"}
    hull = archive.mesh_algorithms["gjk-johnson@decomposition=hull"]
    exact = archive.mesh_algorithms["gjk-johnson@decomposition=exact"]
    assert (hull["pieces_a"] == 1).all()
    assert (exact["pieces_a"] == 2).all()  # the L in two boxes
    assert (exact["piece_pairs_tested"] <= exact["piece_pairs"]).all()
    # The cube is inside the L's hull: the hull intersects wherever the solids are apart.
    apart = ~archive.exact["intersect"].astype(bool)
    said = archive.algorithms["gjk-johnson@decomposition=hull"]["intersect"].astype(bool)
    assert (said[apart]).all()
    assert (archive.algorithms["gjk-johnson@decomposition=exact"]["boolean_correct"]).all()
