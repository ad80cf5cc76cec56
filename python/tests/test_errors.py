"""Every error path: bad data is minksum.InputError (file, place, problem), a bad request ValueError or TypeError."""

import math
import re
from fractions import Fraction

import numpy as np
import pytest

import minksum

# (file in tests/data/bad, place, a word of the problem) — as the command line reports them.
BAD_FILES = [
    ("nan.off", "line 4", "NaN"),
    ("garbage_token.off", "line", "number"),
    ("wrong_magic.off", "line 1", ""),
    ("empty.off", "", "empty"),
    ("open_mesh.off", "", ""),
    ("nonconvex_lprism.off", "", ""),
    ("out_of_range_index.obj", "line", ""),
    ("truncated.ply", "", ""),
    ("flat.off", "", ""),
]


@pytest.mark.parametrize("name,place,word", BAD_FILES)
def test_bad_file_is_an_input_error(data, name, place, word):
    path = str(data / "bad" / name)
    with pytest.raises(minksum.InputError) as e:
        minksum.load(path)
    err = e.value
    assert err.file == path
    assert err.place.startswith(place)
    assert word in err.problem and err.problem
    assert str(err) == path + (": " + err.place if err.place else "") + ": " + err.problem


def test_input_error_matches_the_command_line_message(data):
    import subprocess
    from conftest import minksum_bin

    path = str(data / "bad" / "nan.off")
    r = subprocess.run([minksum_bin(), "stats", path], capture_output=True, text=True)
    assert r.returncode == 3
    with pytest.raises(minksum.InputError) as e:
        minksum.load(path)
    assert r.stderr.strip() == "minksum: " + str(e.value)


def test_not_convex_is_an_input_error_and_hull_accepts_it(data):
    path = str(data / "bad" / "nonplanar_facet.off")
    with pytest.raises(minksum.NotConvexError) as e:
        minksum.load(path)
    assert isinstance(e.value, minksum.InputError)
    assert minksum.load(path, hull=True).num_vertices > 0


def test_missing_file_and_unknown_name():
    with pytest.raises(minksum.InputError, match="no such file"):
        minksum.load("/nonexistent/dir/p.off")
    with pytest.raises(ValueError, match="nosuchsolid"):
        minksum.load("nosuchsolid")
    with pytest.raises(ValueError, match="sphere"):
        minksum.load("sphere:99")


def test_degenerate_points_are_input_errors():
    with pytest.raises(minksum.InputError) as e:
        minksum.Polytope([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)])  # coplanar
    assert e.value.problem
    with pytest.raises(minksum.InputError):
        minksum.Polytope.hull(np.zeros((5, 3)))


def test_open_mesh_from_arrays_is_an_input_error():
    cube = minksum.load("cube")
    with pytest.raises(minksum.InputError):
        minksum.Polytope(cube.vertices, cube.faces[:-1])


@pytest.mark.parametrize(
    "vertices,match",
    [
        (np.zeros((4, 2)), r"\(n, 3\)"),
        (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, math.nan]]), "not finite"),
        (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, math.inf]]), "not finite"),
        ([(0, 0, 0), (1, 0), (0, 1, 0), (0, 0, 1)], r"vertices\[1\]: expected a triple"),
        ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, math.nan)], "NaN"),
        ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, "1/0")], "zero denominator"),
        ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, "x")], "not a number"),
        ([(0, 0, 0), np.zeros((3, 3)), (0, 1, 0), (0, 0, 1)], r"vertices\[1\]: expected a triple .* shape \(3, 3\)"),
        (np.array([(0, 0, 0), (1, 0)], dtype=object), r"vertices: expected an \(n, 3\) array, got .* shape \(2,\)"),
    ],
)
def test_bad_vertices_are_value_errors(vertices, match):
    with pytest.raises(ValueError, match=match):
        minksum.Polytope(vertices)


def test_wrong_types_are_type_errors():
    with pytest.raises(TypeError):
        minksum.Polytope([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, object())])
    with pytest.raises(TypeError):
        minksum.Polytope("cube")
    with pytest.raises(TypeError):
        minksum.minkowski_sum(1, "cube")
    with pytest.raises(TypeError):
        minksum.Polytope(np.eye(3), [(0, 1.5, 2)])


