"""Every error path: bad data is minksum.InputError (file, place, problem), a bad request ValueError or TypeError."""

import math
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
    with pytest.raises(ValueError, match=r"t\[0\]: expected a triple"):
        o.collide((1, 2))


def test_input_error_pickles():
    import pickle

    e = minksum.InputError("a.off", "line 3", "NaN")
    f = pickle.loads(pickle.dumps(e))
    assert (f.file, f.place, f.problem, str(f)) == ("a.off", "line 3", "NaN", "a.off: line 3: NaN")
