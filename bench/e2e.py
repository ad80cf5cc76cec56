#!/usr/bin/python3
"""minksum bench, end to end: whole processes, file to file.

    python3 bench/e2e.py [--minksum build-bench/bin/minksum] [--work build-bench/e2e]
                         [--rounds 22] [--memory-rounds 3] [--page docs/generated/benchmarks.md]
                         [--command "make bench-e2e"]

For each row the operands are written as double OFF files with `minksum gen`
(untimed); for the rows Qhull can take, the pairwise sums of the files'
coordinates (added in double arithmetic) are written in qhull's input format
(untimed).  Then, interleaved over the rounds, each contender runs as a
whole process:

    minksum sum A.off B.off -o S.off
    qconvex o TI pts.txt TO out.off

started by bench_spawn (bench/spawn.cpp, built beside the minksum it
times, or --spawn PATH), which reports its wall time from fork to exit and
its own peak resident memory (wait4's ru_maxrss; started from this Python
process directly, a program's ru_maxrss would include Python's own).
The order of the contenders is reversed every other
round (minksum, qconvex, qconvex, minksum, minksum, ...), and the untimed
first run of each goes in the reverse order of the first round, so over an
even number of rounds each runs exactly half its rounds right after the
other contender and half right after itself:
on a virtual machine the process run just before can slow the next one by
milliseconds (bench/predecessor.py measures it; docs/data-model.md), and a
fixed order would charge that to one contender only.
Each contender's times are also reported by the contender that ran just
before.  Then the load row (`minksum stats` on a 10 000-vertex
file) and the million row: `minksum gen random:1000000:7` (untimed, about
30 s), then `minksum sum r1m.off cube -o S.off --json` over the memory
rounds, with its phases (read, validate, sum, ...).  `--only` takes the row
keys a, b, c1, c2, load, million.  `--baseline PATH` adds another minksum
build (an earlier commit, say) to the rounds of the rows Qhull takes, as a
third contender interleaved with the two (minksum, qconvex, baseline, then
baseline, qconvex, minksum, ..., its output to a file of its own), reported in a line with its median and
quartiles beside minksum's: two builds compared under the same conditions.
The section "End to end: file to file" of
the page is replaced (or inserted before "## Machine and software", or
appended).
"""

import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import time

BEGIN = "<!-- e2e:begin -->"
END = "<!-- e2e:end -->"


# bench_spawn (bench/spawn.cpp), set by use_spawn: every timed program is started through it.
SPAWN = None


def use_spawn(args):
    """Find bench_spawn: --spawn, else beside --minksum (both built by `make bench-e2e`)."""
    global SPAWN
    path = args.spawn or os.path.join(os.path.dirname(os.path.abspath(args.minksum)), "bench_spawn")
    if not os.access(path, os.X_OK):
        raise SystemExit("e2e: %s not found: `make bench-e2e` builds it (target bench_spawn of a build "
                         "configured with -DMINKSUM_BENCH=ON), or give --spawn PATH" % path)
    SPAWN = path


def run_process(argv, stdout=subprocess.DEVNULL):
    """Run argv to completion: (wall seconds, peak RSS KiB, exit status, stdout text or None, stderr text).

    The seconds and the peak memory are bench_spawn's report of the program alone: the clock from just
    before its fork to just after its wait4, and the program's own ru_maxrss.  (Measured from this
    process instead, ru_maxrss would be at least this Python process's own peak: Linux charges the
    address space a vfork'ed child leaves at exec to the child; bench/spawn.cpp.)"""
    r, w = os.pipe()
    try:
        p = subprocess.Popen([SPAWN, str(w)] + list(argv), stdout=stdout, stderr=subprocess.PIPE, pass_fds=(w,))
    finally:
        os.close(w)
    out = p.stdout.read() if stdout == subprocess.PIPE else None
    err = p.stderr.read()
    p.wait()
    with os.fdopen(r) as f:
        report = f.read().split()
    if p.returncode != 0 or len(report) != 3:
        raise SystemExit("e2e: %s failed (%d): %s" % (SPAWN, p.returncode, err.decode(errors="replace").strip()))
    return (float(report[0]), int(report[1]), int(report[2]), (out.decode() if out is not None else None),
            err.decode())


def check(argv):
    t, rss, rc, out, err = run_process(argv, stdout=subprocess.PIPE)
    if rc != 0:
        raise SystemExit("e2e: %s failed (%d): %s" % (" ".join(argv), rc, err.strip()))
    return out