def test_bad_face_index_is_a_value_error():
    with pytest.raises(ValueError, match=r"faces\[0\]: 9 is not a vertex index \(0..3\)"):
        minksum.Polytope([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)], [(0, 1, 9)])
    with pytest.raises(ValueError, match="-1 is not a vertex index"):
        minksum.Polytope([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)], [(0, 1, -1)])


def test_unknown_method():
    with pytest.raises(ValueError, match=r"unknown method 'fast' \(auto, walk"):
        minksum.minkowski_sum("cube", "tetra", method="fast")
    with pytest.raises(ValueError, match="unknown method"):
        minksum.minkowski_sum_many([("cube", "tetra")], method="fast")
    with pytest.raises(ValueError, match="unknown method"):
        minksum.Obstacle("cube", "tetra", method="fast")


def test_save_errors(tmp_path):
    p = minksum.load("sphere:2@rot:1")
    with pytest.raises(ValueError, match="xyz"):
        p.save(tmp_path / "p.xyz")
    with pytest.raises(ValueError):
        p.save(tmp_path / "p.stl", exact=True)
    with pytest.raises(OSError):
        p.save(tmp_path / "no" / "such" / "dir" / "p.off")
    assert not list(tmp_path.iterdir())  # nothing half-written


def test_obstacle_errors():
    o = minksum.Obstacle("cube", "tetra")
    with pytest.raises(ValueError, match="zero vector"):
        o.directional_depth((0, 0, 0), (0, 0, 0))
    with pytest.raises(ValueError, match=r"t: expected a triple \(x, y, z\), got 2 items"):
        o.collide((1, 2))


def test_input_error_pickles():
    import pickle

    e = minksum.InputError("a.off", "line 3", "NaN")
    f = pickle.loads(pickle.dumps(e))
    assert (f.file, f.place, f.problem, str(f)) == ("a.off", "line 3", "NaN", "a.off: line 3: NaN")


CUBE = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
TETRA = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]


def wrong_type_calls():
    """(name, call, pattern of the message) for every public entry point given arguments of the wrong type."""
    cube = minksum.load("cube")
    o = minksum.Obstacle("cube", "tetra")
    return [
        ("Polytope(None)", lambda: minksum.Polytope(None), r"vertices: expected .* got NoneType"),
        ("Polytope(dict)", lambda: minksum.Polytope({0: (0, 0, 0)}), r"vertices: .* got dict"),
        ("Polytope(bytes)", lambda: minksum.Polytope(b"abc"), r"vertices: .* got bytes"),
        ("Polytope(flat list)", lambda: minksum.Polytope([0, 0, 0, 1, 1, 1]), r"vertices\[0\]: expected a triple .* got int"),
        ("Polytope(too deep)", lambda: minksum.Polytope([[(0, 0, 0), (1, 0, 0), (0, 1, 0)]]),
         r"vertices\[0\]\[0\]: expected a number .* got tuple"),
        ("Polytope(object array with None)", lambda: minksum.Polytope(np.array(TETRA[:3] + [(0, 0, None)], dtype=object)),
         r"vertices\[3\]\[2\]: expected a number .* got NoneType"),
        ("Polytope(datetime array)", lambda: minksum.Polytope(np.zeros((4, 3), dtype="datetime64[s]")),
         r"vertices: expected numbers, got an array of dtype datetime64"),
        ("Polytope(faces=5)", lambda: minksum.Polytope(TETRA, 5), r"faces: expected a sequence .* got int"),
        ("Polytope(flat faces)", lambda: minksum.Polytope(TETRA, [0, 1, 2]), r"faces\[0\]: expected a sequence .* got int"),
        ("Polytope(text face)", lambda: minksum.Polytope(TETRA, ["012"]), r"faces\[0\]: expected a sequence .* got str"),
        ("Polytope(float index)", lambda: minksum.Polytope(TETRA, [(0, 1, 2.0)]), r"faces\[0\]: expected integer .* got float"),
        ("Polytope.hull(None)", lambda: minksum.Polytope.hull(None), r"points: .* got NoneType"),
        ("load(None)", lambda: minksum.load(None), r"path_or_name: .* got NoneType"),
        ("minkowski_sum(None, ...)", lambda: minksum.minkowski_sum(None, "cube"), r"a: .* got NoneType"),
        ("minkowski_sum(method=5)", lambda: minksum.minkowski_sum("cube", "cube", 5), "incompatible function arguments"),
        ("minkowski_sum_many(None)", lambda: minksum.minkowski_sum_many(None), "incompatible function arguments"),
        ("minkowski_sum_many(operand 5)", lambda: minksum.minkowski_sum_many([("cube", 5)]), r"pairs\[0\]\[1\]: .* got int"),
        ("minkowski_sum_many(method 5)", lambda: minksum.minkowski_sum_many([("cube", "cube", 5)]),
         r"pairs\[0\]\[2\]: expected a method name \(str\), got int"),
        ("minkowski_sum_many(threads='2')", lambda: minksum.minkowski_sum_many([], threads="2"), "incompatible"),
        ("Obstacle(None, ...)", lambda: minksum.Obstacle(None, "cube"), r"p: .* got NoneType"),
        ("collide(None)", lambda: o.collide(None), r"t: expected a triple \(x, y, z\), got NoneType"),
        ("collide(str)", lambda: o.collide("123"), r"t: expected a triple \(x, y, z\), got str"),
        ("collide(dict)", lambda: o.collide({0: 1, 1: 2, 2: 3}), r"t: expected a triple \(x, y, z\), got dict"),
        ("distance(object array)", lambda: o.distance(np.array([1, None, 2], dtype=object)),
         r"t\[1\]: expected a number .* got NoneType"),
        ("depth(set)", lambda: o.depth({1, 2, 3}), r"t: expected a triple .* got set"),
        ("directional_depth(d=None)", lambda: o.directional_depth((0, 0, 0), None), r"d: expected a triple .* got NoneType"),
        ("translated(None)", lambda: cube.translated(None), r"t: expected a triple .* got NoneType"),
        ("translated(5)", lambda: cube.translated(5), r"t: expected a triple .* got int"),
        ("translated(text)", lambda: cube.translated((0, 0, b"1")), r"t\[2\]: expected a number .* got bytes"),
        ("translated(datetime)", lambda: cube.translated((np.datetime64("2020"), 0, 0)),
         r"t\[0\]: expected a number, got numpy.datetime64"),
        ("save(None)", lambda: cube.save(None), "NoneType"),
        ("Polytope.__setstate__", lambda: minksum.Polytope.__new__(minksum.Polytope).__setstate__((1, 2, 3)), ""),
    ]


