#!/usr/bin/python3
"""The Python package side by side: its overhead over the C++ call, batches on 1 and 2 threads,
and scipy.spatial.ConvexHull on the pairwise vertex sums (what a numpy user writes today).

Run with Debian's interpreter and the package on PYTHONPATH, from a build with assertions off:

    make bench-python

(that is: PYTHONPATH=build-bench/python /usr/bin/python3 bench/python_bench.py --page docs/python.md).
Prints a Markdown report; with --page, also puts it in that page between the lines
<!-- bench-python --> and <!-- /bench-python -->.
"""

import argparse
import contextlib
import io
import math
import os
import platform
import sys
import tempfile
import time
from fractions import Fraction

import numpy as np
import scipy
import scipy.spatial

import minksum


def best(f, repeat):
    """The least wall time of `repeat` runs of f(), and its last result."""
    times, result = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        result = f()
        times.append(time.perf_counter() - t)
    return min(times), result


def fmt_us(seconds):
    return f"{seconds * 1e6:.2f} µs"


def fmt_s(seconds):
    return f"{seconds * 1e3:.1f} ms" if seconds < 1 else f"{seconds:.2f} s"


def overhead(calls):
    a, b = minksum.load("cube"), minksum.load("tetra")
    for _ in range(1000):
        minksum.minkowski_sum(a, b)
    rows = []
    for _ in range(3):
        t = time.perf_counter()
        inside = 0.0
        for _ in range(calls):
            inside += minksum.minkowski_sum(a, b).seconds
        wall = (time.perf_counter() - t) / calls
        rows.append((wall - inside / calls, wall, inside / calls))
    over, wall, inside = min(rows)
    pairs = [(a, b)] * 100  # batches of 100, so that the results do not pile up in memory

    def batches():
        for _ in range(calls // 100):
            minksum.minkowski_sum_many(pairs, threads=1)

    many, _ = best(batches, 3)
    return over, wall, inside, many / (calls // 100 * 100)


def big_vertices():
    t = time.perf_counter()
    p = minksum.load("random:100000:1")
    build = time.perf_counter() - t
    view, v = best(lambda: p.vertices, 1000)
    copy, _ = best(lambda: np.array(p.vertices), 20)
    return p.num_vertices, build, view, copy, np.shares_memory(v, p.vertices) and v.base is p


def batch(n, repeat):
    pairs = [(minksum.load(f"random:200:{i}"), minksum.load(f"random:200:{n + i}")) for i in range(n)]
    t1 = t2 = c1 = c2 = math.inf
    for _ in range(repeat):  # interleaved, so that both see the same load on a shared machine
        c = time.process_time()
        t, one = best(lambda: minksum.minkowski_sum_many(pairs, threads=1), 1)
        t1, c1 = min(t1, t), min(c1, time.process_time() - c)
        c = time.process_time()
        t, two = best(lambda: minksum.minkowski_sum_many(pairs, threads=2), 1)
        t2, c2 = min(t2, t), min(c2, time.process_time() - c)
    same = all(x.exact_vertices() == y.exact_vertices() for x, y in zip(one, two))
    return t1, t2, c1, c2, same


def primitive_plane(p, q, r, outward):
    """The plane through three exact points, as primitive integers (a, b, c, d) oriented along `outward`."""
    u = [q[k] - p[k] for k in range(3)]
    v = [r[k] - p[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    if all(c == 0 for c in n):
        return None  # a degenerate (flat) triangle
    d = sum(n[k] * p[k] for k in range(3))
    den = math.lcm(*(Fraction(c).denominator for c in (*n, d)))
    ints = [int(Fraction(c) * den) for c in (*n, d)]
    g = math.gcd(*ints)
    ints = [c // g for c in ints]
    if sum(ints[k] * outward[k] for k in range(3)) < 0:
        ints = [-c for c in ints]
    return tuple(ints)


def against_scipy(a_spec, b_spec, repeat):
    a, b = minksum.load(a_spec), minksum.load(b_spec)
    t_minksum, s = best(lambda: minksum.minkowski_sum(a, b), repeat)
    A, B = a.vertices, b.vertices

    def scipy_sum():
        points = (A[:, None, :] + B[None, :, :]).reshape(-1, 3)
        return scipy.spatial.ConvexHull(points)

    t_scipy, hull = best(scipy_sum, repeat)
    # Combinatorics, exactly: scipy's vertices and triangles mapped back to pairs (i, j) of input
    # vertices, whose exact sums are compared with minksum's exact answer.
    nb = len(B)
    true_pairs = {tuple(map(int, o)) for o in s.vertex_origin}
    hull_pairs = {divmod(int(k), nb) for k in hull.vertices}
    ea, eb = a.exact_vertices(), b.exact_vertices()

    def exact(k):
        i, j = divmod(int(k), nb)
        return tuple(x + y for x, y in zip(ea[i], eb[j]))

    planes = set(s.planes())
    merged, degenerate, off = set(), 0, 0
    for tri, eq in zip(hull.simplices, hull.equations):
        plane = primitive_plane(*(exact(k) for k in tri), outward=eq[:3])
        if plane is None:
            degenerate += 1
        elif plane not in planes:
            off += 1
        else:
            merged.add(plane)
    return {
        "pair": f"{a_spec} ⊕ {b_spec}",
        "points": len(A) * len(B),
        "minksum": t_minksum,
        "scipy": t_scipy,
        "V": s.num_vertices,
        "F": s.num_facets,
        "scipy_V": len(hull.vertices),
        "missing": len(true_pairs - hull_pairs),
        "spurious": len(hull_pairs - true_pairs),
        "triangles": len(hull.simplices),
        "merged": len(merged),
        "degenerate": degenerate,
        "off": off,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--calls", type=int, default=20000, help="small sums timed for the overhead (default 20000)")
    ap.add_argument("--pairs", type=int, default=1000, help="pairs of random:200 in the batch (default 1000)")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each measurement; the least time is kept")
    ap.add_argument("--command", default="make bench-python", help="the command named in the report")
    ap.add_argument("--page", help="a Markdown page whose bench-python section gets the report")
    args = ap.parse_args()
    text = io.StringIO()
    with contextlib.redirect_stdout(text):
        report(args)
    sys.stdout.write(text.getvalue())
    if args.page:
        write_section(args.page, text.getvalue())


def write_section(page, body):
    """Replace the text between the bench-python markers of `page` (atomically: temporary file + rename)."""
    begin, end = "<!-- bench-python -->\n", "<!-- /bench-python -->\n"
    with open(page, encoding="utf-8") as f:
        old = f.read()
    i, j = old.find(begin), old.find(end)
    if i < 0 or j < i:
        sys.exit(f"python_bench.py: {page}: no section between {begin.strip()} and {end.strip()}")
    new = old[:i + len(begin)] + "\n" + body + "\n" + old[j:]
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(page)), suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write(new)
    os.chmod(tmp, 0o644)
    os.replace(tmp, page)


def report(args):

    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    print(f"Produced by `{args.command}` on {time.strftime('%Y-%m-%d')}: {cpu}, {os.cpu_count()} hardware threads, "
          f"load average {os.getloadavg()[0]:.2f} at the start (a machine shared with other work); "
          f"Python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}. "
          f"Least wall time of {args.repeat} runs.\n")

    over, wall, inside, many = overhead(args.calls)
    print("### Python overhead per sum\n")
    print("| cube ⊕ tetra | per sum |\n|---|---|")
    print(f"| `minksum.minkowski_sum(a, b)`, wall time in Python | {fmt_us(wall)} |")
    print(f"| the C++ call inside it (`Sum.seconds`) | {fmt_us(inside)} |")
    print(f"| **overhead of the binding** | **{fmt_us(over)}** |")
    print(f"| `minkowski_sum_many` on 1 thread, per pair (batches of 100 pairs) | {fmt_us(many)} |\n")

    n, build, view, copy, shared = big_vertices()
    print(f"`Polytope.vertices` of random:100000:1 ({n} vertices): {fmt_us(view)} per access "
          f"(a read-only view of the polytope's own coordinates, shares memory: {shared}); "
          f"copying it with `np.array` takes {fmt_us(copy)}.\n")

    t1, t2, c1, c2, same = batch(args.pairs, args.repeat)
    print(f"### `minkowski_sum_many`: {args.pairs} pairs of random:200 polytopes\n")
    print("| threads | wall time | per pair | speed-up | CPU time of the process |\n|---|---|---|---|---|")
    print(f"| 1 | {fmt_s(t1)} | {fmt_us(t1 / args.pairs)} | 1 | {fmt_s(c1)} |")
    print(f"| 2 | {fmt_s(t2)} | {fmt_us(t2 / args.pairs)} | {t1 / t2:.2f}× | {fmt_s(c2)} |\n")
    print(f"Identical exact results on 1 and 2 threads: {same}.\n")

    print("### Against scipy.spatial.ConvexHull of the pairwise sums\n")
    print("scipy: `ConvexHull((A[:, None] + B[None]).reshape(-1, 3))` on the float64 vertex arrays, "
          "timed with the numpy sums; minksum: `minkowski_sum(a, b)` (walk), exact. The combinatorics "
          "are checked exactly: each scipy vertex is traced back to its pair of input vertices and "
          "compared with minksum's `vertex_origin`; each scipy triangle's exact plane (through the "
          "exact sums of its corners) is compared with minksum's facet planes, and the triangles on "
          "one plane are merged.\n")
    print("| pair | pairwise points | minksum | scipy | scipy / minksum | V exact | V scipy (missing, spurious) "
          "| F exact | scipy triangles → merged facets (flat, off any facet) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for a, b in [("cube", "sphere:6"), ("sphere:4", "sphere:4@rot:5")]:
        r = against_scipy(a, b, args.repeat)
        print(f"| {r['pair']} | {r['points']} | {fmt_s(r['minksum'])} | {fmt_s(r['scipy'])} | "
              f"{r['scipy'] / r['minksum']:.1f}× | {r['V']} | {r['scipy_V']} ({r['missing']}, {r['spurious']}) | "
              f"{r['F']} | {r['triangles']} → {r['merged']} ({r['degenerate']}, {r['off']}) |")


if __name__ == "__main__":
    main()