def off_points(path):
    """Vertex coordinates of an OFF file (text, doubles) and its V/F header counts."""
    with open(path) as f:
        toks = []
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                toks.append(line)
            if len(toks) >= 2 or (toks and toks[0].split() != ["OFF"]):
                break
        head = toks[0].split()
        counts = (toks[1].split() if head == ["OFF"] else head[1:])
        nv, nf = int(counts[0]), int(counts[1])
        pts = []
        while len(pts) < nv:
            line = f.readline()
            if not line:
                break
            line = line.split("#", 1)[0].split()
            if line:
                pts.append((float(line[0]), float(line[1]), float(line[2])))
    return pts, nv, nf


def off_counts(path):
    """(vertices, facets) of an OFF file as a polytope: the vertices its facets use (Qhull's `o` lists every
    input point, interior ones too) and the number of facets.  Also reads qhull's header (a dimension line
    instead of "OFF")."""
    with open(path) as f:
        def lines():
            for line in f:
                line = line.split("#", 1)[0].split()
                if line:
                    yield line
        it = lines()
        head = next(it)
        if head[0] == "OFF" and len(head) == 1:
            head = next(it)
        elif head[0] == "OFF":
            head = head[1:]
        elif len(head) == 1:  # qhull: the dimension, then the counts
            head = next(it)
        nv, nf = int(head[0]), int(head[1])
        for _ in range(nv):
            next(it)
        used = set()
        for _ in range(nf):
            face = next(it)
            used.update(face[1:1 + int(face[0])])
    return len(used), nf


def write_qhull_points(a, b, path):
    """The pairwise sums a_i + b_j (double arithmetic) in qhull's input format."""
    with open(path, "w") as f:
        f.write("3\n%d\n" % (len(a) * len(b)))
        for (x, y, z) in a:
            f.write("".join("%r %r %r\n" % (x + u, y + v, z + w) for (u, v, w) in b))


def fmt_s(x):
    return "%.3g" % x if x < 100 else "%.0f" % x


def fmt_mib(kb):
    return "%.0f MiB" % (kb / 1024.0)


def contender_args(description, rounds):
    """The options bench/e2e.py and bench/predecessor.py share: the two programs, the work directory and
    the number of rounds."""
    ap = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--minksum", default="build-bench/bin/minksum")
    ap.add_argument("--qconvex", default="qconvex")
    ap.add_argument("--work", default="build-bench/e2e")
    ap.add_argument("--rounds", type=int, default=rounds)
    ap.add_argument("--spawn", default="", help="bench_spawn (default: beside --minksum)")
    return ap


