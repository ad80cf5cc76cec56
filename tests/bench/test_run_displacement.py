"""bench/nonconvex/run.py takes the largest displacement of a written file from
the command's --json report, whichever writer made the file: a convex result
(the convex path's sum, a convex part's erosion or opening) is written as the
hull of its rounded vertices, whose note on stderr words the displacement
differently from a rounded solid's, and the page once showed 0 for those rows."""
import importlib.util
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location(
    "nonconvex_run", os.path.join(HERE, "..", "..", "bench", "nonconvex", "run.py"))
run = importlib.util.module_from_spec(spec)
spec.loader.exec_module(run)


def check(got, want, what):
    if got != want:
        sys.exit("%s: displacement %r, expected %r" % (what, got, want))


# The rounding objects of `minksum sum|erode ... --binary --json`, as written.
check(run.displacement({"rounding": {"coordinates": 2161, "max_displacement": 1.3154591741595442e-08,
                                     "split": 0, "hull": True, "merged": 0, "dropped": 0}}),
      1.3154591741595442e-08, "convex result written as the hull of its rounded vertices")
check(run.displacement({"rounding": {"coordinates": 2743, "max_displacement": 1.4797488382518805e-08, "grid": 0}}),
      1.4797488382518805e-08, "rounded solid")
check(run.displacement({"rounding": None}), 0.0, "nothing rounded (null)")
check(run.displacement({}), 0.0, "no rounding object")
print("run.py displacement: 4 cases")
