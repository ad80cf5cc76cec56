"""The Python package minksum through setuptools (pyproject.toml names this backend and holds the metadata).

The extension minksum._minksum is built by the project's own CMake: this file
configures the project for the extension alone (no command, no tests, no
benchmarks) in build-python/ beside this file and builds the one target
minksum_python, then hands the module to setuptools, which installs it with
the pure-Python part (python/minksum/).  Building needs what the C++ library
needs (a C++20 compiler, CMake, GMP, MPFR, CGAL, Boost) and pybind11 with the
interpreter's headers; on Debian, scripts/packages.txt lists them all.

Environment:
  CMAKE_ARGS                   more options for CMake, split as a shell would
                               (e.g. "-DMINKSUM_ASSERTIONS=OFF")
  CMAKE_BUILD_PARALLEL_LEVEL   the number of compile jobs (default: all cores)
"""

import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
# A direct child of the source root, as the usual build/ is: the objects are
# compiled from the same relative paths, so a compiler cache (ccache, with
# CCACHE_BASEDIR above the source) serves one build's objects to the other.
CMAKE_BUILD_DIR = os.path.join(ROOT, "build-python")


def project_version():
    """The version of project(minksum VERSION x.y.z) in CMakeLists.txt: one source of truth."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"project\(\s*minksum\s+VERSION\s+([0-9.]+)", f.read())
    if not m:
        raise RuntimeError("CMakeLists.txt: no project(minksum VERSION ...) line")
    return m.group(1)


class CMakeBuild(build_ext):
    """Builds minksum._minksum with CMake instead of compiling sources itself."""

    def build_extension(self, ext):
        if shutil.which("cmake") is None:
            raise RuntimeError("building minksum needs CMake 3.25 or newer on PATH (Debian: apt-get install cmake)")
        configure = [
            "cmake", "-S", ROOT, "-B", CMAKE_BUILD_DIR,
            "-DCMAKE_BUILD_TYPE=Release",
            "-DMINKSUM_PYTHON=ON",
            f"-DMINKSUM_PYTHON_EXECUTABLE={sys.executable}",
            "-DMINKSUM_CLI=OFF",
            "-DMINKSUM_TESTS=OFF",
            "-DMINKSUM_BENCH=OFF",
            "-DMINKSUM_STATIC_CLI=OFF",
        ] + shlex.split(os.environ.get("CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", CMAKE_BUILD_DIR, "--target", "minksum_python", "-j", jobs], check=True)

        # CMake assembles the package in build-python/python/minksum/, the
        # module named with this interpreter's suffix (.cpython-311-x86_64-linux-gnu.so).
        built = os.path.join(CMAKE_BUILD_DIR, "python", self.get_ext_filename(ext.name))
        if not os.path.isfile(built):
            raise RuntimeError(f"{built}: not built (are pybind11 and the headers of {sys.executable} installed? "
                               "the CMake output above says)")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)
        shutil.copymode(built, target)


setup(
    version=project_version(),
    package_dir={"": "python"},
    packages=["minksum"],
    package_data={"minksum": ["*.pyi", "py.typed"]},
    zip_safe=False,
    ext_modules=[Extension("minksum._minksum", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own staging directory, away from build/ (the usual CMake build tree).
    options={"build": {"build_base": os.path.join("build-python", "setuptools")}},
)
