"""minksum.Polytope: construction from numpy and from exact numbers, the views and exact accessors, files, pickling."""

import pickle
from fractions import Fraction

import numpy as np
import pytest

import minksum

CUBE = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]


def test_hull_of_cube_corners_from_numpy():
    p = minksum.Polytope(np.array(CUBE, dtype=np.float64))
    assert (p.num_vertices, p.num_edges, p.num_facets) == (8, 12, 6)
    assert p.volume() == 1
    assert isinstance(p.volume(), Fraction)
    assert p.coordinates_are_doubles


def test_hull_drops_interior_points():
    pts = CUBE + [(Fraction(1, 2), Fraction(1, 3), Fraction(1, 7))]
    p = minksum.Polytope.hull(pts)
    assert p.num_vertices == 8


def test_exact_fraction_vertices_round_trip():
    third = Fraction(1, 3)
    big = Fraction(2**200 + 1, 3**90)
    tetra = [(0, 0, 0), (third, 0, 0), (0, big, 0), (0, 0, Fraction(-5, 7))]
    p = minksum.Polytope(tetra)
    assert not p.coordinates_are_doubles
    exact = p.exact_vertices()
    assert sorted(exact) == sorted(tuple(Fraction(c) for c in v) for v in tetra)
    for v in exact:
        assert all(isinstance(c, Fraction) for c in v)
    # The volume of the tetrahedron |x y z| / 6, exactly.
    assert p.volume() == third * big * Fraction(5, 7) / 6
    # float64 view: the nearest doubles.
    assert np.array_equal(np.sort(p.vertices[:, 1]), np.sort(np.array([0.0, 0.0, 0.0, float(big)])))


def test_text_and_int_coordinates_are_exact():
    p = minksum.Polytope([("0", "0", "0"), ("1/3", 0, 0), (0, 2**70, 0), (0, 0, "1e-3")])
    assert Fraction(1, 3) in [v[0] for v in p.exact_vertices()]
    assert 2**70 in [v[1] for v in p.exact_vertices()]
    assert Fraction(0.001) in [v[2] for v in p.exact_vertices()]  # the double nearest 1e-3, exactly


def test_float_input_is_taken_exactly():
    p = minksum.Polytope([(0, 0, 0), (0.1, 0, 0), (0, 0.1, 0), (0, 0, 0.1)])
    assert Fraction(0.1) in [v[0] for v in p.exact_vertices()]
    assert p.volume() == Fraction(0.1) ** 3 / 6


def test_vertices_is_a_view_without_copy():
    p = minksum.load("sphere:4")
    v = p.vertices
    assert v.dtype == np.float64 and v.shape == (p.num_vertices, 3)
    assert not v.flags.writeable and not v.flags.owndata
    assert v.base is p
    w = p.vertices
    assert np.shares_memory(v, w)  # both views of the polytope's own storage
    with pytest.raises(ValueError):
        v[0, 0] = 1.0


def test_vertices_view_keeps_the_polytope_alive():
    v = minksum.load("random:100:3").vertices
    import gc

    gc.collect()
    assert np.all(np.abs(np.linalg.norm(v, axis=1) - 1) < 1e-6)


def test_faces_are_ccw_from_outside_and_match_planes():
    p = minksum.load("truncated-cube")
    faces, planes = p.faces, p.planes()
    assert len(faces) == len(planes) == p.num_facets == 14
    ex = p.exact_vertices()
    for loop, (a, b, c, d) in zip(faces, planes):
        assert all(isinstance(k, int) for k in (a, b, c, d))
        for i in loop:
            x, y, z = ex[i]
            assert a * x + b * y + c * z == d  # on the plane, exactly
        # CCW from outside: the loop's normal (Newell) points along (a, b, c).
        pts = np.array([p.vertices[i] for i in loop])
        n = np.cross(pts[1] - pts[0], pts[2] - pts[0])
        assert np.dot(n, [a, b, c]) > 0
    for x, y, z in ex:  # every vertex on or below every plane
        assert all(a * x + b * y + c * z <= d for a, b, c, d in planes)


def test_triangles_cover_the_facets():
    p = minksum.load("dodecahedron")
    t = p.triangles()
    assert t.shape == (sum(len(f) - 2 for f in p.faces), 3) == (36, 3)
    assert t.dtype == np.int64


def test_explicit_faces_merge_coplanar_triangles():
    p = minksum.load("cube")
    tris = p.triangles()
    q = minksum.Polytope(p.vertices, tris)
    assert (q.num_vertices, q.num_edges, q.num_facets) == (8, 12, 6)
    assert q.volume() == p.volume()


def test_save_and_load_round_trip_exact(tmp_path):
    p = minksum.load("sphere:2@rot:5")
    assert not p.coordinates_are_doubles
    path = tmp_path / "s.off"
    p.save(path, exact=True)
    q = minksum.load(str(path))
    assert q.exact_vertices() == p.exact_vertices()
    assert q.planes() == p.planes()
    p.save(tmp_path / "s.stl", binary=True)
    assert minksum.load(tmp_path / "s.stl").num_facets == p.num_facets


def test_load_hull_of_a_triangulated_stl(data):
    p = minksum.load(str(data / "bad" / "triangulated_cube.stl"))
    assert (p.num_vertices, p.num_facets) == (8, 6)


@pytest.mark.parametrize("spec", ["cube", "sphere:3@rot:2", "box:1:1/3:2"])
def test_pickle_keeps_vertices_in_order(spec):
    p = minksum.load(spec)
    q = pickle.loads(pickle.dumps(p))
    assert q.exact_vertices() == p.exact_vertices()
    assert [list(f) for f in q.faces] == [list(f) for f in p.faces]


def test_repr():
    assert repr(minksum.load("cube")) == "<minksum.Polytope: 8 vertices, 12 edges, 6 facets>"


def test_translated_and_negated():
    p = minksum.load("tetra")
    t = p.translated((Fraction(1, 3), 0, 2))
    assert t.volume() == p.volume()
    assert [v[0] - Fraction(1, 3) for v in t.exact_vertices()] == [v[0] for v in p.exact_vertices()]
    n = p.negated()
    assert sorted(n.exact_vertices()) == sorted(tuple(-c for c in v) for v in p.exact_vertices())


def test_pickle_of_a_sum_of_doubles_keeps_every_bit():
    # Vertices that are exact sums hi + lo of two doubles travel as both doubles.
    s = minksum.minkowski_sum("random:50:1", "random:50:2")
    assert not s.coordinates_are_doubles
    t = pickle.loads(pickle.dumps(s))
    assert t.exact_vertices() == s.exact_vertices()
    assert np.array_equal(t.vertices, s.vertices)
