"""Bad input is a ValueError with the command line's message; nothing crashes the interpreter."""

import threading

import numpy as np
import pytest

import gjklab
from conftest import run_cli

A = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
B = A + [3.0, 0.25, 0.5]


def cli_case_error(line):
    """The problem `gjklab query --cases` reports for one JSON line."""
    done = run_cli("query", "--cases", "-", "--algorithms", "gjk-johnson", stdin=line + "\n",
                   check=False)
    assert done.returncode == 1
    return done.stderr.strip().split(": ", 3)[-1]


def test_empty_cloud_has_the_cli_message():
    expected = cli_case_error('{"id": "x", "a": [], "b": [[0, 0, 0]]}')
    assert expected == "cloud a: empty point cloud"
    for empty in (np.zeros((0, 3)), []):
        with pytest.raises(ValueError) as raised:
            gjklab.query(empty, B)
        assert str(raised.value) == expected
    with pytest.raises(ValueError, match="^cloud b: empty point cloud$"):
        gjklab.exact(A, np.zeros((0, 3)))


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_coordinates_name_the_point(bad):
    cloud = B.copy()
    cloud[2, 1] = bad
    for call in (gjklab.query, gjklab.exact):
        with pytest.raises(ValueError, match="^cloud b point 2: non-finite coordinate$"):
            call(A, cloud)


def test_unknown_algorithm_has_the_cli_message():
    done = run_cli("query", "--cases", "-", "--algorithms", "gjk-nope", stdin="", check=False)
    assert done.returncode == 2
    # The first line; a second one lists the peers that answer mesh cases only (fcl-bvh).
    expected = done.stderr.splitlines()[0].removeprefix("gjklab query: ")
    with pytest.raises(ValueError) as raised:
        gjklab.query(A, B, "gjk-nope")
    assert str(raised.value) == expected


@pytest.mark.parametrize("shape", [(4,), (4, 2), (4, 4), (2, 4, 3), (3, 1), ()])
def test_wrong_shapes(shape):
    with pytest.raises(ValueError, match="cloud a: expected an n×3 array, got shape"):
        gjklab.query(np.ones(shape), B)


@pytest.mark.parametrize("dtype", [np.float32, np.int64, np.int32, np.complex128, np.bool_,
                                   object, ">f8"])
def test_wrong_dtypes_are_refused_not_converted(dtype):
    with pytest.raises(ValueError, match="cloud a: expected float64 coordinates, got dtype"):
        gjklab.query(A.astype(dtype), B)


@pytest.mark.parametrize("bad", ["points", None, 3.0, {"a": 1}, [[0, 0]], [[0, 0, "x"]]])
def test_things_that_are_not_arrays(bad):
    with pytest.raises(ValueError, match="^cloud a: "):
        gjklab.query(bad, B)


def test_lists_and_non_contiguous_arrays_give_the_same_answer():
    rng = np.random.default_rng(7)
    big = rng.normal(size=(64, 6))
    a = big[::2, 1:4]  # strided rows and columns
    b = np.asfortranarray(rng.normal(size=(20, 3)) + 4.0)
    reference = gjklab.query(np.ascontiguousarray(a), np.ascontiguousarray(b))
    for left, right in ((a, b), (a.tolist(), b.tolist()), (a.T.copy().T, b[::-1][::-1])):
        assert gjklab.query(left, right).distance == reference.distance


def test_bad_options_are_value_errors():
    with pytest.raises(ValueError, match="option 'colour' does not apply to gjk-johnson; "
                                         "valid: max_iterations, "):
        gjklab.query(A, B, colour=1)
    with pytest.raises(ValueError, match="must be >= 0, got -1"):
        gjklab.query(A, B, relative_gap=-1)
    with pytest.raises(ValueError, match="must be an integer >= 1"):
        gjklab.query(A, B, max_iterations=0.5)
    with pytest.raises(ValueError, match="unknown criterion 'fast'"):
        gjklab.query(A, B, convergence="fast")
    with pytest.raises(ValueError, match="expected a number, a boolean, a string"):
        gjklab.query(A, B, relative_gap={"x": 1})
    with pytest.raises(ValueError, match="expected \\[x, y, z\\]"):
        gjklab.query(A, B, initial_direction=[1, 0])
    with pytest.raises(ValueError, match="must be finite and non-zero"):
        gjklab.query(A, B, initial_direction=[0, 0, 0])
    with pytest.raises(ValueError, match="radius_a: expected a finite number >= 0, got nan"):
        gjklab.query(A, B, radius_a=float("nan"))
    with pytest.raises(ValueError, match="radius_b: expected a finite number >= 0, got -1"):
        gjklab.exact(A, B, radius_b=-1.0)


