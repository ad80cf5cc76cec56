"""minksum.Solid and non-convex sums: exact agreement with `minksum stats` and `minksum sum --json`."""

from fractions import Fraction

import numpy as np
import pytest

import minksum
from conftest import cli_json


def test_tube_stats():
    t = minksum.Solid.load("tube")
    st = t.stats
    assert (st["vertices"], st["edges"], st["facets"]) == (16, 32, 16)
    assert st["volume"] == Fraction(6) and isinstance(st["volume"], Fraction) and st["volume_float"] == 6.0
    assert (st["genus"], st["shells"]) == (1, 1)
    assert st["bounding_box"] == ((-1, -1, -1), (1, 1, 1))
    assert t.volume() == 6 and not t.is_convex
    assert (t.num_vertices, t.num_edges, t.num_facets) == (16, 32, 16)


def test_from_arrays_round_trip():
    t = minksum.Solid.load("tube")
    v = t.vertices
    assert v.dtype == np.float64 and v.shape == (16, 3)
    assert [tuple(map(Fraction, row)) for row in v.tolist()] == t.exact_vertices()
    again = minksum.Solid(v, t.faces)
    assert again.stats == t.stats
    tri = minksum.Solid(v, t.triangles())  # an (m, 3) int64 array
    assert t.triangles().shape == (32, 3) and t.triangles().dtype == np.int64
    assert (tri.num_facets, tri.volume(), tri.stats["genus"]) == (32, tri.volume(), 1)
    assert tri.volume() == 6


def test_exact_vertices_in():
    # a unit cube scaled by 1/3, as text: the exact volume 1/27
    c = minksum.Polytope.hull([(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)])
    v = [tuple(f"{int(q)}/3" for q in row) for row in c.vertices.tolist()]
    s = minksum.Solid(v, c.faces)
    assert s.volume() == Fraction(1, 27) and s.is_convex
    assert s.stats["bounding_box"] == ((0, 0, 0), (Fraction(1, 3),) * 3)


def test_stats_agree_with_the_cli():
    cli = cli_json("stats", "tube")
    st = minksum.Solid.load("tube").stats
    assert (st["vertices"], st["edges"], st["facets"]) == (cli["vertices"], cli["edges"], cli["facets"])
    assert st["volume"] == Fraction(cli["volume"])


@pytest.mark.parametrize("a", ["tube", "Solid"])
def test_sum_agrees_with_the_cli(a):
    cli = cli_json("sum", "tube", "sphere:2@scale:1/4", "--exact")
    operand = minksum.Solid.load("tube") if a == "Solid" else "tube"
    s = minksum.minkowski_sum(operand, minksum.load("sphere:2@scale:1/4"))
    assert isinstance(s, minksum.SolidSum) and isinstance(s, minksum.Solid)
    assert (s.num_vertices, s.num_edges, s.num_facets) == (cli["vertices"], cli["edges"], cli["facets"])
    assert s.volume() == Fraction(cli["volume"])
    assert s.stats["volume_float"] == cli["volume_double"]
    assert s.pieces == (cli["pieces"]["a"], cli["pieces"]["b"])
    assert (s.pairs, s.pair_facets, s.candidate_facets, s.culled_facets) == (
        cli["pairs"], cli["pair_facets"], cli["candidate_facets"], cli["culled_facets"])
    assert (s.clips, s.shells, s.non_manifold_edges, s.dropped_components) == (
        cli["union"]["clips"], cli["union"]["shells"], cli["union"]["non_manifold_edges"],
        cli["union"]["dropped_components"])
    assert (s.method, s.swept) == (cli["nonconvex_method"], cli["swept"])
    assert set(s.phases) == {"decompose", "pairs", "union", "boundary"}
    assert s.seconds == pytest.approx(sum(s.phases.values()))
    assert s.stats["genus"] == 1 and s.stats["shells"] == 1


def test_sum_operand_order_and_result_as_operand():
    b = minksum.load("cube@scale:1/8")
    ab = minksum.minkowski_sum("tube", b)
    ba = minksum.minkowski_sum(b, minksum.Solid.load("tube"))
    assert ab.volume() == ba.volume() and ab.stats == ba.stats
    assert ab.swept == "a" and ba.swept == "b"
    # the result of a sum is an operand again
    again = minksum.minkowski_sum(ab, "cube@scale:1/8")
    cli = cli_json("sum", "tube", "cube@scale:1/4", "--exact")
    assert again.volume() == Fraction(cli["volume"])


