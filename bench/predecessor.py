#!/usr/bin/python3
"""How the process run just before changes a `minksum sum` run, file to file.

    /usr/bin/python3 bench/predecessor.py [--minksum build-bench/bin/minksum] [--work build-bench/e2e]
                                          [--rounds 12] [--probes]

Times `minksum sum cube.off sphere6.off -o S.off` (the first row of bench/e2e.py, whose files it
expects in --work: run `make bench-e2e` or bench/e2e.py once first) right after each of these,
interleaved over the rounds:

    qconvex o TI pts-a.txt TO FILE    Qhull's hull of the row's pairwise sums, written to a file
    qconvex o TI pts-a.txt TO /dev/null   the same, nothing written
    the same minksum sum              itself
    cp sphere6.off FILE               a 1 MB file written, nothing computed
    sleep 0.2                         nothing

FILE already exists (as in the benchmark's rounds, where each contender writes over its output of the
round before).  Each `minksum sum` is timed as bench/e2e.py times a contender (spawn to exit, wall
clock); the medians and quartiles are printed per predecessor.  That is what makes bench/e2e.py
reverse the order of its contenders every other round.

With --probes, two small programs are timed after each predecessor as well, each from inside (its own
start-up excluded), to tell where a slower run loses its time:

    huge pages   four fresh 2 MiB pages of anonymous memory, advised MADV_HUGEPAGE (as minksum's heap
                 is), first touched one after the other: the milliseconds of each first touch
    cpu          a fixed loop of Python arithmetic, touching no new memory
"""

import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from e2e import contender_args, run_process, use_spawn  # noqa: E402


# The probes: Python programs that print the seconds of what they time.
HUGE_PAGES = """
import ctypes, mmap, time
n, huge = 4, 2 << 20
m = mmap.mmap(-1, (n + 1) * huge, flags=mmap.MAP_PRIVATE | mmap.MAP_ANONYMOUS)  # (a shared mapping would be shmem)
off = -ctypes.addressof(ctypes.c_char.from_buffer(m)) % huge
m.madvise(mmap.MADV_HUGEPAGE, off, n * huge)
ts = []
for i in range(n):
    t = time.perf_counter()
    for j in range(0, huge, 4096):
        m[off + i * huge + j] = 1
    ts.append(time.perf_counter() - t)
print(" ".join(repr(t) for t in ts))
"""
CPU = """
import time
t = time.perf_counter()
x = 0
for i in range(300000):
    x += i * i % 7
print(repr(time.perf_counter() - t))
"""


def probe(code):
    """Run a probe in a fresh interpreter: the seconds it printed."""
    out = subprocess.run([sys.executable, "-c", code], stdout=subprocess.PIPE, check=True, text=True).stdout
    return [float(x) for x in out.split()]


def quartiles(ts):
    q = statistics.quantiles(ts, n=4) if len(ts) > 1 else [ts[0]] * 3
    return "median %6.2f ms, quartiles %6.2f-%6.2f ms" % (1e3 * statistics.median(ts), 1e3 * q[0], 1e3 * q[2])


def main():
    ap = contender_args(__doc__, 12)
    ap.add_argument("--probes", action="store_true", help="also time the huge-page and cpu probes after each")
    args = ap.parse_args()
    use_spawn(args)
    W = lambda name: os.path.join(args.work, name)  # noqa: E731
    for need in ("cube.off", "sphere6.off", "pts-a.txt"):
        if not os.path.exists(W(need)):
            raise SystemExit("predecessor: %s is missing: run `make bench-e2e` first" % W(need))
    out = W("predecessor-out")
    os.makedirs(out, exist_ok=True)
    ms = [args.minksum, "sum", W("cube.off"), W("sphere6.off"), "-o", os.path.join(out, "sum.off")]
    before = [
        ("qconvex TO a file", [args.qconvex, "o", "TI", W("pts-a.txt"), "TO", os.path.join(out, "qconvex.off")]),
        ("qconvex TO /dev/null", [args.qconvex, "o", "TI", W("pts-a.txt"), "TO", "/dev/null"]),
        ("itself", ms),
        ("cp of a 1 MB file", ["cp", W("sphere6.off"), os.path.join(out, "copy.off")]),
        ("sleep 0.2", ["sleep", "0.2"]),
    ]
    for _, cmd in before + [("", ms)]:  # every output file exists before the first timed round
        if run_process(cmd)[2] != 0:
            raise SystemExit("predecessor: %s failed" % " ".join(cmd))
    times = {name: [] for name, _ in before}
    pages = {name: [[] for _ in range(4)] for name, _ in before}
    cpu = {name: [] for name, _ in before}
    for r in range(args.rounds):
        for name, cmd in before:
            run_process(cmd)
            t, rss, rc, _, err = run_process(ms)
            if rc != 0:
                raise SystemExit("predecessor: %s failed (%d): %s" % (" ".join(ms), rc, err.strip()))
            times[name].append(t)
            if args.probes:
                run_process(cmd)
                for i, t in enumerate(probe(HUGE_PAGES)):
                    pages[name][i].append(t)
                run_process(cmd)
                cpu[name].append(probe(CPU)[0])
    print("minksum sum cube.off sphere6.off -o S.off, %d rounds, by the process run just before:" % args.rounds)
    for name, ts in times.items():
        print("  after %-22s %s" % (name, quartiles(ts)))
    if args.probes:
        print("probes by the process run just before: huge pages (the four first touches together; the median of "
              "each) and cpu:")
        for name in times:
            total = [sum(ts) for ts in zip(*pages[name])]
            print("  after %-22s pages %s (%s ms); cpu %s" % (
                name, quartiles(total), " ".join("%.2f" % (1e3 * statistics.median(p)) for p in pages[name]),
                quartiles(cpu[name])))


if __name__ == "__main__":
    main()