def test_option_errors_read_as_in_experiment_files(tmp_path):
    experiment = ('name = "x"\nseed = 1\ncases = 1\n[[family]]\nshape = "box"\n'
                  '[[algorithm]]\nname = "gjk-johnson"\nrelative_gap = -1\n')
    with pytest.raises(ValueError) as from_file:
        gjklab.run(experiment, out=str(tmp_path / "x.h5"))
    with pytest.raises(ValueError) as from_query:
        gjklab.query(A, B, relative_gap=-1)
    problem = str(from_query.value).split(": ", 2)[-1]
    assert str(from_file.value).endswith(".relative_gap': " + problem)
    assert str(from_query.value) == "gjk-johnson: option 'relative_gap': " + problem


def test_extreme_but_valid_inputs_answer():
    huge = A * 1e300
    assert gjklab.query(huge, huge + 1e300).termination
    tiny = A * 1e-300
    assert gjklab.exact(tiny, tiny + 1e-300).distance_squared >= 0
    one = np.zeros((1, 3))
    assert gjklab.query(one, one).intersect


def test_queries_release_the_gil():
    # An exact answer on large clouds takes a while in C++; while it runs, this thread must
    # keep running Python.
    rng = np.random.default_rng(3)
    a = rng.normal(size=(200_000, 3))
    b = rng.normal(size=(200_000, 3)) + 0.5
    started = threading.Event()
    counted = []

    def work():
        started.set()
        gjklab.exact(a, b)

    worker = threading.Thread(target=work)
    worker.start()
    started.wait()
    count = 0
    while worker.is_alive():
        count += 1
    worker.join()
    counted.append(count)
    assert counted[0] > 10_000


def test_large_clouds_name_the_non_finite_point():
    # From 4096 points the shapes are built with the GIL released; the message is the same.
    rng = np.random.default_rng(11)
    cloud = rng.normal(size=(5000, 3))
    cloud[4321, 2] = np.inf
    with pytest.raises(ValueError, match="^cloud a point 4321: non-finite coordinate$"):
        gjklab.query(cloud, B)
    with pytest.raises(ValueError, match="^cloud shape point 4321: non-finite coordinate$"):
        gjklab.Shape(cloud)


def test_unaligned_and_strided_arrays_answer_as_contiguous_ones():
    rng = np.random.default_rng(12)
    a, b = rng.normal(size=(300, 3)), rng.normal(size=(300, 3)) + 2.5
    raw = bytearray(a.nbytes + 1)
    unaligned = np.frombuffer(raw, dtype=np.float64, count=a.size, offset=1).reshape(a.shape)
    unaligned[...] = a
    assert not unaligned.flags.aligned
    strided = np.asfortranarray(b)
    reference = gjklab.query(gjklab.Shape(a), gjklab.Shape(b))
    result = gjklab.query(unaligned, strided)
    assert (result.distance, result.iterations) == (reference.distance, reference.iterations)


def test_shapes_from_arrays_of_changing_sizes_answer_as_shapes_built_once():
    # Shapes built from arrays reuse storage from one query to the next.
    rng = np.random.default_rng(13)
    pairs = [(rng.normal(size=(n, 3)), rng.normal(size=(m, 3)) + [1.5, 0, 0])
             for n, m in ((3000, 5), (1, 9000), (40, 40), (8193, 8191), (7, 2))]
    expected = [gjklab.query(gjklab.Shape(a), gjklab.Shape(b)) for a, b in pairs]
    for _ in range(2):
        for (a, b), want in zip(pairs, expected):
            got = gjklab.query(a, b)
            assert (got.distance, got.iterations, got.intersect) == \
                (want.distance, want.iterations, want.intersect)


def test_a_query_run_while_converting_an_input_leaves_the_outer_query_intact():
    # Converting b may run Python code (here __array__), which may itself query: the outer
    # query's shape a must not be overwritten by the inner query's shapes.
    rng = np.random.default_rng(14)
    a, b = rng.normal(size=(50, 3)), rng.normal(size=(60, 3)) + [3.0, 0, 0]
    inner = []

    class Converting:
        def __array__(self, dtype=None, copy=None):
            inner.append(gjklab.query(rng.normal(size=(70, 3)), rng.normal(size=(80, 3))))
            return b

    want = gjklab.query(gjklab.Shape(a), gjklab.Shape(b))
    got = gjklab.query(a, Converting())
    assert inner and (got.distance, got.iterations) == (want.distance, want.iterations)
