"""minksum.minkowski_sum: exact agreement with the command `minksum sum --json` on catalog pairs, for every method."""

from collections import Counter
from fractions import Fraction

import numpy as np
import pytest

import minksum
from conftest import cli_json

PAIRS = [
    ("cube", "tetra"),
    ("cube", "sphere:3"),
    ("dodecahedron", "truncated-cube"),
    ("sphere:3", "sphere:3@rot:5"),
    ("box:1:2:3", "octahedron"),
    ("tetra", "tetra@neg"),
    ("random:200:1", "random:200:2"),
    ("dioctagonal:17", "dioctagonal:17@rot:100,0,0,99"),
]
METHODS = [m for m in minksum.METHODS if m != "auto"]


def test_methods_are_the_cli_methods():
    assert set(minksum.METHODS) == {"auto", "walk", "chms", "cvms", "essdms", "mssd", "cgm"}


@pytest.mark.parametrize("a,b", PAIRS)
@pytest.mark.parametrize("method", ["auto"] + METHODS)
def test_agrees_with_the_cli(a, b, method):
    cli = cli_json("sum", a, b, "--method", method)
    s = minksum.minkowski_sum(minksum.load(a), minksum.load(b), method=method)
    assert isinstance(s, minksum.Sum) and isinstance(s, minksum.Polytope)
    assert (s.num_vertices, s.num_edges, s.num_facets) == (cli["vertices"], cli["edges"], cli["facets"])
    assert s.volume() == Fraction(cli["volume"])
    assert s.method == cli["method"]
    if "facet_types" in cli:
        kinds = Counter(kind for kind, _, _ in s.facet_provenance)
        assert {k: kinds.get(k, 0) for k in cli["facet_types"]} == cli["facet_types"]


@pytest.mark.parametrize("a,b", PAIRS[:5])
def test_every_method_gives_the_same_polytope(a, b):
    pa, pb = minksum.load(a), minksum.load(b)
    ref = minksum.minkowski_sum(pa, pb, "chms")
    for method in METHODS:
        s = minksum.minkowski_sum(pa, pb, method)
        assert sorted(s.exact_vertices()) == sorted(ref.exact_vertices()), method
        assert sorted(s.planes()) == sorted(ref.planes()), method


@pytest.mark.parametrize("method", METHODS)
def test_vertex_origin_and_provenance(method):
    a, b = minksum.load("truncated-cube"), minksum.load("sphere:2@rot:3")
    s = minksum.minkowski_sum(a, b, method)
    ea, eb, es = a.exact_vertices(), b.exact_vertices(), s.exact_vertices()
    origin = s.vertex_origin
    assert origin.shape == (s.num_vertices, 2) and origin.dtype == np.int64
    for v, (i, j) in enumerate(origin):
        assert es[v] == tuple(x + y for x, y in zip(ea[i], eb[j]))
    prov = s.facet_provenance
    assert len(prov) == s.num_facets
    dims = {"translated": ("facet", "vertex"), "corner": ("vertex", "facet"), "edge": ("edge", "edge"),
            "facet_facet": ("facet", "facet")}
    for kind, fa, fb in prov:
        if kind in dims:
            assert (fa[0], fb[0]) == dims[kind]
        else:
            assert kind == "facet_edge" and {fa[0], fb[0]} == {"facet", "edge"}


def test_operands_by_name_and_closed_form():
    # box ⊕ box is the box of the summed sides.
    s = minksum.minkowski_sum("box:1:2:3", "box:1/3:1/5:1/7")
    assert s.volume() == Fraction(4, 3) * Fraction(11, 5) * Fraction(22, 7)
    assert (s.num_vertices, s.num_facets) == (8, 6)
    # P ⊕ P = 2P: eight times the volume.
    p = minksum.load("sphere:2")
    assert minksum.minkowski_sum(p, p).volume() == 8 * p.volume()


def test_sum_of_a_sum_and_its_repr():
    s = minksum.minkowski_sum("cube", "tetra", method="walk")
    assert repr(s) == f"<minksum.Sum (walk): {s.num_vertices} vertices, {s.num_edges} edges, {s.num_facets} facets>"
    t = minksum.minkowski_sum(s, "octahedron")
    assert t.num_vertices > 0 and t.volume() > s.volume()


def test_help_explains_the_methods():
    doc = minksum.minkowski_sum.__doc__
    for m in minksum.METHODS:
        assert m + ":" in doc
    assert "auto" in doc and "walk" in doc


def test_sum_pickles_with_its_history():
    import pickle

    s = minksum.minkowski_sum("cube", "sphere:2@rot:1", "cvms")
    t = pickle.loads(pickle.dumps(s))
    assert t.method == "cvms"
    assert t.exact_vertices() == s.exact_vertices()
    assert np.array_equal(t.vertex_origin, s.vertex_origin)
    assert t.facet_provenance == s.facet_provenance
