"""Obstacle queries on an (N, 3) batch of translations: exactly the N single queries, and the sign of t."""

from fractions import Fraction

import numpy as np
import pytest

import minksum
from conftest import cli_json

P, Q = "cube", "tetra@rot:3"
SEED = 38


def poses(n=300):
    rng = np.random.default_rng(SEED)
    return rng.uniform(-3, 3, size=(n, 3))


def single(query, t):
    return [query(row) for row in t]


@pytest.mark.parametrize("threads", [1, 2, None])
def test_batch_equals_single_queries(threads):
    t = poses()
    o, ref = minksum.Obstacle(P, Q), minksum.Obstacle(P, Q)
    codes = o.collide(t, threads=threads)
    assert codes.dtype == np.int8 and codes.shape == (len(t),)
    names = [minksum.STATUS[c] for c in codes]
    want = [r.status for r in single(ref.collide, t)]
    bad = [i for i in range(len(t)) if names[i] != want[i]]
    assert not bad, f"seed {SEED}: collide differs at {[(i, t[i].tolist(), names[i], want[i]) for i in bad[:5]]}"

    d = o.distance(t, threads=threads)
    dist = single(ref.distance, t)
    assert d.dtype == np.float64
    bad = [i for i in range(len(t)) if d[i] != dist[i].distance]
    assert not bad, f"seed {SEED}: distance differs at {[(i, t[i].tolist()) for i in bad[:5]]}"
    exact = o.distance(t, exact=True, threads=threads)
    assert [r.squared_distance for r in exact] == [r.squared_distance for r in dist]
    assert [r.status for r in exact] == [r.status for r in dist]

    depth = o.depth(t, threads=threads)
    ds = single(ref.depth, t)
    bad = [i for i in range(len(t)) if depth[i] != ds[i].depth]
    assert not bad, f"seed {SEED}: depth differs at {[(i, t[i].tolist()) for i in bad[:5]]}"
    assert [r.squared_depth for r in o.depth(t, exact=True, threads=threads)] == [r.squared_depth for r in ds]

    direction = (1, Fraction(1, 3), 0)
    dd = o.directional_depth(t, direction, threads=threads)
    dds = [ref.directional_depth(row, direction) for row in t]
    assert dd.tolist() == [r.depth for r in dds], f"seed {SEED}"
    assert [r.t for r in o.directional_depth(t, direction, exact=True, threads=threads)] == [r.t for r in dds]


def test_batch_of_exact_triples():
    o = minksum.Obstacle("box:2:2:2", "box:2:2:2")
    t = [(Fraction(5, 2), 0, 0), ("3", "1/2", 0), (2, 0, 0), (1, 0, 0)]
    assert minksum.STATUS == ("separate", "touching", "penetrating")
    assert o.collide(t).tolist() == [0, 0, 1, 2]
    assert [r.squared_distance for r in o.distance(t, exact=True)] == [Fraction(1, 4), 1, 0, 0]
    assert o.collide(np.zeros((0, 3))).shape == (0,)


def test_batch_errors():
    o = minksum.Obstacle("cube", "tetra")
    with pytest.raises(ValueError, match=r"t: expected an \(n, 3\) array, got an array of shape \(4, 2\)"):
        o.distance(np.zeros((4, 2)))
    with pytest.raises(ValueError, match=r"t\[1\]: not finite"):
        o.collide(np.array([[0, 0, 0], [np.inf, 0, 0]]))
    with pytest.raises(ValueError, match="threads must be at least 1"):
        o.collide(np.zeros((2, 3)), threads=0)


@pytest.mark.parametrize("u", [(3, 0, 0), (Fraction(1, 2), -1, Fraction(1, 3))])
def test_sign_of_t_against_the_cli(u):
    # t moves Q relative to P: the command's --translate-q w is t = w, its --translate-p u is t = -u.
    text = ",".join(str(Fraction(c)) for c in u)
    o = minksum.Obstacle(P, Q)
    neg = tuple(-Fraction(c) for c in u)
    by_p = cli_json("query", "distance", P, Q, "--translate-p", text)
    by_q = cli_json("query", "distance", P, Q, "--translate-q", text)
    assert o.distance(np.array([neg], dtype=object), exact=True)[0].squared_distance == Fraction(by_p["squared_distance"])
    assert o.distance([u], exact=True)[0].squared_distance == Fraction(by_q["squared_distance"])
    assert o.distance(neg).squared_distance == Fraction(by_p["squared_distance"])
