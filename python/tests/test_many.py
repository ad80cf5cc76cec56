"""minksum.minkowski_sum_many: results in input order, identical for any number of threads, errors per pair."""

import threading
from fractions import Fraction

import pytest

import minksum
from conftest import interrupt_after_start

SPECS = ["cube", "tetra", "sphere:2", "random:60:1", "dodecahedron", "box:1:2:3", "sphere:2@rot:4", "octahedron"]


def pairs():
    return [(a, b) for a in SPECS for b in SPECS[::-1]]


def summary(s):
    return (s.method, s.exact_vertices(), s.planes(), s.vertex_origin.tolist(), s.volume())


def test_identical_for_one_two_and_four_threads():
    ps = [(minksum.load(a), minksum.load(b)) for a, b in pairs()]
    one = [summary(s) for s in minksum.minkowski_sum_many(ps, threads=1)]
    two = [summary(s) for s in minksum.minkowski_sum_many(ps, threads=2)]
    four = [summary(s) for s in minksum.minkowski_sum_many(ps, threads=4)]
    assert one == two == four
    single = [summary(minksum.minkowski_sum(a, b)) for a, b in ps]
    assert one == single


def test_names_are_loaded_on_the_workers_and_method_per_pair():
    out = minksum.minkowski_sum_many([("cube", "tetra", "chms"), ("cube", "tetra"), ("cube", "tetra", "cgm")],
                                     threads=2, method="cvms")
    assert [s.method for s in out] == ["chms", "cvms", "cgm"]
    assert len({s.volume() for s in out}) == 1


def solid_summary(s):
    return (type(s), s.method, s.num_vertices, s.num_edges, s.num_facets, s.volume(), s.stats["genus"], s.shells)


# Solids in a batch as in minkowski_sum: a Solid object, or a name that is not
# a convex polytope, makes the pair's result a SolidSum, whose exact volume
# has a closed form here:
#   tube + [-1/4, 1/4]^3: [-5/4, 5/4]^3 less a hole of side 1/2: 125/8 - 5/8 = 15, genus 1;
#   lshape + [-1/4, 1/4]^3: the L (area 3) grown by 1/4: two 5/2 x 3/2 rectangles
#   overlapping in 3/2 x 3/2, area 21/4, times the height 3/2: 63/8;
#   cube + tube@scale:1/2 (a hole of side 1/2, filled): [-3/2, 3/2]^3, 27.
def test_solids_and_names_of_solids_in_a_batch():
    tube = minksum.Solid.load("tube")
    ps = [(tube, "cube@scale:1/4"), ("cube", "tetra"), ("lshape", "cube@scale:1/4"),
          ("cube", "tube@scale:1/2"), ("cube@scale:1/4", tube, "chms")]
    for threads in (1, 2):
        out = minksum.minkowski_sum_many(ps, threads=threads)
        assert [type(s) for s in out] == [minksum.SolidSum, minksum.Sum, minksum.SolidSum, minksum.SolidSum,
                                         minksum.SolidSum]
        assert [s.volume() for s in out] == [15, Fraction(176, 3), Fraction(63, 8), 27, 15]
        assert out[0].stats["genus"] == 1 and out[2].stats["genus"] == 0 and out[3].stats["genus"] == 0
        # Each one what minkowski_sum gives.
        assert [solid_summary(s) for s in (out[0], out[2], out[3], out[4])] == [
            solid_summary(minksum.minkowski_sum(*p)) for p in (ps[0], ps[2], ps[3], ps[4])]
        assert out[1].planes() == minksum.minkowski_sum("cube", "tetra").planes()


def test_failing_solid_pair_returned_in_place(data):
    open_mesh = str(data / "bad" / "open_mesh.off")
    out = minksum.minkowski_sum_many([("tube", "cube"), ("tube", open_mesh)], on_error="return")
    assert isinstance(out[0], minksum.SolidSum) and out[0].volume() == 64  # [-2, 2]^3: the hole filled
    assert isinstance(out[1], minksum.InputError) and out[1].file == open_mesh
    assert any("pairs[1]" in n for n in out[1].__notes__)


def test_empty_batch():
    assert minksum.minkowski_sum_many([]) == []


def test_failing_pair_raises_with_its_index(data):
    bad = str(data / "bad" / "nan.off")
    with pytest.raises(minksum.InputError) as e:
        minksum.minkowski_sum_many([("cube", "tetra"), ("cube", bad), ("nosuch", "cube")], threads=2)
    assert e.value.file == bad
    assert any("pairs[1]" in n for n in e.value.__notes__)


