"""minksum.Obstacle: exact answers equal to the command `minksum query ... --json`, and closed forms."""

from fractions import Fraction

import numpy as np
import pytest

import minksum
from conftest import cli_json, interrupt_after_start

P, Q = "cube", "tetra@rot:3"
TRANSLATIONS = [(3, 0, 0), (Fraction(1, 2), Fraction(1, 3), Fraction(1, 5)), (0, 0, 0), (-2, Fraction(7, 3), 1)]


def text(t):
    return ",".join(str(Fraction(c)) for c in t)


def exact(v):
    return tuple(Fraction(c) for c in v)


def feature(f):
    return (f["type"], f["index"])


def same_witness(w, cli):
    assert (w.facet, w.m, w.p, w.q) == (cli["facet"], feature(cli["m"]), feature(cli["p"]), feature(cli["q"]))


@pytest.mark.parametrize("t", TRANSLATIONS)
def test_queries_agree_with_the_cli(t):
    # A fresh Obstacle for each query, as each command starts afresh: a query
    # starts from the previous one's witness, and the witness of an answer
    # may depend on where its walk started.
    def obstacle():
        return minksum.Obstacle(P, Q)

    c = cli_json("query", "collide", P, Q, "--translate-q", text(t))
    r = obstacle().collide(t)
    assert r.status == c["status"]
    same_witness(r.witness, c["witness"])

    c = cli_json("query", "distance", P, Q, "--translate-q", text(t))
    r = obstacle().distance(t)
    assert (r.status, r.squared_distance) == (c["status"], Fraction(c["squared_distance"]))
    assert r.direction == exact(c["direction"])
    assert isinstance(r.squared_distance, Fraction)
    same_witness(r.witness, c["witness"])

    c = cli_json("query", "depth", P, Q, "--translate-q", text(t))
    r = obstacle().depth(t)
    assert (r.status, r.squared_depth, r.direction) == (c["status"], Fraction(c["squared_depth"]), exact(c["direction"]))
    same_witness(r.witness, c["witness"])

    d = (1, Fraction(1, 2), 0)
    c = cli_json("query", "ddepth", P, Q, "--translate-q", text(t), "--direction", text(d))
    r = obstacle().directional_depth(t, d)
    assert (r.status, r.t, r.translation) == (c["status"], Fraction(c["t"]), exact(c["direction"]))
    same_witness(r.witness, c["witness"])


def test_coherent_queries_give_the_same_exact_answers():
    o, fresh = minksum.Obstacle(P, Q), lambda: minksum.Obstacle(P, Q)
    for t in TRANSLATIONS * 2:
        assert o.collide(t).status == fresh().collide(t).status
        assert o.distance(t).squared_distance == fresh().distance(t).squared_distance
        assert o.depth(t).squared_depth == fresh().depth(t).squared_depth


def test_closed_forms_for_two_boxes():
    # P = Q = [-1, 1]^3, so M = P ⊕ (−Q) = [-2, 2]^3 and every answer is a distance to its faces.
    o = minksum.Obstacle("box:2:2:2", "box:2:2:2")
    assert o.collide((5, 0, 0)).status == "separate"
    assert o.collide((2, 1, 0)).status == "touching"
    assert o.collide(np.array([1.5, 0, 0])).status == "penetrating"
    r = o.distance((5, Fraction(1, 3), 0))
    assert r.squared_distance == 9 and r.distance == 3.0
    assert tuple(q - p for p, q in zip(r.point_p, r.point_q)) == r.direction
    d = o.depth((Fraction(3, 2), 0, 0))
    assert d.status == "penetrating" and d.squared_depth == Fraction(1, 4)
    assert d.direction == (Fraction(-1, 2), 0, 0)
    dd = o.directional_depth((1, 0, 0), (-1, 0, 0))  # P moves left until it only touches Q
    assert dd.t == 1 and dd.translation == (-1, 0, 0)
    assert o.obstacle.volume() == 64


def test_obstacle_is_p_plus_minus_q():
    o = minksum.Obstacle("cube", "tetra")
    m = minksum.minkowski_sum("cube", minksum.load("tetra").negated())
    assert sorted(o.obstacle.planes()) == sorted(m.planes())
    assert o.p.num_vertices == 8 and o.q.num_vertices == 4


OBSTACLE_CTRL_C_SCRIPT = r"""
import sys, time
import minksum

p, q = minksum.load("sphere:8"), minksum.load("sphere:8@rot:1")
start = time.monotonic()
try:
    print("started", flush=True)
    minksum.Obstacle(p, q)
except KeyboardInterrupt:
    print("KeyboardInterrupt after %.1f s" % (time.monotonic() - start), flush=True)
    sys.exit(3)
print("finished after %.1f s" % (time.monotonic() - start), flush=True)
"""


def test_ctrl_c_stops_obstacle_construction():
    # SIGINT one second into building the obstacle of two sphere:8 (M has about a million facets; its
    # planes take tens of seconds here): KeyboardInterrupt within 5 s of the signal, where Ctrl-C used to
    # wait for the whole construction.  The sum and M's planes poll SumOptions::cancel.
    interrupt_after_start(OBSTACLE_CTRL_C_SCRIPT, what="Obstacle()", limit=5)