@pytest.mark.parametrize("name", [name for name, _, _ in wrong_type_calls()])
def test_wrong_type_is_type_error(name):
    # TypeError naming the argument and the position — never RuntimeError ("Unable to cast") or SystemError.
    (call, match), = [(c, m) for n, c, m in wrong_type_calls() if n == name]
    with pytest.raises(Exception) as e:
        call()
    assert type(e.value) is TypeError, (name, repr(e.value))
    assert e.value.args and re.search(match, str(e.value)), (name, str(e.value))


def test_face_index_too_large_for_a_machine_word_is_value_error():
    with pytest.raises(ValueError, match=r"faces\[0\]: 1180591620717411303424 is not a vertex index \(0..3\)"):
        minksum.Polytope(TETRA, [(0, 1, 2**70)])


@pytest.mark.parametrize(
    "batch",
    [
        np.array([[3.0, 0, 0], [4.0, 0, 0]]),
        np.array([[3.0, 0, 0], [4.0, 0, 0], [5.0, 0, 0]]),  # three rows: once a SystemError
        np.array([[3, 0, 0]]),
        [(3, 0, 0), (4, 0, 0), (5, 0, 0)],
        [np.array([3.0, 0, 0]), np.array([4.0, 0, 0])],
    ],
)
def test_a_batch_of_translations_is_answered_a_batch_of_directions_refused(batch):
    o = minksum.Obstacle("box:2:2:2", "box:2:2:2")
    n = len(batch)
    # a batch of t: one answer per row (tests/test_obstacle_batch.py checks them against single calls)
    assert o.collide(batch).tolist() == [0] * n
    assert o.distance(batch).tolist() == [float(3 + i - 2) for i in range(n)]
    assert o.depth(batch).tolist() == [0.0] * n
    assert o.directional_depth(batch, (1, 0, 0)).tolist() == [0.0] * n
    with pytest.raises(ValueError, match=r"d: takes one direction, a triple \(x, y, z\), not a batch"):
        o.directional_depth((0, 0, 0), batch)
    # One translation, as a triple or an array of shape (3,), is answered exactly.
    assert o.distance(np.array([5.0, 0, 0])).squared_distance == 9
    assert o.distance([5, 0, 0]).squared_distance == 9
