"""Test python.pip: the package installs the Python way, without the network.

In a copy of the sources (what setup.py's CMake build reads), from scratch:
  1. a fresh virtual environment that sees the system's packages (numpy,
     setuptools, wheel: Debian's), made by the interpreter under test;
  2. pip install --no-build-isolation --no-index SOURCE into it: setup.py
     configures CMake for the extension alone and builds it;
  3. the installed package, imported from outside the source tree, computes
     exact sums (counts and volumes known in closed form), convex and not;
  4. python3 -m build --no-isolation --wheel, then the same with a source
     distribution first (a wheel built from the sdist: MANIFEST.in holds what
     the build needs); each wheel holds the module and the package, and the
     wheel from the sdist, installed over the first install, computes again.

Usage: check_pip.py --source DIR --work DIR [--python PY] [--cmake-args ARGS]
"""

import argparse
import os
import shutil
import subprocess
import sys
import tarfile
import zipfile

# What setup.py's build reads; the rest of the repository (the command, the
# web pages, the tests) stays out of the copy.
COPIED = ["CMakeLists.txt", "MANIFEST.in", "README.md", "pyproject.toml", "setup.py", "cmake", "src", "python"]

CHECK = r'''
import os, sys, sysconfig
from fractions import Fraction
import minksum

site = os.path.realpath(sysconfig.get_paths()["platlib"])
where = os.path.realpath(minksum.__file__)
assert sys.prefix != sys.base_prefix, "not in the virtual environment"
assert where.startswith(site + os.sep), f"minksum imported from {where}, not from {site}"
assert os.path.realpath(minksum._minksum.__file__).startswith(site + os.sep), minksum._minksum.__file__

# [-1, 1]^3 + [-1/2, 1/2]^3 = [-3/2, 3/2]^3
s = minksum.minkowski_sum("cube", "cube@scale:1/2")
assert (s.num_vertices, s.num_edges, s.num_facets) == (8, 12, 6), (s.num_vertices, s.num_edges, s.num_facets)
assert s.volume() == 27, s.volume()
assert sorted(s.planes()) == sorted([(2, 0, 0, 3), (-2, 0, 0, 3), (0, 2, 0, 3), (0, -2, 0, 3),
                                     (0, 0, 2, 3), (0, 0, -2, 3)]), s.planes()
t = minksum.minkowski_sum(minksum.load("cube"), minksum.load("tetra"))
assert t.volume() == Fraction(176, 3), t.volume()

# The tube ([-1, 1]^3 less a square hole of side 1 along z) + [-1/4, 1/4]^3:
# [-5/4, 5/4]^3 less a hole of side 1/2, volume (5/2)^3 - (1/2)^2 (5/2) = 15, genus 1.
ts = minksum.minkowski_sum(minksum.Solid.load("tube"), "cube@scale:1/4")
assert isinstance(ts, minksum.SolidSum), type(ts)
assert ts.volume() == 15, ts.volume()
assert ts.stats["genus"] == 1 and ts.shells == 1, (ts.stats["genus"], ts.shells)
print("installed in", os.path.dirname(where))
'''


def run(cmd, **kw):
    print("+", " ".join(c if "\n" not in c else "<the check>" for c in cmd), flush=True)
    subprocess.run(cmd, check=True, **kw)


def check_wheel(path):
    names = zipfile.ZipFile(path).namelist()
    module = [n for n in names if n.startswith("minksum/_minksum") and n.endswith(".so")]
    for want in ("minksum/__init__.py", "minksum/dask.py", "minksum/_minksum.pyi", "minksum/py.typed"):
        assert want in names, f"{path}: no {want} in {names}"
    assert len(module) == 1, f"{path}: expected one extension module, found {module}"
    assert any(n.endswith(".dist-info/METADATA") for n in names), f"{path}: no METADATA"
    assert "-cp3" in os.path.basename(path) and "linux" in os.path.basename(path), \
        f"{path}: not a platform wheel (the extension was not seen by setuptools)"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--source", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--python", default=sys.executable)
    ap.add_argument("--cmake-args", default="")
    args = ap.parse_args()

    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    src = os.path.join(work, "src")
    os.makedirs(src)
    for name in COPIED:
        a, b = os.path.join(args.source, name), os.path.join(src, name)
        if os.path.isdir(a):
            shutil.copytree(a, b, ignore=shutil.ignore_patterns("__pycache__", "*.so", "*.egg-info"))
        else:
            shutil.copy2(a, b)

    env = dict(os.environ, CMAKE_ARGS=args.cmake_args, PIP_DISABLE_PIP_VERSION_CHECK="1", PIP_NO_INPUT="1",
               PYTHONDONTWRITEBYTECODE="1", TMPDIR=os.path.join(work, "tmp"))
    env.pop("PYTHONPATH", None)
    env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    os.makedirs(env["TMPDIR"])

    venv = os.path.join(work, "venv")
    run([args.python, "-m", "venv", "--system-site-packages", venv], env=env)
    py = os.path.join(venv, "bin", "python")
    run([py, "-m", "pip", "install", "--no-build-isolation", "--no-index", src], env=env)
    run([py, "-c", CHECK], env=env, cwd=work)

    dist = os.path.join(work, "dist")
    run([py, "-m", "build", "--no-isolation", "--wheel", "--outdir", dist, src], env=env)
    wheels = [os.path.join(dist, f) for f in os.listdir(dist) if f.endswith(".whl")]
    assert len(wheels) == 1, wheels
    check_wheel(wheels[0])

    sdist_dist = os.path.join(work, "dist-sdist")
    run([py, "-m", "build", "--no-isolation", "--outdir", sdist_dist, src], env=env)
    sdists = [os.path.join(sdist_dist, f) for f in os.listdir(sdist_dist) if f.endswith(".tar.gz")]
    wheels = [os.path.join(sdist_dist, f) for f in os.listdir(sdist_dist) if f.endswith(".whl")]
    assert len(sdists) == 1 and len(wheels) == 1, os.listdir(sdist_dist)
    members = tarfile.open(sdists[0]).getnames()
    assert not any(m.endswith(".so") or "/tests/" in m for m in members), "the sdist holds built or test files"
    check_wheel(wheels[0])
    run([py, "-m", "pip", "install", "--no-index", "--force-reinstall", "--no-deps", wheels[0]], env=env)
    run([py, "-c", CHECK], env=env, cwd=work)

    shutil.rmtree(work)
    print("python.pip: pip install, the wheel and the sdist all build and compute")


if __name__ == "__main__":
    main()
