#!/usr/bin/python3
"""Non-convex sums, erosions and openings, three programs in one run: minksum, Manifold, CGAL.

    /usr/bin/python3 bench/nonconvex/run.py [--build build-bench] [--reps 3] [--timeout 120]
        [--meshes DIR] [--work DIR] [--resume] [--minksum-timeout S] [--manifold-timeout S]
        [--operations sum,erode,open] [--catalog-operations sum,...]
        [--page docs/generated/benchmarks-nonconvex.md]
        [--command "make bench-nonconvex"] [A:B ...]

Rows: A:B catalog specs (default: a triangulated torus family ⊕ a level-2
geodesic ball, a torus ⊕ a torus, and the catalog rows of docs/nonconvex.md),
then, with --meshes DIR, every mesh file of DIR ⊕ a level-2 geodesic ball
(`sphere:2`, radius 1) scaled to 2 % of the mesh's bounding-box diagonal.

Each row is run for each of --operations (default all three; the catalog
rows, A:B specs, for each of --catalog-operations when it is given): sum A ⊕ B,
erode A ⊖ B and open (A ⊖ B) ⊕ B (`minksum erode|open`, Manifold's
minkowskiDifference, then minkowskiSum for the opening; CGAL's
reference_erosion for erode and nothing for open).  For each row:

1. minksum, as a user runs it: the whole process
   `minksum sum A B -o OUT.stl --binary --json` (A a catalog spec or the
   file as given), wall clock and CPU time (user + system, from wait4) and
   peak memory; the median wall time of --reps runs (one run when the first
   takes more than 2 s);
2. the written OUT.stl checked independently: `bench_nonconvex --check`,
   CGAL's Polygon_mesh_processing on exact points (closed, no
   self-intersection, outward), and its exact volume against the exact sum's;
3. Manifold: `node bench/nonconvex/manifold.mjs A.stl B.stl`,
   Manifold.minkowskiSum (npm manifold-3d, pinned in
   bench/nonconvex/package-lock.json) on the operands as binary STL (its
   JavaScript API takes floats: catalog solids written by `minksum gen
   --binary`, files converted here with each coordinate the nearest float),
   the median of the same number of runs; only the call is timed;
4. CGAL: `bench_nonconvex --json --side cgal 'A|B'`, minkowski_sum_3 on the
   exact operands as Nef polyhedra, once, in a process of its own stopped
   after --timeout seconds; its exact volume is compared with minksum's.

A mesh that minksum refuses (not a closed solid: exit status 3) is listed
with minksum's message, and not given to the others.  The table (Markdown)
goes to standard output and, with --page, to that file with the command,
the machine, its load and a summary of the targets of docs/nonconvex.md.
Needs the targets bench_nonconvex and minksum_cli built in --build and the
npm packages of bench/nonconvex installed (`make bench-nonconvex` does all).
"""

import argparse
import datetime
import json
import os
import platform
import re
import struct
import subprocess
import sys
import threading
import time
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))
BALL = "sphere:2@scale:1/10"

# The torus family (256 ... 65 536 triangles) ⊕ a ball of 80 facets, a torus
# ⊕ a torus (1 024 ⊕ 256 triangles), and the catalog rows: tube ⊕ balls of 114
# and 1 106 vertices, an L-bracket ⊕ a ball, a gear ⊕ a cylinder.
DEFAULT_ROWS = [
    "torus:16:8:" + BALL,
    "torus:32:16:" + BALL,
    "torus:64:32:" + BALL,
    "torus:128:64:" + BALL,
    "torus:256:128:" + BALL,
    "torus:32:16:torus:16:8@scale:1/4",
    "tube:ball:8@scale:1/4",
    "tube:ball:24@scale:1/4",
    "lshape:ball:8@scale:1/4",
    "gear:8:prism:16@scale:1/8",
]
MESH_EXTENSIONS = (".off", ".obj", ".stl", ".ply")


def fail(message, status=1):
    sys.stderr.write("run.py: %s\n" % message)
    raise SystemExit(status)


