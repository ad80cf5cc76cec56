#!/usr/bin/python3
"""Non-convex sums, three programs in one run: minksum, CGAL, Manifold.

    /usr/bin/python3 bench/nonconvex/run.py [--build build-bench] [--reps 3] [--timeout 120]
        [--work DIR] [--page docs/generated/benchmarks-nonconvex.md] [--command "make bench-nonconvex"]
        [A:B ...]

For each row A:B (catalog specs; default: the rows of docs/nonconvex.md):

1. minksum: `bench_nonconvex --json --side minksum --reps R A:B`, i.e.
   minkowski_sum_nonconvex on the exact operands, R times, the median (and
   its phases: decomposition, pair sums, union, boundary);
2. CGAL: `bench_nonconvex --json --side cgal A:B`, minkowski_sum_3 on the
   same exact operands as Nef polyhedra, once, in a process of its own that
   is killed after --timeout seconds ("> 120 s" in the table); its exact
   volume is compared with minksum's;
3. Manifold: the operands written by `minksum gen SPEC -o X.stl --binary`
   (exact triangulation, each coordinate the nearest float, which is what
   Manifold's JavaScript API takes), then `node bench/nonconvex/manifold.mjs
   A.stl B.stl --reps R`: Manifold.minkowskiSum (npm manifold-3d, the version
   pinned in bench/nonconvex/package-lock.json), the median of R runs;
4. untimed, `minksum sum A.stl B.stl --json`: the exact sum of the float
   operands Manifold was given, to tell its own error from its input's.

The table (Markdown) goes to standard output and, with --page, to that file
with the command, the machine and its load in the header.  Needs the
targets bench_nonconvex and minksum_cli built in --build and the npm
packages of bench/nonconvex installed (`make bench-nonconvex` does all).
"""

import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys
import time
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))

# tube ⊕ ball series (26, 114, 266, 1106 vertices), an L-bracket ⊕ a ball, a
# gear ⊕ a cylinder.
DEFAULT_ROWS = [
    "tube:ball:4@scale:1/4",
    "tube:ball:8@scale:1/4",
    "tube:ball:12@scale:1/4",
    "tube:ball:24@scale:1/4",
    "lshape:ball:8@scale:1/4",
    "gear:8:prism:16@scale:1/8",
]


def fail(message, status=1):
    sys.stderr.write("run.py: %s\n" % message)
    raise SystemExit(status)


