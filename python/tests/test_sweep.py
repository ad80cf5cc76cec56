"""Sums with points, segments and flat polygons (docs/sweeps.md) from Python: ConvexSet in and out,
the same exact results as 'minksum sum', in minkowski_sum and minkowski_sum_many."""
import pickle
from fractions import Fraction

import numpy as np
import pytest

import minksum
from conftest import cli_json


def test_convex_set_from_points_is_the_exact_hull_in_its_dimension():
    p = minksum.ConvexSet([(1, 2, 3)])
    assert (p.dimension, p.kind, p.num_vertices) == (0, "point", 1)
    s = minksum.ConvexSet([(0, 0, 0), (1, 1, 1), ("1/2", "1/2", "1/2")])  # the middle point is no vertex
    assert (s.dimension, s.kind, s.num_vertices, s.num_edges) == (1, "segment", 2, 1)
    sq = minksum.ConvexSet(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0]]))
    assert (sq.dimension, sq.kind, sq.num_vertices, sq.num_facets) == (2, "polygon", 4, 1)
    assert sq.area_squared() == 1 and sq.volume() == 0
    assert sorted(sq.exact_vertices()) == [(0, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0)]
    assert sq.vertices.shape == (4, 3) and sq.vertices.dtype == np.float64
    assert sq.method is None and sq.route is None
    t = minksum.ConvexSet([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)])
    assert (t.dimension, t.kind, t.volume()) == (3, "polytope", Fraction(1, 6))


def test_convex_set_load():
    seg = minksum.ConvexSet.load("segment:0,0,0:3,1,2")
    assert seg.kind == "segment" and sorted(seg.exact_vertices()) == [(0, 0, 0), (3, 1, 2)]
    assert minksum.ConvexSet.load("square").kind == "polygon"
    with pytest.raises(ValueError):
        minksum.ConvexSet.load("nosuchshape")
    with pytest.raises(TypeError):
        minksum.ConvexSet.load(minksum.load("cube"))


def test_polytope_swept_along_a_segment_is_a_sum_with_its_route():
    swept = minksum.minkowski_sum("cube", minksum.ConvexSet.load("segment:0,0,0:3,1,2"))
    assert isinstance(swept, minksum.Sum)
    assert swept.route == "sweep"
    # a cube of side 2 swept along v: 8 + sum over the axes of |v_i| times the face area 4
    assert swept.volume() == 8 + 4 * (3 + 1 + 2)
    assert swept.facet_provenance == [] and swept.vertex_origin.shape == (0, 2)
    assert minksum.minkowski_sum("cube", "tetra").route is None


def test_lower_dimensional_results_are_convex_sets():
    rect = minksum.minkowski_sum(minksum.ConvexSet([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]),
                                 "segment:0,0,0:1,0,0")
    assert isinstance(rect, minksum.ConvexSet)
    assert (rect.kind, rect.num_vertices, rect.area_squared()) == ("polygon", 4, 4)
    assert rect.method == "walk" and rect.route in ("sweep", "hull")
    assert rect.seconds >= 0
    par = minksum.minkowski_sum("segment:0,0,0:2,0,0", "segment:0,0,0:1,1,0")
    assert (par.kind, par.area_squared()) == ("polygon", 4)
    moved = minksum.minkowski_sum("point:1,2,3", minksum.ConvexSet([(1, 1, 1)]))
    assert moved.kind == "point" and moved.exact_vertices() == [(2, 3, 4)]
    assert minksum.minkowski_sum("cube", "point:1,2,3").volume() == 8


def test_a_set_with_a_non_convex_solid_is_refused():
    with pytest.raises(ValueError, match="non-convex solid"):
        minksum.minkowski_sum("tube", minksum.ConvexSet.load("segment:0,0,0:1,0,0"))
    with pytest.raises(ValueError, match="only walk|walk"):
        minksum.minkowski_sum("cube", "segment:0,0,0:1,0,0", method="cgm")


def test_many_takes_sets_and_gives_what_minkowski_sum_gives():
    pairs = [("cube", "segment:0,0,0:3,1,2"), ("segment:0,0,0:2,0,0", "segment:0,0,0:1,1,0"),
             ("tube", "cube@scale:1/8"), ("cube", "tetra")]
    many = minksum.minkowski_sum_many(pairs, threads=2)
    for (a, b), r in zip(pairs, many):
        one = minksum.minkowski_sum(a, b)
        assert type(r) is type(one)
        assert r.volume() == one.volume()
        assert r.num_vertices == one.num_vertices
    assert [type(r).__name__ for r in many] == ["Sum", "ConvexSet", "SolidSum", "Sum"]


@pytest.mark.parametrize("a,b", [("cube", "segment:0,0,0:3,1,2"), ("segment:0,0,0:2,0,0", "square"),
                                 ("tube", "sphere:1@scale:1/4")])
def test_same_as_the_command(a, b):
    out = cli_json("sum", a, b)
    r = minksum.minkowski_sum(a, b)
    assert str(r.volume()) == out["volume"]
    assert r.num_vertices == out["vertices"] and r.num_facets == out["facets"]


def test_every_kind_of_result_pickles_exactly():
    for r in [minksum.minkowski_sum("cube", "segment:0,0,0:3,1,2"),
              minksum.minkowski_sum("segment:0,0,0:2,0,0", "segment:0,0,0:1,1,0"),
              minksum.minkowski_sum("tube", "cube@scale:1/8"),
              minksum.erode("lshape", "cube@scale:1/4"),
              minksum.ConvexSet([(0, 0, 0), ("1/3", 0, 0), (0, "1/7", 0)]),
              minksum.Solid.load("tube")]:
        back = pickle.loads(pickle.dumps(r))
        assert type(back) is type(r)
        assert back.volume() == r.volume()
        assert back.exact_vertices() == r.exact_vertices()
        assert back.num_facets == r.num_facets
        for attr in ("route", "method", "operation", "pieces", "clips", "shells", "kind", "dimension"):
            if hasattr(r, attr):
                assert getattr(back, attr) == getattr(r, attr), attr
    s = pickle.loads(pickle.dumps(minksum.minkowski_sum("tube", "cube@scale:1/8")))
    assert minksum.minkowski_sum(s, "cube@scale:1/8").volume() > s.volume()  # an operand again