def run(argv, timeout=None, allow=(0,)):
    """(status, stdout, stderr, seconds) of argv; status None when it timed out."""
    t0 = time.perf_counter()
    try:
        p = subprocess.run(argv, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, None, "", time.perf_counter() - t0
    if p.returncode not in allow:
        fail("%s exited with %d: %s" % (" ".join(argv), p.returncode, p.stderr.strip()),
             p.returncode if p.returncode in (2, 3) else 1)
    return p.returncode, p.stdout, p.stderr, time.perf_counter() - t0


def timed(argv, out_path, timeout=None):
    """Runs argv with stdout to out_path: (status, wall s, cpu s, peak MiB, stderr); status None when it
    was stopped after `timeout` seconds.  The wait blocks, so the wall time ends when the process does,
    not at the next poll; a timer kills the process at the timeout.  The first wait leaves the process a
    zombie (WNOWAIT) until the timer is stopped, so the timer never signals a reused pid."""
    err_path = out_path + ".err"
    with open(out_path, "w") as out, open(err_path, "w") as err:
        t0 = time.perf_counter()
        p = subprocess.Popen(argv, stdout=out, stderr=err)
        stopped = []

        def stop():
            stopped.append(True)
            p.kill()

        timer = threading.Timer(timeout, stop) if timeout is not None else None
        if timer:
            timer.start()
        os.waitid(os.P_PID, p.pid, os.WEXITED | os.WNOWAIT)
        wall = time.perf_counter() - t0
        if timer:
            timer.cancel()
            timer.join()
        _, status, usage = os.wait4(p.pid, 0)
        if stopped:
            p.returncode = -9
            return None, wall, 0.0, 0.0, ""
    p.returncode = os.waitstatus_to_exitcode(status)
    with open(err_path) as f:
        stderr = f.read()
    return p.returncode, wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0, stderr


def one_json(text, argv):
    lines = [l for l in text.splitlines() if l.strip()]
    if len(lines) != 1:
        fail("%s printed %d lines, expected one JSON object" % (" ".join(argv), len(lines)))
    return json.loads(lines[0])


# ---------------------------------------------------------------------------
# Mesh files: triangles and bounding box, and binary STL for Manifold.

def read_triangles(path):
    """The triangles of an OFF, OBJ, ASCII or binary STL or ASCII PLY file (faces fanned)."""
    data = open(path, "rb").read()
    ext = os.path.splitext(path)[1].lower()
    pts, faces = [], []
    if ext == ".stl":
        if not data[:5].lower() == b"solid" or b"facet" not in data[:1000]:
            (n,) = struct.unpack_from("<I", data, 80)
            tris = []
            for i in range(n):
                v = struct.unpack_from("<12f", data, 84 + 50 * i)
                tris.append((v[3:6], v[6:9], v[9:12]))
            return tris
        verts = [tuple(float(x) for x in l.split()[1:4]) for l in data.decode("latin-1").splitlines()
                 if l.strip().lower().startswith("vertex")]
        return [tuple(verts[i:i + 3]) for i in range(0, len(verts), 3)]
    text = data.decode("latin-1")
    if ext == ".off":
        tokens = []
        for line in text.splitlines():
            line = line.split("#")[0]
            tokens.extend(line.split())
        if tokens and tokens[0].upper().endswith("OFF"):
            tokens = tokens[1:]
        nv, nf = int(tokens[0]), int(tokens[1])
        at = 3
        for _ in range(nv):
            pts.append(tuple(float(x) for x in tokens[at:at + 3]))
            at += 3
        for _ in range(nf):
            k = int(tokens[at])
            faces.append([int(x) for x in tokens[at + 1:at + 1 + k]])
            at += 1 + k
    elif ext == ".obj":
        for line in text.splitlines():
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                pts.append(tuple(float(x) for x in p[1:4]))
            elif p[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in p[1:]])
    elif ext == ".ply":
        lines = text.splitlines()
        nv = nf = 0
        i = 0
        while lines[i].strip() != "end_header":
            w = lines[i].split()
            if w[:2] == ["element", "vertex"]:
                nv = int(w[2])
            if w[:2] == ["element", "face"]:
                nf = int(w[2])
            i += 1
        i += 1
        for k in range(nv):
            pts.append(tuple(float(x) for x in lines[i + k].split()[:3]))
        for k in range(nf):
            w = lines[i + nv + k].split()
            faces.append([int(x) for x in w[1:1 + int(w[0])]])
    tris = []
    for f in faces:
        for j in range(1, len(f) - 1):
            tris.append((pts[f[0]], pts[f[j]], pts[f[j + 1]]))
    return tris