def run(argv, timeout=None):
    """(stdout, stderr, seconds) of argv; None for stdout when it timed out."""
    t0 = time.perf_counter()
    try:
        p = subprocess.run(argv, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "", time.perf_counter() - t0
    if p.returncode != 0:
        fail("%s exited with %d: %s" % (" ".join(argv), p.returncode, p.stderr.strip()),
             p.returncode if p.returncode in (2, 3) else 1)
    return p.stdout, p.stderr, time.perf_counter() - t0


def one_json(text, argv):
    lines = [l for l in text.splitlines() if l.strip()]
    if len(lines) != 1:
        fail("%s printed %d lines, expected one JSON object" % (" ".join(argv), len(lines)))
    return json.loads(lines[0])


def write_stl(minksum, spec, path):
    """minksum gen SPEC -o path --binary; the largest displacement of a vertex when rounded to floats (0 if none)."""
    _, err, _ = run([minksum, "gen", spec, "-o", path, "--binary"])
    m = re.search(r"largest vertex displacement ([0-9.eE+-]+)", err)
    return float(m.group(1)) if m else 0.0


def bench_row(args, row, index):
    bench = os.path.join(args.build, "bin", "bench_nonconvex")
    minksum = os.path.join(args.build, "bin", "minksum")
    argv = [bench, "--json", "--side", "minksum", "--reps", str(args.reps), row]
    mine = one_json(run(argv)[0], argv)
    ours = dict(mine["minksum"], threads=mine["threads"])
    a, b = mine["a"], mine["b"]  # the row split as bench_nonconvex splits it
    argv = [bench, "--json", "--side", "cgal", row]
    out, _, wall = run(argv, timeout=args.timeout)
    cgal = one_json(out, argv)["cgal"] if out is not None else None
    stl_a = os.path.join(args.work, "row%d-a.stl" % index)
    stl_b = os.path.join(args.work, "row%d-b.stl" % index)
    moved = max(write_stl(minksum, a, stl_a), write_stl(minksum, b, stl_b))
    argv = ["node", os.path.join(HERE, "manifold.mjs"), stl_a, stl_b, "--reps", str(args.reps)]
    theirs = one_json(run(argv)[0], argv)
    # The exact sum of the float operands Manifold was given (untimed).
    argv = [minksum, "sum", stl_a, stl_b, "--json"]
    floats = one_json(run(argv)[0], argv)
    exact = Fraction(ours["volume"])
    return {
        "row": row, "a": a, "b": b, "vertices_b": mine["vertices_b"],
        "minksum": ours, "cgal": cgal, "cgal_wall": wall, "manifold": theirs, "exact": exact, "moved": moved,
        "floats": {"volume": Fraction(floats["volume"]), "vertices": floats["vertices"]},
    }


def fmt_s(x):
    return "%.3f" % x if x < 10 else "%.1f" % x


def relative(value, exact):
    """(value − exact) / exact for a double value and an exact Fraction, "0" when equal."""
    d = (Fraction(value) - exact) / exact
    return "0" if d == 0 else "%+.1e" % float(d)


def table(results, timeout):
    head = ("| A ⊕ B | V(B) | minksum s (decompose / pairs / union / boundary) | CGAL minkowski_sum_3 s | CGAL / minksum "
            "| Manifold minkowskiSum s | Manifold / minksum | exact volume | Manifold volume | relative difference "
            "| relative difference, float operands | vertices: exact / float operands / Manifold "
            "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    rows = []
    for r in results:
        o, c, m = r["minksum"], r["cgal"], r["manifold"]
        if c is None:
            cgal, ratio = "> %d" % timeout, "> %.1f×" % (timeout / o["seconds"])
        else:
            same = Fraction(c["volume"]) == r["exact"]
            cgal = fmt_s(c["seconds"]) + ("" if same else " (volume DIFFERS)")
            ratio = "%.1f×" % (c["seconds"] / o["seconds"])
        rows.append("| %s ⊕ %s | %d | %s (%s / %s / %s / %s) | %s | %s | %s | %.2f× | %.9g | %.9g | %s | %s | %d / %d / %d |" % (
            r["a"], r["b"], r["vertices_b"], fmt_s(o["seconds"]), fmt_s(o["decompose"]), fmt_s(o["pairs_s"]),
            fmt_s(o["union"]), fmt_s(o["boundary"]), cgal, ratio, fmt_s(m["seconds"]), m["seconds"] / o["seconds"],
            float(r["exact"]), m["volume"], relative(m["volume"], r["exact"]), relative(m["volume"], r["floats"]["volume"]),
            o["vertices"], r["floats"]["vertices"], m["vertices"]))
    return head + "\n".join(rows) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("rows", nargs="*", default=DEFAULT_ROWS, help="A:B catalog specs")
    ap.add_argument("--build", default="build-bench", help="build directory with bin/bench_nonconvex and bin/minksum")
    ap.add_argument("--reps", type=int, default=3, help="runs of minksum and of Manifold per row (median)")
    ap.add_argument("--timeout", type=int, default=120, help="seconds after which CGAL's run is stopped")
    ap.add_argument("--work", help="directory for the operands' STL files (default BUILD/nonconvex)")
    ap.add_argument("--page", help="write the page here (e.g. docs/generated/benchmarks-nonconvex.md)")
    ap.add_argument("--command", default="/usr/bin/python3 bench/nonconvex/run.py",
                    help="the command named in the page's header")
    args = ap.parse_args()
    if args.reps < 1 or args.timeout < 1:
        fail("--reps and --timeout need positive integers", 2)
    args.work = args.work or os.path.join(args.build, "nonconvex")
    os.makedirs(args.work, exist_ok=True)
    load_start = " ".join(open("/proc/loadavg").read().split()[:3])
    started = time.perf_counter()
    results = []
    for i, row in enumerate(args.rows):
        sys.stderr.write("run.py: %s\n" % row)
        results.append(bench_row(args, row, i))
    wall = time.perf_counter() - started
    load_end = " ".join(open("/proc/loadavg").read().split()[:3])
    md = table(results, args.timeout)
    sys.stdout.write(md)
    sys.stdout.flush()
    if args.page:
        write_page(args, results, md, load_start, load_end, wall)


def write_page(args, results, md, load_start, load_end, wall):
    manifold = results[0]["manifold"]["manifold"] if results else "?"
    node = subprocess.run(["node", "--version"], capture_output=True, text=True).stdout.strip()
    threads = results[0]["minksum"].get("threads", os.cpu_count()) if results else os.cpu_count()
    moved = max((r["moved"] for r in results), default=0.0)
    text = """# Non-convex sums: minksum, CGAL's minkowski_sum_3 and Manifold's minkowskiSum

<!-- Generated by `{command}` (bench/nonconvex/run.py, bench/nonconvex/main.cpp, bench/nonconvex/manifold.mjs). Do not edit by hand: every figure below comes from that command. -->

Generated by `{command}` on {date}, {wall:.0f} s in all, on {machine} with {cpus} hardware threads,
load average {load_start} at the start and {load_end} at the end (other builds ran beside it:
absolute times are inflated, the three columns alike).
Method and reading of the columns: [docs/nonconvex.md](../nonconvex.md), "Speed".

* minksum: `minkowski_sum_nonconvex` on the exact operands, the median of {reps} runs in one process
  (`bench_nonconvex --side minksum --reps {reps}`), pairs summed on every hardware thread; the phases are those of
  the median run.
* CGAL: `minkowski_sum_3` on the same exact operands as Nef polyhedra, once, in a process of its own stopped
  after {timeout} s; every row it finished has exactly minksum's volume unless the cell says otherwise.
* Manifold: `Manifold.minkowskiSum` of manifold-3d {manifold} (WebAssembly, one thread) under Node {node},
  the median of {reps} runs on operands built afresh each time (`bench/nonconvex/manifold.mjs`). Its operands
  are the exact ones rounded to the nearest floats (its JavaScript API takes `Float32Array` vertices): no vertex
  moved by more than {moved:.2g}.
* exact volume: minksum's exact rational volume rounded to a double; relative difference:
  (Manifold − exact) / exact. The next column compares Manifold's volume with the exact volume of the sum of
  the float operands it was given (`minksum sum A.stl B.stl`, untimed), which separates Manifold's own error
  from the rounding of its input; the vertex counts are those of the exact boundary (merged coplanar
  facets), the same for the float operands, and Manifold's triangle mesh.

{md}""".format(command=args.command, date=datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
               wall=wall, machine=platform.machine(), cpus=threads, load_start=load_start, load_end=load_end,
               reps=args.reps, timeout=args.timeout, manifold=manifold, node=node, moved=moved, md=md)
    tmp = args.page + ".tmp"
    try:
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, args.page)
    except OSError as e:
        fail("cannot write %s: %s" % (args.page, e))


if __name__ == "__main__":
    main()
