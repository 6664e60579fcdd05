"""gjklab.query and gjklab.exact give the command line's answers, bit for bit."""

import json
import math
from fractions import Fraction

import numpy as np
import pytest

import gjklab
from conftest import cli_query, is_collinear_pair, run_cli


def plain(value):
    """JSON-comparable: arrays as lists, NaN as None (JSON writes NaN as null)."""
    if isinstance(value, np.ndarray):
        return [plain(float(x)) for x in value]
    if isinstance(value, float) and math.isnan(value):
        return None
    return value


def answer(result):
    return {k: plain(v) for k, v in result.to_dict().items()}


def test_every_algorithm_answers_as_the_cli_on_300_pairs(pairs):
    # FCL's libccd-based distance query never returns on two parallel separated segments
    # (case 24 here), so it gets the pairs that are not both collinear; the rest of the
    # registry gets every pair. (`gjklab query` runs sat only when named.)
    others = [name for name in gjklab.algorithms() if name not in ("sat", "fcl-libccd")]
    lines = cli_query(pairs, "--algorithms", ",".join(others))
    if "fcl-libccd" in gjklab.algorithms():
        lines += cli_query([c for c in pairs if not is_collinear_pair(c[0])], "--algorithms",
                           "fcl-libccd")
    by_id = {c[0]: c for c in pairs}
    algorithms_seen = set()
    intersecting = separated = 0
    for line in lines:
        assert "error" not in line, line
        _, a, b = by_id[line["id"]]
        algorithms_seen.add(line["algorithm"])
        result = gjklab.query(a, b, line["algorithm"])
        # Every field, the exact answer's rationals included: both come from answer_fields.
        expected = {k: plain(v) for k, v in line.items() if k != "id"}
        assert answer(result) == expected, line["id"]
        # The attributes carry the same names and values as the JSON.
        for key in ("intersect", "distance", "depth", "iterations", "support_calls",
                    "termination"):
            if key in expected:
                assert plain(getattr(result, key)) == expected[key]
        if line["algorithm"] == "exact":
            intersecting += line["intersect"]
            separated += not line["intersect"]
    # The sample is representative: every registered algorithm but sat (which the CLI runs
    # only when named), both answers.
    assert algorithms_seen == set(gjklab.algorithms()) - {"sat"}
    assert intersecting >= 50 and separated >= 50


def test_exact_fractions_equal_the_cli_rationals(pairs):
    lines = cli_query(pairs, "--algorithms", "exact")
    by_id = {c[0]: c for c in pairs}
    certified = 0
    for line in lines:
        _, a, b = by_id[line["id"]]
        answer = gjklab.exact(a, b)
        assert answer.distance_squared == Fraction(int(line["distance2_num"]),
                                                   int(line["distance2_den"]))
        assert answer.intersect == line["intersect"]
        assert answer.distance == line["distance"]
        assert answer.method == line["method"]
        assert (answer.hull_vertices_a, answer.hull_vertices_b) == (
            line["hull_vertices_a"], line["hull_vertices_b"])
        assert answer.depth_squared is None
        certified += answer.method == "certified"
    assert certified > 0


def test_exact_depth_fractions_equal_the_cli_rationals(pairs):
    overlapping = [c for c in pairs if gjklab.exact(c[1], c[2]).intersect][:40]
    assert len(overlapping) == 40  # the sample holds enough intersecting pairs
    lines = cli_query(overlapping, "--algorithms", "exact", "--depth")
    by_id = {c[0]: c for c in overlapping}
    for line in lines:
        _, a, b = by_id[line["id"]]
        answer = gjklab.exact(a, b, depth=True)
        assert answer.depth_squared == Fraction(int(line["depth2_num"]), int(line["depth2_den"]))
        assert answer.depth_method == line["depth_method"]
        assert answer.depth == line["depth"]


def test_exact_answers_are_exact_on_pairs_known_by_hand():
    # Two points: the squared distance is the exact sum of squared coordinate differences.
    p = np.array([[0.1, 0.2, 0.3]])
    q = np.array([[1.0 / 3.0, -2.5, 1e-7]])
    answer = gjklab.exact(p, q)
    expected = sum((Fraction(x) - Fraction(y)) ** 2 for x, y in zip(p[0], q[0]))
    assert answer.distance_squared == expected
    assert not answer.intersect
    assert answer.distance == math.sqrt(float(expected)) or abs(
        answer.distance - math.sqrt(float(expected))) <= 1e-16 * answer.distance
    # Two unit cubes overlapping by 1/4 along x: depth 1/4, exactly.
    cube = np.array([[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)])
    answer = gjklab.exact(cube, cube + [0.75, 0.0, 0.0], depth=True)
    assert answer.intersect
    assert answer.distance_squared == 0
    assert answer.depth_squared == Fraction(1, 16)
    assert (answer.hull_vertices_a, answer.hull_vertices_b) == (8, 8)


