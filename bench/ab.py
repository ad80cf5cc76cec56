#!/usr/bin/python3
"""Two builds of the command, alternated, as whole processes.

    /usr/bin/python3 bench/ab.py NEW OLD [--rounds 60] [--cwd DIR] [--after CMD] [--faults] -- ARGS...

Runs `NEW ARGS...` and `OLD ARGS...` (two minksum executables, say a build
of the working tree and one of an earlier commit) alternately, the order
reversed every other round (NEW, OLD, OLD, NEW, ...), each timed from spawn
to exit (wall clock, output to /dev/null), and prints the quartiles of
each in milliseconds and the ratio of the medians.  Neither is charged for
running after the other only.  Both must succeed on the first round.

With --after CMD, CMD (split as a shell would, run in --cwd, untimed, its
output discarded) runs before every timed run: both builds are then timed
right after the same other program, say `--after "qconvex o TI pts-a.txt TO
qconvex-a.off"` in build-bench/e2e, the program bench/e2e.py alternates them
with (on a virtual machine the program run just before can change the next
one's time: docs/data-model.md).

With --faults, also prints what a first touch costs on this machine, from
inside this process: one byte read per 64 KiB of OLD's file through mmap
(the faults a program's code takes, one 64 KiB stretch at a time), and one
byte written per 4 KiB of fresh anonymous memory.  docs/data-model.md
("Page faults at start-up") quotes both.
"""

import argparse
import mmap
import os
import shlex
import statistics
import subprocess
import sys
import time


def quartiles(t):
    return [x * 1000 for x in statistics.quantiles(t, n=4)]


def fault_costs(path):
    """(file faults, ms) for 64 KiB steps through the file, (anon faults, ms) for 4 KiB steps."""
    with open(path, "rb") as f:
        size = os.fstat(f.fileno()).st_size
        m = mmap.mmap(f.fileno(), size, prot=mmap.PROT_READ)
        steps = range(0, size, 65536)
        t0 = time.perf_counter()
        s = 0
        for i in steps:
            s += m[i]
        file_ms = (time.perf_counter() - t0) * 1000
        m.close()
    n = 256
    a = mmap.mmap(-1, n * 4096)
    if hasattr(a, "madvise") and hasattr(mmap, "MADV_NOHUGEPAGE"):
        a.madvise(mmap.MADV_NOHUGEPAGE)
    t0 = time.perf_counter()
    for i in range(0, n * 4096, 4096):
        a[i] = 1
    anon_ms = (time.perf_counter() - t0) * 1000
    a.close()
    return (len(steps), file_ms), (n, anon_ms)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("new")
    ap.add_argument("old")
    ap.add_argument("--rounds", type=int, default=60)
    ap.add_argument("--cwd", default=None, help="run the commands in this directory")
    ap.add_argument("--after", default=None, help="a command run (untimed) before every timed run")
    ap.add_argument("--faults", action="store_true", help="also time first touches (see above)")
    argv = sys.argv[1:]
    if "--" not in argv:
        ap.error("give the command's arguments after --")
    cut = argv.index("--")
    o = ap.parse_args(argv[:cut])
    args = argv[cut + 1:]
    o.new, o.old = os.path.abspath(o.new), os.path.abspath(o.old)  # --cwd may move elsewhere
    if o.rounds < 2:
        ap.error("--rounds must be at least 2")
    after = shlex.split(o.after) if o.after else None
    times = {o.new: [], o.old: []}
    for r in range(o.rounds):
        order = [o.new, o.old] if r % 2 == 0 else [o.old, o.new]
        for exe in order:
            if after:
                q = subprocess.run(after, cwd=o.cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                if r == 0 and q.returncode != 0:
                    sys.exit(f"ab: {o.after} exited with {q.returncode}: {q.stderr.decode(errors='replace').strip()}")
            t0 = time.perf_counter()
            p = subprocess.run([exe] + args, cwd=o.cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            times[exe].append(time.perf_counter() - t0)
            if r == 0 and p.returncode != 0:
                sys.exit(f"ab: {exe} {' '.join(args)} exited with {p.returncode}: "
                         f"{p.stderr.decode(errors='replace').strip()}")
    qn, qo = quartiles(times[o.new]), quartiles(times[o.old])
    print(f"ab: {' '.join(args)} ({o.rounds} rounds each, alternated"
          + (f", each right after {o.after}" if after else "") + ")")
    print(f"  new {o.new}: quartiles {qn[0]:.2f} {qn[1]:.2f} {qn[2]:.2f} ms")
    print(f"  old {o.old}: quartiles {qo[0]:.2f} {qo[1]:.2f} {qo[2]:.2f} ms")
    print(f"  old median / new median: {qo[1] / qn[1]:.3f}")
    if o.faults:
        (nf, fms), (na, ams) = fault_costs(o.old)
        print(f"  first touches: {nf} faults through 64 KiB of {o.old}: {fms:.2f} ms "
              f"({fms * 1000 / nf:.1f} µs each); {na} fresh anonymous 4 KiB pages: {ams:.2f} ms "
              f"({ams * 1000 / na:.1f} µs each)")


if __name__ == "__main__":
    main()