def test_convex_pairs_keep_the_convex_path():
    s = minksum.minkowski_sum("cube", "tetra")
    assert isinstance(s, minksum.Sum)
    # a Solid operand makes it a SolidSum, the same polytope
    ss = minksum.minkowski_sum(minksum.Solid.load("cube"), "tetra")
    assert isinstance(ss, minksum.SolidSum) and ss.is_convex
    assert ss.volume() == s.volume() and (ss.num_vertices, ss.num_edges, ss.num_facets) == (
        s.num_vertices, s.num_edges, s.num_facets)
    assert not minksum.minkowski_sum("tube", "cube@scale:1/8").is_convex


def test_bad_solids():
    t = minksum.Solid.load("tube")
    with pytest.raises(minksum.InputError, match="open mesh") as e:
        minksum.Solid(t.vertices, t.triangles()[:-1])
    assert e.value.file == "" and e.value.place.startswith("edge ")
    with pytest.raises(ValueError, match=r"faces\[3\]: 99 is not a vertex index \(0\.\.15\)"):
        minksum.Solid(t.vertices, [list(f) for f in t.faces[:3]] + [[0, 1, 99]])
    with pytest.raises(TypeError, match=r"faces\[0\]: expected integer vertex indices"):
        minksum.Solid(t.vertices, [[0.0, 1.0, 2.0]])
    with pytest.raises(ValueError, match=r"vertices\[1\]: not finite"):
        minksum.Solid(np.array([[0, 0, 0], [np.nan, 0, 0], [0, 1, 0], [0, 0, 1.0]]), [[0, 1, 2]])
    with pytest.raises(TypeError, match="Solid.load: expected a file path"):
        minksum.Solid.load(minksum.load("cube"))
    with pytest.raises(TypeError, match=r"^a: expected a Polytope"):
        minksum.minkowski_sum(3, "tube")


def test_save_then_the_commands_read_it(tmp_path):
    # A sum from Python, written as 'minksum sum -o' writes it; then 'stats', 'convert' and 'view' of
    # the file, and Solid.load of it: the exact file has the exact volume, the rounded one is a valid
    # solid within the rounding's displacement.
    import subprocess
    from conftest import minksum_bin

    s = minksum.minkowski_sum("tube", minksum.load("sphere:2@scale:1/4"))
    exact = tmp_path / "sum.off"
    assert s.save(exact, exact=True) is None
    back = minksum.Solid.load(str(exact))
    assert back.volume() == s.volume() and back.num_facets == s.num_facets
    assert cli_json("stats", str(exact))["volume"] == str(s.volume())
    stl = tmp_path / "sum.stl"
    r = s.save(stl, binary=True)
    assert r is not None and r["coordinates"] > 0 and 0 < r["max_displacement"] < 1e-5
    st = cli_json("stats", str(stl))
    assert st["kind"] == "solid" and st["genus"] == 1 == cli_json("stats", str(exact))["genus"]  # the hole stays
    assert abs(Fraction(st["volume"]) - s.volume()) < 1e-4
    out = cli_json("convert", str(stl), "-o", str(tmp_path / "sum.obj"))
    assert out["facets"] == st["facets"]
    page = tmp_path / "sum.html"
    subprocess.run([minksum_bin(), "view", str(stl), "-o", str(page)], check=True, capture_output=True)
    assert page.stat().st_size > 0
    with pytest.raises(ValueError):
        s.save(tmp_path / "sum.stl", exact=True)  # STL holds no rationals
    with pytest.raises(ValueError):
        s.save(tmp_path / "sum.xyz")
    with pytest.raises(OSError):
        s.save(tmp_path / "no" / "such" / "dir.off")
    # an empty erosion: a file with no faces
    e = minksum.erode("cube", "cube@scale:2")
    assert e.empty and e.save(tmp_path / "empty.off") is None
    assert (tmp_path / "empty.off").read_text().split()[:3] == ["OFF", "0", "0"]
