"""minksum.erode, opening and closing: exact agreement with `minksum erode|open|close --json`."""

from fractions import Fraction

import pytest

import minksum
from conftest import cli_json


def test_erode_l_by_cube_matches_the_command():
    e = minksum.erode("lshape", "cube@scale:1/4")
    assert isinstance(e, minksum.SolidSum)
    assert (e.operation, e.empty) == ("erosion", False)
    assert e.volume() == Fraction(5, 8)
    assert e.shells == 1 and e.num_facets == 8
    j = cli_json("erode", "lshape", "cube@scale:1/4")
    assert Fraction(j["volume"]) == e.volume()
    assert (j["vertices"], j["facets"], j["pairs"]) == (e.num_vertices, e.num_facets, e.pairs)


def test_opening_and_closing_of_an_l_by_a_smaller_cube_are_the_l():
    l = minksum.Solid.load("lshape")
    for f, name in ((minksum.opening, "opening"), (minksum.closing, "closing")):
        r = f(l, minksum.load("cube@scale:1/4"))
        assert r.operation == name
        assert r.volume() == l.volume() == 3
    assert minksum.open is minksum.opening and minksum.close is minksum.closing
    assert "open" not in minksum.__all__ and "closing" in minksum.__all__


def test_erosion_that_empties_and_that_splits():
    e = minksum.erode("cube", "cube@scale:2")
    assert e.empty and e.volume() == 0 and e.num_facets == 0 and e.shells == 0
    # the tube's walls, 1/2 thick, eroded by a cube of side 1/4: still a ring (genus 1)
    t = minksum.erode("tube", "cube@scale:1/8")
    assert not t.empty and t.shells == 1 and t.stats["genus"] == 1


def test_erosion_and_opening_of_a_convex_a_take_the_half_space_path(tmp_path):
    # cube = [-1,1]^3 eroded by [-1/4,1/4]^3: [-3/4,3/4]^3, one pair, no union
    e = minksum.erode("cube", "cube@scale:1/4")
    assert (e.operation, e.empty, e.volume(), e.num_facets, e.pairs) == ("erosion", False, Fraction(27, 8), 6, 1)
    j = cli_json("erode", "cube", "cube@scale:1/4")
    assert (Fraction(j["volume"]), j["pairs"], j["union"]["clips"]) == (e.volume(), 1, 0)
    o = minksum.opening("dodecahedron", "sphere:2@scale:1/10")
    assert o.shells == 1 and o.volume() < minksum.Solid.load("dodecahedron").volume()
    o.save(tmp_path / "o.stl", binary=True)
    assert minksum.Solid.load(str(tmp_path / "o.stl")).volume() > 0


def test_save_of_a_convex_erosion_writes_the_commands_file(tmp_path):
    # The erosion and the opening of a convex a are convex polytopes, written as
    # the convex path writes one: the same bytes and rounding as the command's.
    for fn, command in ((minksum.erode, "erode"), (minksum.opening, "open")):
        r = fn("dodecahedron", "sphere:2@scale:1/10")
        for name, binary in (("x.stl", True), ("x.off", False)):
            mine, theirs = tmp_path / ("py-" + name), tmp_path / ("cli-" + name)
            rounding = r.save(mine, binary=binary)
            args = [command, "dodecahedron", "sphere:2@scale:1/10", "-o", str(theirs)]
            j = cli_json(*(args + (["--binary"] if binary else [])))
            assert mine.read_bytes() == theirs.read_bytes(), (command, name)
            assert rounding is not None and rounding["coordinates"] == j["rounding"]["coordinates"] > 0
            assert rounding["max_displacement"] == j["rounding"]["max_displacement"]
            assert minksum.load(str(mine)).num_facets > 0  # reads back as a convex polytope


def test_b_must_be_convex():
    with pytest.raises(ValueError, match="convex"):
        minksum.erode("cube", "lshape")
    with pytest.raises(ValueError, match="unknown method|method"):
        minksum.opening("lshape", "cube@scale:1/4", method="nonsense")


def test_opening_inside_a_inside_closing():
    a = minksum.Solid.load("star:5")
    b = minksum.load("sphere:1@scale:1/8")
    o, c = minksum.opening(a, b), minksum.closing(a, b)
    assert o.volume() <= a.volume() <= c.volume()
    assert o.volume() < a.volume() < c.volume()  # the star has convex and concave edges