def main():
    ap = contender_args(__doc__, 22)
    ap.add_argument("--memory-rounds", type=int, default=3)
    ap.add_argument("--page", default="docs/generated/benchmarks.md")
    ap.add_argument("--command", default="make bench-e2e")
    ap.add_argument("--only", default="", help="comma-separated row keys (a,b,c1,c2,load,million)")
    ap.add_argument("--baseline", default="", help="another minksum build, run as a third contender (rows a, b)")
    args = ap.parse_args()
    use_spawn(args)
    ms = os.path.abspath(args.minksum)
    os.makedirs(args.work, exist_ok=True)
    W = lambda name: os.path.join(args.work, name)
    only = set(filter(None, args.only.split(",")))
    log = lambda *m: print("e2e:", *m, file=sys.stderr, flush=True)
    wall0 = time.perf_counter()
    load_start = open("/proc/loadavg").read().split()[:3]

    def gen(spec, name):
        path = W(name)
        out = check([ms, "gen", spec, "-o", path])
        log(out.strip())
        return path

    def convex_as_written(path):
        t, rss, rc, out, err = run_process([ms, "stats", path], stdout=subprocess.PIPE)
        return rc == 0, err.strip()

    rows = [
        dict(key="a", a="cube", fa="cube.off", b="sphere:6", fb="sphere6.off", qhull=True,
             goal="ratio", goal_value=10, rounds=args.rounds),
        dict(key="b", a="sphere:4", fa="sphere4.off", b="sphere:4@rot:5", fb="sphere4rot5.off", qhull=True,
             goal="ratio", goal_value=20, rounds=args.rounds),
        dict(key="c1", a="sphere:7", fa="sphere7.off", b="sphere:7@rot:1", fb="sphere7rot1.off", qhull=False,
             goal="rss", goal_value=1024, rounds=args.memory_rounds),
        dict(key="c2", a="random:100000:1", fa="random100000-1.off", b="random:100000:2",
             fb="random100000-2.off", qhull=False, goal="rss", goal_value=2048, rounds=args.memory_rounds),
    ]
    results = []
    for row in rows:
        if only and row["key"] not in only:
            continue
        log("row", row["key"], row["a"], "+", row["b"])
        fa, fb = gen(row["a"], row["fa"]), gen(row["b"], row["fb"])
        notes = []
        hull = False
        for spec, path in ((row["a"], fa), (row["b"], fb)):
            ok, why = convex_as_written(path)
            if ok and "@rot" in spec:
                notes.append("`%s` rounded to doubles is still exactly convex (`minksum stats` accepts the file): "
                             "no `--hull`" % spec)
            if not ok:
                hull = True
                notes.append("`%s` rounded to doubles is not exactly convex (`minksum stats`: %s): the sum "
                             "runs with `--hull` (the exact hull of each file's points)" % (spec, why))
        sum_cmd = [ms, "sum", fa, fb, "-o", W("sum-%s.off" % row["key"])] + (["--hull"] if hull else [])
        contenders = [("minksum", sum_cmd)]
        pa, nva, _ = off_points(fa)
        pb, nvb, _ = off_points(fb)
        pairs = nva * nvb
        if row["qhull"]:
            pts = W("pts-%s.txt" % row["key"])
            log("writing %d pairwise sums to %s" % (pairs, pts))
            write_qhull_points(pa, pb, pts)
            contenders.append(("qconvex", [args.qconvex, "o", "TI", pts, "TO", W("qconvex-%s.off" % row["key"])]))
            if args.baseline:
                contenders.append(("baseline", [args.baseline, "sum", fa, fb, "-o", W("baseline-%s.off" % row["key"])] +
                                    (["--hull"] if hull else [])))
        del pa, pb
        # One untimed run of each (files in the page cache, binaries loaded), then the rounds, interleaved.
        # The untimed runs go in the reverse order of round 1, so that round 1 starts with its first
        # contender right after itself: over an even number of rounds each contender then runs exactly
        # half its rounds after itself and half after another.
        for name, cmd in contenders[::-1]:
            t, rss, rc, out, err = run_process(cmd)
            if rc != 0:
                raise SystemExit("e2e: %s failed (%d): %s" % (" ".join(cmd), rc, err.strip()))
        times = {name: [] for name, _ in contenders}
        rsss = {name: [] for name, _ in contenders}
        after = {name: {} for name, _ in contenders}  # name -> the contender run just before -> times
        last = contenders[0][0]  # the last untimed run
        for r in range(row["rounds"]):
            for name, cmd in (contenders if r % 2 == 0 else contenders[::-1]):
                t, rss, rc, out, err = run_process(cmd)
                if rc != 0:
                    raise SystemExit("e2e: %s failed (%d): %s" % (" ".join(cmd), rc, err.strip()))
                times[name].append(t)
                rsss[name].append(rss)
                after[name].setdefault(last, []).append(t)
                last = name
                log("  round %d %s: %.3f s, %s" % (r + 1, name, t, fmt_mib(rss)))
        res = dict(row=row, hull=hull, notes=notes, pairs=pairs, cmds=dict(contenders), times=times, rss=rsss,
                   after=after)
        res["counts"] = {"minksum": off_counts(W("sum-%s.off" % row["key"]))}
        if row["qhull"]:
            res["counts"]["qconvex"] = off_counts(W("qconvex-%s.off" % row["key"]))
        # The phases of one further run, when the CLI reports them (untimed here).
        try:
            js = json.loads(check(sum_cmd + ["--json"]))
            res["phases"] = js.get("phases")
        except (SystemExit, ValueError):
            res["phases"] = None
        results.append(res)

    load = None
    if not only or "load" in only:
        log("row load")
        path = gen("random:10000:1", "random10000-1.off")
        nv, nf = off_counts(path)
        ok, why = convex_as_written(path)
        if not ok:
            raise SystemExit("e2e: %s is not exactly convex as written: %s" % (path, why))
        cmd = [ms, "stats", path]
        run_process(cmd)
        times, rsss, phases = [], [], []
        for r in range(args.rounds):
            t, rss, rc, out, err = run_process(cmd)
            times.append(t)
            rsss.append(rss)
            try:
                js = json.loads(check(cmd + ["--json"]))
                if isinstance(js.get("phases"), dict):
                    phases.append(js["phases"])
            except (SystemExit, ValueError):
                pass
        load = dict(path=path, nv=nv, nf=nf, cmd=cmd, times=times, rss=rsss, phases=phases)

    million = None
    if not only or "million" in only:
        log("row million")
        path = W("r1m.off")
        gen_cmd = [ms, "gen", "random:1000000:7", "-o", path]
        gen_t, gen_rss, rc, out, err = run_process(gen_cmd, stdout=subprocess.PIPE)
        if rc != 0:
            raise SystemExit("e2e: %s failed (%d): %s" % (" ".join(gen_cmd), rc, err.strip()))
        log(out.strip())
        log("  minksum gen: %.3f s, %s" % (gen_t, fmt_mib(gen_rss)))
        nv, nf = off_counts(path)
        cmd = [ms, "sum", path, "cube", "-o", W("sum-million.off"), "--json"]
        times, rsss, phases = [], [], []
        for r in range(args.memory_rounds):
            t, rss, rc, out, err = run_process(cmd, stdout=subprocess.PIPE)
            if rc != 0:
                raise SystemExit("e2e: %s failed (%d): %s" % (" ".join(cmd), rc, err.strip()))
            times.append(t)
            rsss.append(rss)
            try:
                js = json.loads(out)
                if isinstance(js.get("phases"), dict):
                    phases.append(js["phases"])
            except ValueError:
                pass
            log("  round %d minksum: %.3f s, %s" % (r + 1, t, fmt_mib(rss)))
        million = dict(path=path, nv=nv, nf=nf, cmd=cmd, times=times, rss=rsss, phases=phases,
                       gen_cmd=gen_cmd, gen_t=gen_t, gen_rss=gen_rss)

    md = section(args, results, load, million, load_start, time.perf_counter() - wall0)
    write_page(args.page, md)
    log("wrote the section \"End to end: file to file\" of %s in %.0f s" % (args.page, time.perf_counter() - wall0))


