#!/usr/bin/env bash
# Build and run the proximity benchmark (minksum vs libccd, and FCL when
# libfcl-dev is installed) and write its
# markdown section to docs/generated/benchmarks-proximity.md.
#   [MESHES=DIR] bench/proximity/run.sh [BUILD_DIR] [extra bench_proximity arguments]
# BUILD_DIR defaults to build-bench-prox (Release, assertions off).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build-bench-prox}
shift || true
if [ -x "$BUILD/bin/bench_proximity" ] && [ "${REBUILD:-0}" = 0 ]; then
  :
else
  # The benchmark suite's bench/CMakeLists.txt adds this directory; when it is
  # absent, build this one benchmark on its own.
  cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DMINKSUM_ASSERTIONS=OFF -DMINKSUM_TESTS=OFF \
        -DMINKSUM_BENCH=ON >/dev/null
  cmake --build "$BUILD" -j 2 --target bench_proximity
fi
out=docs/generated/benchmarks-proximity.md
tmp=$(mktemp "$out.XXXXXX")
"$BUILD/bin/bench_proximity" --steps 100000 --reps 2000 "$@" > "$tmp"
# The rotation section; MESHES names a directory with the robot-link meshes
# (ur5e_forearm.stl, ur5e_upperarm.stl, franka_link1.stl) to add their hulls.
printf '\n' >> "$tmp"
"$BUILD/bin/bench_proximity" --rotation --poses 100000 ${MESHES:+--meshes "$MESHES"} >> "$tmp"
mv "$tmp" "$out"
cat "$out"
