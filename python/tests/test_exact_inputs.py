"""Coordinates are taken exactly or refused: Decimal and Fraction exactly, float as its double, complex and
numpy.longdouble refused with TypeError naming the argument and the position — at every entry point."""

from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

import minksum

CUBE = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]


def scaled_cube(s):
    return [tuple(s if c else 0 for c in v) for v in CUBE]


def test_decimal_is_exact():
    tenth = Decimal("0.1")
    p = minksum.Polytope(scaled_cube(tenth))
    assert p.volume() == Fraction(1, 1000)
    assert {c for v in p.exact_vertices() for c in v} == {0, Fraction(1, 10)}
    assert not p.coordinates_are_doubles  # 1/10 is not a double
    assert minksum.Polytope.hull(scaled_cube(tenth)).volume() == Fraction(1, 1000)
    # With faces, as a mesh.
    cube = minksum.load("cube")  # [-1, 1]^3
    mesh = [tuple(Decimal(int(c)) * Decimal("0.05") + Decimal("0.05") for c in v) for v in cube.vertices]
    assert minksum.Polytope(mesh, cube.faces).volume() == Fraction(1, 1000)
    # Object arrays of Decimals, large exponents and many digits.
    q = minksum.Polytope(np.array(scaled_cube(Decimal("1e-30")), dtype=object))
    assert q.volume() == Fraction(1, 10**90)
    r = minksum.Polytope(scaled_cube(Decimal("0.333333333333333333333333333333")))
    assert r.volume() == Fraction(333333333333333333333333333333, 10**30) ** 3
    # Translations and queries.
    assert {c for v in p.translated((Decimal("0.2"), 0, 0)).exact_vertices() for c in v} >= {Fraction(3, 10)}
    o = minksum.Obstacle("box:2:2:2", "box:2:2:2")  # M = [-2, 2]^3
    assert o.distance((Decimal("4.1"), 0, 0)).squared_distance == Fraction(21, 10) ** 2
    assert o.depth((Decimal("1.9"), 0, 0)).squared_depth == Fraction(1, 10) ** 2
    assert o.directional_depth((Decimal("1.9"), 0, 0), (Decimal("-0.1"), 0, 0)).t == 1
    assert o.collide((Decimal("2.0"), Decimal("-1.5"), 0)).status == "touching"
    assert minksum.minkowski_sum(p, p).volume() == Fraction(8, 1000)


@pytest.mark.parametrize("bad,word", [(Decimal("NaN"), "NaN"), (Decimal("sNaN"), "NaN"),
                                      (Decimal("Infinity"), "Infinity"), (Decimal("-Infinity"), "Infinity")])
def test_decimal_not_finite_is_value_error(bad, word):
    pts = CUBE[:3] + [(0, 0, bad)]
    with pytest.raises(ValueError, match=r"vertices\[3\]\[2\]: .*" + word + ".* not a finite number"):
        minksum.Polytope(pts)
    with pytest.raises(ValueError, match=r"t\[1\]: .*not a finite number"):
        minksum.Obstacle("cube", "tetra").distance((0, bad, 0))


def test_int_fraction_and_float_are_exact():
    big = 2**100 + 1
    p = minksum.Polytope(scaled_cube(big))
    assert p.volume() == big**3
    f = Fraction(1, 3)
    assert minksum.Polytope(scaled_cube(f)).volume() == Fraction(1, 27)
    assert minksum.Polytope(scaled_cube(0.1)).volume() == Fraction(0.1) ** 3  # the double, exactly
    assert minksum.Polytope(np.array(scaled_cube(0.1))).volume() == Fraction(0.1) ** 3
    # numpy integer and float scalars of at most 64 bits, and float32 / int arrays: exact.
    assert minksum.Polytope(scaled_cube(np.int64(3))).volume() == 27
    assert minksum.Polytope(scaled_cube(np.float32(0.1))).volume() == Fraction(float(np.float32(0.1))) ** 3
    assert minksum.Polytope(np.array(scaled_cube(0.1), dtype=np.float32)).volume() == Fraction(
        float(np.float32(0.1))) ** 3
    assert minksum.Polytope(np.array(scaled_cube(2**62), dtype=np.int64)).volume() == 2**186
    assert minksum.Polytope(np.array(scaled_cube(2**63), dtype=np.uint64)).volume() == 2**189