def test_options_go_through_the_registry_schema():
    a = np.random.default_rng(1).normal(size=(64, 3))
    b = a + [3.0, 0.0, 0.0]
    default = gjklab.query(a, b, "gjk-johnson")
    # Every documented default, given explicitly, changes nothing.
    defaults = gjklab.algorithms()["gjk-johnson"]["options"]
    assert "max_iterations" in defaults and "relative_gap" in defaults
    explicit = gjklab.query(a, b, "gjk-johnson", **defaults)
    assert answer(explicit) == answer(default)
    # An option takes effect: one iteration is a reported step limit, not an answer.
    short = gjklab.query(a, b, "gjk-johnson", max_iterations=1)
    assert short.iterations == 1 and short.termination == "step_limit"
    assert default.termination == "converged"
    # Vectors and booleans as experiment files give them.
    turned = gjklab.query(a, b, "gjk-johnson", initial_direction=[0, 0, 1], recenter=False,
                          start="fixed_direction")
    assert turned.distance == pytest.approx(default.distance, rel=1e-12)


def test_every_algorithm_lists_its_options_with_defaults():
    listed = gjklab.algorithms()
    assert {"gjk-bool", "gjk-johnson", "epa", "exact", "libccd-gjk"} <= set(listed)
    for name, entry in listed.items():
        assert entry["kind"] in ("boolean", "distance", "exact")
        assert entry["group"] in ("gjk", "own", "peer", "oracle")
        assert (entry["group"] == "peer") == entry["peer"]
        assert isinstance(entry["description"], str) and entry["description"]
        for key, default in entry["options"].items():
            # Each default is accepted back as the option's value.
            if name != "exact":
                gjklab.query([[0.0, 0.0, 0.0]], [[1.0, 0.0, 0.0]], name, **{key: default})


def test_the_module_and_gjklab_names_list_the_same_algorithms_and_defaults():
    # Two paths to the registry: the module reads the defaults back from their archived text,
    # `gjklab names --json` from the options struct itself.
    listed = gjklab.algorithms()
    named = json.loads(run_cli("names", "--json").stdout)["algorithms"]
    assert [a["name"] for a in named] == list(listed)
    for a in named:
        entry = listed[a["name"]]
        assert (a["group"], a["kind"], a["answers"]["depth"]) == \
            (entry["group"], entry["kind"], entry["depth"])
        assert {o["key"]: o["default"] for o in a["options"]} == entry["options"], a["name"]


def test_sphere_swept_shapes():
    # A sphere (a point swept by 1) and a capsule 5 apart along x: distance 5 - 1 - 0.5.
    sphere = np.zeros((1, 3))
    capsule = np.array([[5.0, -1.0, 0.0], [5.0, 1.0, 0.0]])
    result = gjklab.query(sphere, capsule, "gjk-johnson", radius_a=1.0, radius_b=0.5)
    assert result.distance == pytest.approx(3.5, rel=1e-15)
    answer = gjklab.exact(sphere, capsule, radius_a=1.0, radius_b=0.5)
    assert answer.swept and answer.distance == 3.5 and answer.distance_squared == 25


def test_shapes_built_once_answer_as_arrays(pairs):
    for _, a, b in pairs[:60]:
        shape_a, shape_b = gjklab.Shape(a), gjklab.Shape(b)
        assert len(shape_a) == len(a)
        assert np.array_equal(shape_a.vertices, a)
        for algorithm in ("gjk-bool", "gjk-johnson", "epa", "libccd-gjk"):
            from_arrays = answer(gjklab.query(a, b, algorithm))
            assert answer(gjklab.query(shape_a, shape_b, algorithm)) == from_arrays
            assert answer(gjklab.query(shape_a, b, algorithm)) == from_arrays
        assert gjklab.exact(shape_a, shape_b).distance_squared == gjklab.exact(
            a, b).distance_squared
    with pytest.raises(ValueError, match="^cloud shape point 0: non-finite coordinate$"):
        gjklab.Shape([[float("nan"), 0.0, 0.0]])
