"""The Python side of bench_proximity --python-batch (python_batch.cpp runs it).

Loads the poses the bench wrote (--dir: t_a.npy, t_b.npy, and for each kind
of rotation, quaternion and matrix, <kind>_r_a.npy and <kind>_r_b.npy), builds
the two bodies as the bench did (--a and --b: catalog names, or mesh paths
whose hull is taken with --hull; their vertices must be the bench's,
a_vertices.npy and b_vertices.npy), and times minksum.collide_rigid and
minksum.distance_rigid on them: the best of --reps calls, each one call for
every pose, from the numpy arrays to the numpy arrays of results, on
--threads threads (0: None, one per hardware thread).  Prints
"<kind>.collide MS", "<kind>.distance MS" and "<kind>.same yes|no": whether
the statuses, distance, lower and upper equal the C++ batch's
(<kind>_collide.npy, <kind>_distance_status.npy, <kind>_distance.npy), bit
for bit.
"""

import argparse
import os
import sys
import timeit

import numpy as np

import minksum


def body(spec, hull):
    return minksum.RigidBody(minksum.load(spec, hull=True) if hull else spec)


def best(reps, call):
    """The least wall time of `reps` calls, in ms, and the answers of one more (not timed)."""
    return min(timeit.repeat(call, number=1, repeat=reps)) * 1e3, call()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dir", required=True)
    ap.add_argument("--a", required=True)
    ap.add_argument("--b", required=True)
    ap.add_argument("--hull", action="store_true")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--reps", type=int, default=3)
    args = ap.parse_args()

    def load(name):
        return np.load(os.path.join(args.dir, name + ".npy"))

    a, b = body(args.a, args.hull), body(args.b, args.hull)
    for x, name in ((a, "a"), (b, "b")):
        if not np.array_equal(x.polytope.vertices, load(name + "_vertices")):
            sys.exit("python_batch.py: the vertices of %s differ from the bench's" % name)
    threads = args.threads or None
    t_a, t_b = load("t_a"), load("t_b")
    for kind in ("quaternion", "matrix"):
        r_a, r_b = load(kind + "_r_a"), load(kind + "_r_b")
        collide_ms, codes = best(args.reps, lambda: minksum.collide_rigid(a, b, t_b, r_b, t_a, r_a, threads=threads))
        distance_ms, dist = best(args.reps, lambda: minksum.distance_rigid(a, b, t_b, r_b, t_a, r_a, threads=threads))
        cpp = load(kind + "_distance")
        same = (np.array_equal(codes, load(kind + "_collide"))
                and np.array_equal(dist["status"], load(kind + "_distance_status"))
                and all(np.array_equal(dist[key], cpp[:, k]) for k, key in enumerate(("distance", "lower", "upper"))))
        print("%s.collide %.6g" % (kind, collide_ms))
        print("%s.distance %.6g" % (kind, distance_ms))
        print("%s.same %s" % (kind, "yes" if same else "no"))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
