#!/usr/bin/env bash
# Build and run the proximity benchmark (minksum vs libccd, and FCL when
# libfcl-dev is installed) and write its
# markdown section to docs/generated/benchmarks-proximity.md.
#   [MESHES=DIR] [POSES=N] [OUT=PAGE] bench/proximity/run.sh [BUILD_DIR] [extra bench_proximity arguments]
# BUILD_DIR defaults to build-bench-prox (Release, assertions off).  POSES
# (100000) is the number of poses of the rotation section and of the Python
# batch table; OUT (the page above) where the page goes; the extra arguments
# go to the translation tables (e.g. --steps 1000 --reps 10 for a quick check).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build-bench-prox}
shift || true
POSES=${POSES:-100000}
if [ -x "$BUILD/bin/bench_proximity" ] && compgen -G "$BUILD/python/minksum/_minksum*.so" >/dev/null &&
   [ "${REBUILD:-0}" = 0 ]; then
  :
else
  # The benchmark suite's bench/CMakeLists.txt adds this directory; when it is
  # absent, build this one benchmark on its own.  The Python module
  # (minksum_python) is the Python side of the Python batch table.
  cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DMINKSUM_ASSERTIONS=OFF -DMINKSUM_TESTS=OFF \
        -DMINKSUM_BENCH=ON >/dev/null
  cmake --build "$BUILD" -j 2 --target bench_proximity minksum_python
fi
out=${OUT:-docs/generated/benchmarks-proximity.md}
tmp=$(mktemp "$out.XXXXXX")
"$BUILD/bin/bench_proximity" --steps 100000 --reps 2000 "$@" > "$tmp"
# The rotation section; MESHES names a directory with the robot-link meshes
# (ur5e_forearm.stl, ur5e_upperarm.stl, franka_link1.stl) to add their hulls.
printf '\n' >> "$tmp"
"$BUILD/bin/bench_proximity" --rotation --poses "$POSES" ${MESHES:+--meshes "$MESHES"} >> "$tmp"
# The Python batch table (the same poses through the C++ batch and through
# minksum.collide_rigid / distance_rigid with /usr/bin/python3 and the
# module built in $BUILD/python) and the targets summary.
printf '\n' >> "$tmp"
"$BUILD/bin/bench_proximity" --python-batch --poses "$POSES" ${MESHES:+--meshes "$MESHES"} >> "$tmp"
mv "$tmp" "$out"
cat "$out"