LONG = np.longdouble
needs_longdouble = pytest.mark.skipif(np.finfo(np.longdouble).nmant <= 52, reason="long double is a double here")


@needs_longdouble
def test_longdouble_refused_with_type_error():
    tenth = LONG(1) / LONG(10)  # not a double: rounding it would change the polytope
    assert Fraction(*tenth.as_integer_ratio()) != Fraction(0.1)
    with pytest.raises(TypeError, match=r"vertices: numpy.longdouble is refused.*float128"):
        minksum.Polytope(np.array(scaled_cube(tenth), dtype=np.longdouble))
    with pytest.raises(TypeError, match=r"points: numpy.longdouble is refused"):
        minksum.Polytope.hull(np.array(CUBE, dtype=np.longdouble))
    with pytest.raises(TypeError, match=r"vertices\[5\]\[1\]: numpy.longdouble is refused"):
        minksum.Polytope(CUBE[:5] + [(0, tenth, 0)] + CUBE[6:])
    with pytest.raises(TypeError, match=r"vertices\[2\]: numpy.longdouble is refused"):
        minksum.Polytope(CUBE[:2] + [np.array([0, 1, 0], dtype=np.longdouble)] + CUBE[3:])
    cube = minksum.load("cube")
    with pytest.raises(TypeError, match=r"t\[0\]: numpy.longdouble is refused"):
        cube.translated((tenth, 0, 0))
    with pytest.raises(TypeError, match=r"t: numpy.longdouble is refused"):
        cube.translated(np.array([0, 0, 1], dtype=np.longdouble))
    o = minksum.Obstacle("cube", "tetra")
    for query in (o.collide, o.distance, o.depth):
        with pytest.raises(TypeError, match=r"t\[2\]: numpy.longdouble is refused"):
            query((0, 0, tenth))
    with pytest.raises(TypeError, match=r"d\[1\]: numpy.longdouble is refused"):
        o.directional_depth((0, 0, 0), (1, tenth, 0))
    with pytest.raises(TypeError, match=r"t: numpy.longdouble is refused"):
        o.distance(np.array(tenth))  # a 0-d array


def test_complex_refused():
    cube = minksum.load("cube")
    o = minksum.Obstacle("cube", "tetra")
    with pytest.raises(TypeError, match=r"vertices\[3\]\[2\]: complex numbers are refused.*got complex"):
        minksum.Polytope(CUBE[:3] + [(0, 0, 1 + 0j)] + CUBE[4:])
    with pytest.raises(TypeError, match=r"vertices: complex numbers are refused.*dtype complex128"):
        minksum.Polytope(np.array(CUBE, dtype=np.complex128))  # the imaginary parts are zero: still refused
    with pytest.raises(TypeError, match=r"points: complex numbers are refused.*dtype complex64"):
        minksum.Polytope.hull(np.array(CUBE, dtype=np.complex64) + 0.5j)
    with pytest.raises(TypeError, match=r"vertices\[0\]\[0\]: complex numbers are refused.*numpy.complex128"):
        minksum.Polytope([(np.complex128(0), 0, 0)] + CUBE[1:])
    with pytest.raises(TypeError, match=r"t\[0\]: complex numbers are refused"):
        cube.translated((1j, 0, 0))
    with pytest.raises(TypeError, match=r"t: complex numbers are refused"):
        cube.translated(np.zeros(3, dtype=complex))
    with pytest.raises(TypeError, match=r"t\[1\]: complex numbers are refused"):
        o.collide((0, 2 + 0j, 0))
    with pytest.raises(TypeError, match=r"d: complex numbers are refused"):
        o.directional_depth((0, 0, 0), np.array([1, 0, 0], dtype=complex))