def rel(path):
    return os.path.relpath(path) if os.path.isabs(path) else path


def shown(cmd):
    return " ".join(rel(c) if os.path.sep in c else c for c in cmd)


def quartile_text(ts):
    """"quartiles A–B s" of a list of times (one time: both quartiles are it)."""
    q = statistics.quantiles(ts, n=4) if len(ts) > 1 else [ts[0]] * 3
    return "quartiles %s–%s s" % (fmt_s(q[0]), fmt_s(q[2]))


def spread(ts):
    return "%s, range %s–%s s" % (quartile_text(ts), fmt_s(min(ts)), fmt_s(max(ts)))


def quartiles(ts):
    return "median %s s, %s" % (fmt_s(statistics.median(ts)), quartile_text(ts))


def section(args, results, load, million, load_start, wall):
    L = []
    add = L.append
    add(BEGIN)
    add("## End to end: file to file")
    add("")
    add("<!-- Generated by `%s` (bench/e2e.py). Do not edit by hand. -->" % args.command)
    add("")
    add("Whole processes, from operand files to the sum's file, on the machine of \"Machine and software\" (shared: other jobs may be "
        "running). Produced by `%s`, i.e. `/usr/bin/python3 bench/e2e.py --minksum %s --work %s --rounds %d "
        "--memory-rounds %d`, on %s; load average at start %s, at end %s; %.0f s in all."
        % (args.command, rel(args.minksum), rel(args.work), args.rounds, args.memory_rounds,
           datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"), " ".join(load_start),
           " ".join(open("/proc/loadavg").read().split()[:3]), wall))
    add("")
    add("* The operands are written as double OFF files with `minksum gen SPEC -o FILE` (rotated solids are "
        "rounded to the nearest doubles). For Qhull, the pairwise sums a_i + b_j of the files' coordinates "
        "(added in double arithmetic) are written beforehand in qhull's input format; neither step is timed.")
    add("* Timed, each as a process from fork to exit (wall clock, started by `bench_spawn`, bench/spawn.cpp): "
        "`minksum sum A.off B.off -o S.off` and "
        "`qconvex o TI pts.txt TO out.off` (Qhull's command-line hull, default pre-merge `C-0`, output as OFF). "
        "Peak memory: the process's own maximum resident set (`ru_maxrss` from `wait4` in `bench_spawn`; "
        "a program started from the Python script directly would report at least the script's own).")
    add("* After one untimed run of each (in the reverse order of the first round), the contenders of a row "
        "alternate for the row's rounds, in an order reversed every other round (minksum, qconvex, qconvex, "
        "minksum, minksum, ...): over an even number of rounds each runs exactly half its rounds right after "
        "the other and half right after itself. On this machine the process run just "
        "before can slow the next one by milliseconds (`bench/predecessor.py` measures it; see "
        "[data-model.md](../data-model.md)), so a fixed order would charge that to one contender; the notes below give each contender's median by the contender run just "
        "before. A figure is the **median** over all the rounds, the ratio is qconvex's median ÷ minksum's "
        "median.")
    add("")
    add("| A ⊕ B | files | rounds | minksum sum: time | peak RSS | V/F | qconvex o: time | peak RSS | V/F | "
        "qconvex ÷ minksum | target | verdict |")
    add("|---|---|---:|---:|---:|---|---:|---:|---|---:|---|---|")
    notes = []
    for r in results:
        row = r["row"]
        tm = statistics.median(r["times"]["minksum"])
        rm = max(r["rss"]["minksum"])
        vm = "%d/%d" % r["counts"]["minksum"]
        files = "`%s`, `%s`" % (row["fa"], row["fb"])
        if r["hull"]:
            files += " (`--hull`)"
        if row["qhull"]:
            tq = statistics.median(r["times"]["qconvex"])
            rq = max(r["rss"]["qconvex"])
            vq = "%d/%d" % r["counts"]["qconvex"]
            ratio = tq / tm
            q = (fmt_s(tq) + " s", fmt_mib(rq), vq, "%.2f×" % ratio)
        else:
            q = ("not run: %.3g pairwise sums" % r["pairs"], "—", "—", "—")
        if row["goal"] == "ratio":
            target = "≥ %d×" % row["goal_value"]
            met = ratio >= row["goal_value"]
        else:
            target = "peak RSS < %s" % ("%d GiB" % (row["goal_value"] // 1024))
            met = rm < row["goal_value"] * 1024
        add("| `%s` ⊕ `%s` | %s | %d | %s s | %s | %s | %s | %s | %s | %s | %s | %s |"
            % (row["a"], row["b"], files, row["rounds"], fmt_s(tm), fmt_mib(rm), vm, q[0], q[1], q[2], q[3],
               target, "met" if met else "not met"))
        for n in r["notes"]:
            notes.append("`%s` ⊕ `%s`: %s." % (row["a"], row["b"], n))
        if r.get("phases"):
            notes.append("`%s` ⊕ `%s`, phases of one `minksum sum --json` run: %s." % (
                row["a"], row["b"], ", ".join("%s %s s" % (k, fmt_s(float(v))) for k, v in r["phases"].items())))
        if r["times"]["minksum"]:
            notes.append("`%s` ⊕ `%s`: minksum %s%s." % (
                row["a"], row["b"], spread(r["times"]["minksum"]),
                ("; qconvex %s" % spread(r["times"]["qconvex"])) if row["qhull"] else ""))
        if row["qhull"] and len(r["after"]) > 1:
            def by_before(name):
                return ", ".join("after %s %s s (%d round%s)" % ("itself" if b == name else b,
                                                                  fmt_s(statistics.median(ts)), len(ts),
                                                                  "" if len(ts) == 1 else "s")
                                 for b, ts in sorted(r["after"][name].items()))
            line = "`%s` ⊕ `%s`, medians by the contender run just before: minksum %s; qconvex %s" % (
                row["a"], row["b"], by_before("minksum"), by_before("qconvex"))
            mq = r["after"]["minksum"].get("qconvex")
            if mq:
                line += "; qconvex's median ÷ minksum's median after qconvex: %.2f×" % (
                    statistics.median(r["times"]["qconvex"]) / statistics.median(mq))
            notes.append(line + ".")
        if r["times"].get("baseline"):
            notes.append("`%s` ⊕ `%s`, against the baseline build `%s` (`--baseline`, interleaved in the same "
                         "rounds): minksum %s; baseline %s." % (
                             row["a"], row["b"], r["cmds"]["baseline"][0], quartiles(r["times"]["minksum"]),
                             quartiles(r["times"]["baseline"])))
    add("")
    add("Peak RSS is the largest over the rounds. V/F: the vertices used by the output file's facets, and its "
        "facets (Qhull's `o` lists every input point; its facets are its merged facets).")
    add("")
    for n in notes:
        add("* " + n)
    if load:
        add("")
        add("### Load and validate")
        add("")
        tl = statistics.median(load["times"])
        add("`minksum stats FILE` on `%s` (`minksum gen random:10000:1`: %d vertices, %d triangles, doubles), "
            "%d rounds, median, as a process." % (os.path.basename(load["path"]), load["nv"], load["nf"],
                                                  len(load["times"])))
        add("")
        add("| what | time | peak RSS | target | verdict |")
        add("|---|---:|---:|---|---|")
        ph = [p for p in load["phases"] if "read" in p]
        if ph:
            read = statistics.median(float(p["read"]) for p in ph)
            val = statistics.median(float(p.get("read", 0)) + float(p.get("validate", 0)) for p in ph)
            add("| load + validate (`stats`, process) | %s s | %s | | |" % (fmt_s(tl), fmt_mib(max(load["rss"]))))
            add("| load + validate (phases `read` + `validate` of `stats --json`) | %s s | | ≤ 5× parse | %s |"
                % (fmt_s(val), "met" if val <= 5 * read else "not met"))
            add("| parse only (phase `read`) | %s s | | | |" % fmt_s(read))
            add("")
            add("load + validate ÷ parse = %.2f×." % (val / read))
        else:
            add("| load + validate (`stats`, process) | %s s | %s | ≤ 5× parse | not measured |"
                % (fmt_s(tl), fmt_mib(max(load["rss"]))))
            add("| parse only | — | — | | |")
            add("")
            add("TODO: parse-only time needs a phase report from minksum (`\"phases\"` with `read` and `validate` "
                "seconds in `minksum stats --json`); this build's `stats --json` has none, so the ratio "
                "load + validate ÷ parse is not measured.")
    if million:
        add("")
        add("### A million vertices")
        add("")
        tm = statistics.median(million["times"])
        add("`%s` on `%s` (`minksum gen random:1000000:7`, timed once below: %d vertices, %d triangles, doubles) and the "
            "catalog's cube, %d rounds, median, as a process; the phases are those its `--json` reports."
            % (shown(million["cmd"]), os.path.basename(million["path"]), million["nv"], million["nf"],
               len(million["times"])))
        add("")
        add("| what | time | peak RSS | target | verdict |")
        add("|---|---:|---:|---|---|")
        peak = max(million["rss"])
        add("| `minksum sum` (process: read, validate, sum, write) | %s s | %s | peak RSS < 1.5 GiB | %s |"
            % (fmt_s(tm), fmt_mib(peak), "met" if peak < 1.5 * 1024 * 1024 else "not met"))
        add("| `%s` (process, once) | %s s | %s | within 30 s | %s |"
            % (shown(million["gen_cmd"]), fmt_s(million["gen_t"]), fmt_mib(million["gen_rss"]),
               "met" if million["gen_t"] <= 30 else "not met"))
        ph = [p for p in million["phases"] if "read" in p]
        if ph:
            read = statistics.median(float(p["read"]) for p in ph)
            rvs = statistics.median(float(p["read"]) + float(p.get("validate", 0)) + float(p.get("sum", 0)) +
                                    float(p.get("explicit", 0)) for p in ph)
            add("| read + validate + sum (phases `read`, `validate`, `sum`, `explicit`) | %s s | | ≤ 10× parse | %s |"
                % (fmt_s(rvs), "met" if rvs <= 10 * read else "not met"))
            add("| parse only (phase `read`) | %s s | | | |" % fmt_s(read))
            for k in ("validate", "sum", "explicit", "write"):
                if k in ph[0]:
                    add("| phase `%s` | %s s | | | |" % (k, fmt_s(statistics.median(float(p[k]) for p in ph))))
            add("")
            add("read + validate + sum ÷ parse = %.2f×." % (rvs / read))
    add(END)
    return "\n".join(L) + "\n"


def write_page(page, md):
    text = open(page).read() if os.path.exists(page) else ""
    if BEGIN in text and END in text:
        i, j = text.index(BEGIN), text.index(END) + len(END)
        if j < len(text) and text[j] == "\n":
            j += 1
        text = text[:i] + md + text[j:]
    elif "\n## Machine and software" in text:
        i = text.index("\n## Machine and software") + 1
        text = text[:i] + md + "\n" + text[i:]
    else:
        text = text + ("\n" if text and not text.endswith("\n\n") else "") + md
    os.makedirs(os.path.dirname(page) or ".", exist_ok=True)
    with open(page, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