def diagonal(tris):
    lo = [min(p[k] for t in tris for p in t) for k in range(3)]
    hi = [max(p[k] for t in tris for p in t) for k in range(3)]
    return sum((hi[k] - lo[k]) ** 2 for k in range(3)) ** 0.5


def write_binary_stl(tris, path):
    with open(path, "wb") as f:
        f.write(b"minksum bench: binary STL for Manifold".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<12fH", 0.0, 0.0, 0.0, *t[0], *t[1], *t[2], 0))


def split_row(row):
    """A:B at the first ':' that starts a catalog name (a letter after it)."""
    for m in re.finditer(":", row):
        rest = row[m.start() + 1:]
        if rest[:1].isalpha() and not re.match(r"^(scale|rot|translate|neg)\b", rest):
            head = row[:m.start()]
            if head:
                return head, rest
    fail("'%s' is not A:B" % row, 2)


# ---------------------------------------------------------------------------

OPERATIONS = {"sum": "%s ⊕ %s", "erode": "%s ⊖ %s", "open": "(%s ⊖ %s) ⊕ B"}


def displacement(report):
    """The largest displacement of the written file's points, from the
    command's --json report ("rounding": every writer reports it there; a
    convex result's note on stderr words it differently); 0 when nothing was
    rounded."""
    rounding = report.get("rounding") if report else None
    return float(rounding.get("max_displacement", 0.0)) if isinstance(rounding, dict) else 0.0


def bench_row(args, a, b, index, label, triangles, op="sum"):
    minksum = os.path.join(args.build, "bin", "minksum")
    bench = os.path.join(args.build, "bin", "bench_nonconvex")
    work = args.work
    out_stl = os.path.join(work, "row%d-%s.stl" % (index, op))
    argv = [minksum, op, a, b, "-o", out_stl, "--binary", "--json"]
    runs = []
    report = None
    for r in range(args.reps):
        status, wall, cpu, peak, err = timed(argv, os.path.join(work, "row%d-minksum.json" % index),
                                             args.minksum_timeout)
        if status is None:
            return {"label": label, "refused": "minksum stopped after %d s" % args.minksum_timeout}
        if status == 3 and op != "sum" and "is not convex" in err:
            return None  # erode and open take a convex B: no such row for this pair
        if status in (1, 3):  # not a solid (3), or a sum that could not be written (1): reported as is
            return {"label": label, "refused": err.strip().splitlines()[-1] if err.strip() else "exit %d" % status}
        if status != 0:
            fail("%s exited with %d: %s" % (" ".join(argv), status, err.strip()))
        runs.append((wall, cpu, peak))
        with open(os.path.join(work, "row%d-minksum.json" % index)) as f:
            report = report or one_json(f.read(), argv)
        moved = displacement(report)
        if wall > 2:
            break
    runs.sort()
    wall, cpu, peak = runs[len(runs) // 2]
    peak = max(r[2] for r in runs)
    reps = len(runs)
    # The written file, checked by CGAL (an empty result has nothing to check).
    exact = Fraction(report["volume"])
    if report.get("empty"):
        chk = {"closed": True, "self_intersects": False, "outward": True, "volume": None, "empty": True}
    else:
        argv = [bench, "--check", out_stl]
        _, out, _, _ = run(argv)
        chk = one_json(out, argv)
    # Manifold on float operands.
    stl = []
    for k, spec in enumerate((a, b)):
        path = os.path.join(work, "row%d-%s.stl" % (index, "ab"[k]))
        if os.path.isfile(spec):
            write_binary_stl(read_triangles(spec), path)
        else:
            run([minksum, "gen", spec, "-o", path, "--binary"])
        stl.append(path)
    argv = ["node", os.path.join(HERE, "manifold.mjs"), stl[0], stl[1], "--reps", str(reps), "--op", op]
    status, out, err, _ = run(argv, timeout=args.manifold_timeout, allow=(0, 3))
    theirs = None
    if status == 0:
        theirs = one_json(out, argv)
    elif status is None:
        theirs = {"timeout": args.manifold_timeout}
    else:
        theirs = {"error": err.strip()}
    # CGAL on the exact operands (the sum or the erosion; not the opening).
    cgal, cgal_wall = None, 0.0
    if op != "open":
        argv = [bench, "--json", "--side", "cgal", "--operation", op, a + "|" + b]
        # Any exit status: CGAL's own assertions (its Nef convex decomposition
        # aborts on some inputs) are reported on the row, not fatal.
        status, out, err, cgal_wall = run(argv, timeout=args.timeout, allow=range(-128, 256))
        if status == 0:
            cgal = one_json(out, argv)["cgal"]
        elif status is not None:
            why = [l.strip() for l in err.splitlines() if l.strip()]
            cgal = {"failed": "exit %d%s" % (status, ": " + " ".join(why[-3:])[:160] if why else "")}
    return {"label": label, "op": op, "a": a, "b": b, "triangles": triangles, "wall": wall, "cpu": cpu, "peak": peak,
            "reps": reps, "report": report, "check": chk, "exact": exact, "moved": moved, "manifold": theirs,
            "cgal": cgal, "cgal_wall": cgal_wall}


def fmt_s(x):
    return "%.3f" % x if x < 10 else "%.1f" % x


def relative(value, exact):
    d = (Fraction(value) - exact) / exact
    return "0" if d == 0 else "%+.1e" % float(d)


def table(results, timeout):
    head = ("| A ⊕ B, A ⊖ B, (A ⊖ B) ⊕ B | triangles of A | minksum wall s (CPU s) | pairs / union / boundary s | pieces kept facets / culled "
            "| peak MiB | Manifold s | Manifold / minksum | CGAL s | CGAL / minksum | exact volume "
            "| written STL: closed, no self-intersection; volume − exact (relative); largest displacement "
            "| Manifold volume − exact (relative) |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    rows = []
    refused = []
    for r in results:
        if "refused" in r:
            refused.append("* %s: %s" % (r["label"], r["refused"] if r["refused"].startswith("minksum stopped")
                                         else "minksum: `%s`" % r["refused"]))
            continue
        o, m, c = r["report"], r["manifold"], r["cgal"]
        ph = o.get("phases", {})
        phases = "%s / %s / %s" % (fmt_s(ph.get("pairs", 0)), fmt_s(ph.get("union", 0)), fmt_s(ph.get("boundary", 0))) \
            if "union" in ph else "convex path"
        kept = "%d / %d" % (o.get("candidate_facets", 0), o.get("culled_facets", 0)) if "culled_facets" in o else "—"
        if m is None or "error" in m:
            man, mratio, mvol = "failed: %s" % (m or {}).get("error", "?")[:80], "—", "—"
        elif m.get("timeout"):
            man, mratio, mvol = "> %d" % m["timeout"], "> %.1f×" % (m["timeout"] / r["wall"]), "—"
        else:
            man = fmt_s(m["seconds"])
            mratio = "%.2f×" % (m["seconds"] / r["wall"])
            mvol = relative(m["volume"], r["exact"]) if r["exact"] else "%.3g (exact 0)" % m["volume"]
        if c is None and r.get("op") == "open":
            cg, cratio = "—", "—"
        elif c is not None and "failed" in c:
            cg, cratio = "failed (%s)" % c["failed"].replace("|", "/"), "—"
        elif c is None:
            q = timeout / r["wall"]
            cg, cratio = "> %d" % timeout, ("> %.0f×" if q >= 10 else "> %.1f×") % q
        else:
            same = Fraction(c["volume"]) == r["exact"]
            cg = fmt_s(c["seconds"]) + ("" if same else " (volume DIFFERS)")
            cratio = "%.1f×" % (c["seconds"] / r["wall"])
        k = r["check"]
        ok = "yes" if k["closed"] and not k["self_intersects"] and k["outward"] else "NO (%s)" % json.dumps(k)
        wvol = relative(Fraction(k["volume"]), r["exact"]) if k["volume"] and r["exact"] else "—"
        rows.append("| %s | %d | %s (%s) | %s | %s | %.0f | %s | %s | %s | %s | %.9g | %s; %s; %.2g | %s |" % (
            r["label"], r["triangles"], fmt_s(r["wall"]), fmt_s(r["cpu"]), phases, kept, r["peak"], man, mratio, cg,
            cratio, float(r["exact"]), ok, wvol, r["moved"], mvol))
    return head + "\n".join(rows) + "\n" + ("\n" + "\n".join(refused) + "\n" if refused else "")


def targets(results, timeout):
    ok = [r for r in results if "refused" not in r]
    lines = []
    for op, what in (("sum", "sums"), ("erode", "erosions"), ("open", "openings")):
        big = [r for r in ok if r.get("op", "sum") == op and r["triangles"] >= 1024 and r["manifold"]
               and "seconds" in r["manifold"]]
        if not big and op != "sum":
            continue
        met = [r for r in big if r["manifold"]["seconds"] >= 10 * r["wall"]]
        lines.append("* %s: ≥ 10× faster than Manifold on every row of ≥ 1 024 triangles: %d of %d rows%s." % (
            what, len(met), len(big), "" if len(met) == len(big) else " (not met)"))
    sums = {(r["a"], r["b"]): r for r in ok if r.get("op", "sum") == "sum"}
    opened = [(r, sums[(r["a"], r["b"])]) for r in ok if r.get("op") == "open" and (r["a"], r["b"]) in sums]
    if opened:
        within = [o for o, s in opened if o["wall"] <= 3 * s["wall"]]
        lines.append("* openings within 3× the time of the same sum: %d of %d rows (%s)." % (
            len(within), len(opened), ", ".join("%.1f×" % (o["wall"] / s["wall"]) for o, s in opened)))
    timed_rows = [r for r in ok if r["manifold"] and "seconds" in r["manifold"]]
    faster = [r for r in timed_rows if r["manifold"]["seconds"] > r["wall"]]
    lines.append("* faster than Manifold: %d of %d rows." % (len(faster), len(timed_rows)))
    finished = [r for r in ok if r["cgal"] is not None and "failed" not in r["cgal"]]
    hundred = [r for r in finished if r["cgal"]["seconds"] >= 100 * r["wall"]]
    lines.append("* ≥ 100× faster than CGAL where CGAL finished within %d s: %d of %d rows; CGAL's volume equal to "
                 "minksum's on %d of them." % (timeout, len(hundred), len(finished),
                                               sum(Fraction(r["cgal"]["volume"]) == r["exact"] for r in finished)))
    largest = [r for r in ok if r["label"].startswith("torus:256:128")]
    for r in largest:
        lines.append("* the 65 536-triangle torus: %s s wall, %.0f MiB peak (targets ≤ 10 s, ≤ 4 096 MiB)." % (
            fmt_s(r["wall"]), r["peak"]))
    valid = [r for r in ok if r["check"]["closed"] and not r["check"]["self_intersects"] and r["check"]["outward"]]
    lines.append("* written STL closed, outward and without self-intersection (CGAL): %d of %d rows." % (len(valid), len(ok)))
    return "\n".join(lines) + "\n"


def main():
    if hasattr(sys, "set_int_max_str_digits"):
        sys.set_int_max_str_digits(0)  # exact volumes of thousands of digits
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("rows", nargs="*", help="A:B catalog specs (default: the torus family and the catalog rows)")
    ap.add_argument("--build", default="build-bench", help="build directory with bin/bench_nonconvex and bin/minksum")
    ap.add_argument("--reps", type=int, default=3, help="runs of minksum and of Manifold per row (median)")
    ap.add_argument("--timeout", type=int, default=120, help="seconds after which CGAL's run is stopped")
    ap.add_argument("--manifold-timeout", type=int, default=1800, help="seconds after which Manifold's run is stopped")
    ap.add_argument("--resume", action="store_true",
                    help="reuse the rows a previous run with the same --work finished (their saved results)")
    ap.add_argument("--minksum-timeout", type=int, default=1800, help="seconds after which minksum's run is stopped")
    ap.add_argument("--meshes", help="a directory of mesh files: each ⊕ a ball of 2 %% of its bounding-box diagonal")
    ap.add_argument("--work", help="directory for the operands' STL files (default BUILD/nonconvex)")
    ap.add_argument("--operations", default="sum,erode,open",
                    help="comma-separated operations of every row: sum, erode, open (default all three)")
    ap.add_argument("--catalog-operations",
                    help="the operations of the catalog rows (A:B specs) when they differ from --operations, "
                         "e.g. sum: the erosions and openings of the mesh files only")
    ap.add_argument("--page", help="write the page here (e.g. docs/generated/benchmarks-nonconvex.md)")
    ap.add_argument("--command", default="/usr/bin/python3 bench/nonconvex/run.py",
                    help="the command named in the page's header")
    args = ap.parse_args()
    if args.reps < 1 or args.timeout < 1:
        fail("--reps and --timeout need positive integers", 2)
    if args.meshes and not os.path.isdir(args.meshes):
        fail("--meshes: %s is not a directory" % args.meshes, 2)
    args.operations = [o for o in args.operations.split(",") if o]
    if not args.operations or any(o not in OPERATIONS for o in args.operations):
        fail("--operations takes a comma-separated list of sum, erode, open", 2)
    if args.catalog_operations is None:
        args.catalog_operations = args.operations
    else:
        args.catalog_operations = [o for o in args.catalog_operations.split(",") if o]
        if not args.catalog_operations or any(o not in OPERATIONS for o in args.catalog_operations):
            fail("--catalog-operations takes a comma-separated list of sum, erode, open", 2)
    args.work = args.work or os.path.join(args.build, "nonconvex")
    os.makedirs(args.work, exist_ok=True)
    args.reused = 0
    jobs = []
    for row in args.rows or DEFAULT_ROWS:
        a, b = split_row(row)
        m = re.match(r"^torus:(\d+):(\d+)", a)
        tri = 2 * int(m.group(1)) * int(m.group(2)) if m else 0
        jobs.append((a, b, "%s ⊕ %s" % (a, b), tri))
    catalog_jobs = len(jobs)
    if args.meshes:
        for name in sorted(os.listdir(args.meshes)):
            path = os.path.join(args.meshes, name)
            if not name.lower().endswith(MESH_EXTENSIONS) or not os.path.isfile(path):
                continue
            try:
                tris = read_triangles(path)
            except (ValueError, IndexError, struct.error) as e:
                jobs.append((path, None, name, 0, "not read by this script: %s" % e))
                continue
            r = 0.02 * diagonal(tris)
            ball = "sphere:2@scale:%.4g" % r
            jobs.append((path, ball, "%s ⊕ %s" % (name, ball), len(tris)))
    load_start = " ".join(open("/proc/loadavg").read().split()[:3])
    started = time.perf_counter()
    results = []
    for i, job in enumerate(jobs):
        sys.stderr.write("run.py: %s\n" % job[2])
        if job[1] is None:
            results.append({"label": job[2], "refused": job[4]})
            continue
        a, b, sum_label, tri = job
        shown_a, shown_b = sum_label.split(" ⊕ ", 1)
        for op in args.catalog_operations if i < catalog_jobs else args.operations:
            label = OPERATIONS[op] % (shown_a, shown_b)
            cache = os.path.join(args.work, "result-%s.json" % re.sub(r"[^A-Za-z0-9.@:_-]+", "_", op + "-" + label))
            if args.resume and os.path.isfile(cache):
                args.reused += 1
                with open(cache) as f:
                    r = json.load(f)
                if "exact" in r:
                    r["exact"] = Fraction(r["exact"])
                if "report" in r:
                    r["moved"] = displacement(r["report"])
                results.append(r)
                continue
            if not tri:
                # A catalog solid: its triangles as minksum writes them.
                path = os.path.join(args.work, "count%d.stl" % i)
                run([os.path.join(args.build, "bin", "minksum"), "gen", a, "-o", path, "--binary"])
                tri = len(read_triangles(path))
            if op != "sum":
                sys.stderr.write("run.py: %s\n" % label)
            r = bench_row(args, a, b, i, label, tri, op)
            if r is None:
                continue
            results.append(r)
            with open(cache, "w") as f:
                json.dump(results[-1], f, default=str)
    wall = time.perf_counter() - started
    if args.meshes:
        # Messages name the directory as the command line does: DIR.
        for r in results:
            if "refused" in r:
                for d in (os.path.abspath(args.meshes), os.path.normpath(args.meshes), args.meshes):
                    r["refused"] = r["refused"].replace(d.rstrip("/") + "/", "DIR/")
    load_end = " ".join(open("/proc/loadavg").read().split()[:3])
    md = table(results, args.timeout)
    sys.stdout.write(md + "\n" + targets(results, args.timeout))
    sys.stdout.flush()
    if args.page:
        write_page(args, results, md, load_start, load_end, wall)


def write_page(args, results, md, load_start, load_end, wall):
    done = [r for r in results if "refused" not in r and r["manifold"] and "manifold" in r["manifold"]]
    manifold = done[0]["manifold"]["manifold"] if done else "?"
    node = subprocess.run(["node", "--version"], capture_output=True, text=True).stdout.strip()
    text = """# Non-convex sums and erosions: minksum, Manifold's minkowskiSum and minkowskiDifference, CGAL's minkowski_sum_3

<!-- Generated by `{command}` (bench/nonconvex/run.py, bench/nonconvex/main.cpp, bench/nonconvex/manifold.mjs). Do not edit by hand: every figure below comes from that command. -->

Generated by `{command}` on {date}, {wall:.0f} s in all{reused}, on {machine} with {cpus} hardware threads,
load average {load_start} at the start and {load_end} at the end.
Method and reading of the columns: [docs/nonconvex.md](../nonconvex.md), "Speed".

* minksum: the whole process `minksum sum A B -o OUT.stl --binary --json` (`erode`, `open` for the rows
  A ⊖ B and (A ⊖ B) ⊕ B) as a user runs it (reading,
  validation, the sum on every hardware thread, the rounded write), the median wall time of up to {reps}
  runs (one when a run takes over 2 s), its CPU time (user + system) and peak memory; the phases are the
  sum's own.
* the written STL: read back and checked by CGAL's Polygon_mesh_processing on exact points (closed, outward,
  no self-intersection), its exact volume against the exact sum's, and the largest displacement minksum's
  rounding reported.
* Manifold: `Manifold.minkowskiSum` (erosions: `minkowskiDifference`; openings: both in turn) of
  manifold-3d {manifold} (WebAssembly, one thread) under Node {node}, on
  the operands as float STL, only the call timed, the median of as many runs as minksum's.
* CGAL: `minkowski_sum_3` on the same exact operands as Nef polyhedra (erosions: A minus
  `minkowski_sum_3`(box − A, −B); openings: not run), once, stopped after {timeout} s; a run that
  CGAL itself aborts (an assertion of its Nef polyhedra) is reported on its row.

{md}
## Targets (docs/nonconvex.md, "Speed")

{targets}""".format(command=args.command, date=datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                    wall=wall, reused="" if not args.reused else
                    " (%d rows measured by earlier runs of the same command in the same --work directory and reused "
                    "with --resume)" % args.reused, machine=platform.machine(), cpus=os.cpu_count(), load_start=load_start,
                    load_end=load_end, reps=args.reps, timeout=args.timeout, manifold=manifold, node=node, md=md,
                    targets=targets(results, args.timeout))
    tmp = args.page + ".tmp"
    try:
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, args.page)
    except OSError as e:
        fail("cannot write %s: %s" % (args.page, e))


if __name__ == "__main__":
    main()