def test_failing_pairs_returned_in_place(data):
    bad = str(data / "bad" / "nan.off")
    out = minksum.minkowski_sum_many([("cube", "tetra"), ("cube", bad), ("nosuch", "cube")], on_error="return")
    assert isinstance(out[0], minksum.Sum) and out[0].volume() == minksum.minkowski_sum("cube", "tetra").volume()
    assert isinstance(out[1], minksum.InputError) and out[1].place == "line 4"
    assert isinstance(out[2], ValueError) and "nosuch" in str(out[2])


@pytest.mark.parametrize(
    "args,match",
    [
        (([("cube",)],), r"pairs\[0\]: expected \(a, b\)"),
        ((["cube"],), r"pairs\[0\]: expected \(a, b\)"),
        (([("cube", "tetra")], 0), "threads must be at least 1"),
        (([("cube", "tetra")], -3), "threads must be at least 1"),
        (([("cube", "tetra", "nope")],), "unknown method 'nope'"),
    ],
)
def test_bad_arguments(args, match):
    with pytest.raises(ValueError, match=match):
        minksum.minkowski_sum_many(*args)


def test_bad_on_error():
    with pytest.raises(ValueError, match="on_error"):
        minksum.minkowski_sum_many([], on_error="ignore")


def test_gil_is_released_python_threads_run_sums_concurrently():
    # Python threads each calling minkowski_sum get the same exact answers as serial calls.
    ps = pairs()[:16]
    expected = [summary(minksum.minkowski_sum(a, b)) for a, b in ps]
    got = [None] * len(ps)

    def work(k):
        for i in range(k, len(ps), 4):
            got[i] = summary(minksum.minkowski_sum(*ps[i]))

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert got == expected


def test_ctrl_c_interrupts_a_long_sum():
    # SIGINT while a long sum runs with the GIL released: KeyboardInterrupt at the method's next report point.
    # The signal is repeated every 10 ms from 50 ms on until the call returns, so that one of them arrives
    # while the sum runs however fast the machine is (a single one could come after the last report point).
    import os
    import signal

    a, b = minksum.load("sphere:7"), minksum.load("sphere:7@rot:1")  # a sum of about 170 000 vertices
    done = threading.Event()

    def interrupt():
        if done.wait(0.05):
            return
        while not done.is_set():
            os.kill(os.getpid(), signal.SIGINT)
            done.wait(0.01)

    handled = []

    def first_only(signum, frame):  # Python's own behaviour once; the later repeats are ignored
        handled.append(signum)
        if len(handled) == 1:
            raise KeyboardInterrupt

    previous = signal.signal(signal.SIGINT, first_only)
    sender = threading.Thread(target=interrupt)
    sender.start()
    try:
        with pytest.raises(KeyboardInterrupt, match="minksum: the sum was interrupted"):  # raised inside the sum
            minksum.minkowski_sum(a, b)
    finally:
        done.set()
        sender.join()
        signal.signal(signal.SIGINT, previous)


CTRL_C_SCRIPT = r"""
import sys, time
import minksum

pairs = [("sphere:6", f"sphere:6@rot:{i}") for i in range(int(sys.argv[1]))]
start = time.monotonic()
try:
    print("started", flush=True)
    minksum.minkowski_sum_many(pairs, threads=2)
except KeyboardInterrupt:
    print("KeyboardInterrupt after %.1f s" % (time.monotonic() - start), flush=True)
    sys.exit(3)
print("finished after %.1f s" % (time.monotonic() - start), flush=True)
"""


def test_ctrl_c_stops_minkowski_sum_many():
    # SIGINT one second into a batch of sphere:6 ⊕ sphere:6@rot pairs that would take at least two minutes
    # (sized from one pair timed here, on two threads): the process must end with KeyboardInterrupt within
    # 10 s of the signal.  The jobs run on C++ threads; the calling thread polls for signals while it waits.
    import math
    import time

    start = time.monotonic()
    minksum.minkowski_sum("sphere:6", "sphere:6@rot:1")
    one = time.monotonic() - start
    n = max(8, math.ceil(2 * 120 / one))
    interrupt_after_start(CTRL_C_SCRIPT, str(n), what=f"minkowski_sum_many of {n} pairs", limit=10)
