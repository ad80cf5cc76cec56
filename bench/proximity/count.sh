#!/usr/bin/env bash
# Instructions per query (callgrind), which unlike wall-clock times do not
# depend on the machine's load: every pair and configuration of
# bench_proximity's table (bench_proximity --count) and its coherent
# trajectory (--count-trajectory).  Prints markdown tables on stdout.
#   bench/proximity/count.sh [BUILD_DIR] [N]
# BUILD_DIR: a build with -DMINKSUM_BENCH=ON and FCL (default build-bench);
# N: queries per loop (default 20; the trajectory has 100·N steps).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build-bench}
N=${2:-20}
BIN="$BUILD/bin/bench_proximity"
command -v valgrind >/dev/null || { echo "count.sh: valgrind is not installed" >&2; exit 1; }
[ -x "$BIN" ] || { echo "count.sh: $BIN not found (make bench builds it)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The inclusive instruction count of function $2 in callgrind output $1, per query.
per() {
  callgrind_annotate --inclusive=yes --threshold=100 "$1" 2>/dev/null |
    awk -v f="$2" -v n="$3" 'index($0, f "(") { gsub(",", "", $1); printf "%\047d", $1 / n; exit }'
}
pairs=("cube cube@rot:3" "sphere:2 sphere:2@rot:1" "random:50:1 random:50:2" "random:500:1 random:350:2"
       "sphere:4 sphere:4@rot:1")
configs=("separated 1.5" "touching 1" "near-touching out 1.000000001" "near-touching in 0.999999999" "penetrating 0.5")
echo "| pair | configuration | status | ours collide | GJK | ours distance | ours distance + exact |" \
     "+ lowest terms | FCL distance | ours depth | ours depth + exact | GJK+EPA |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for pr in "${pairs[@]}"; do
  set -- $pr
  for cf in "${configs[@]}"; do
    name=${cf% *}
    f=${cf##* }
    out=$(valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" "$BIN" --count "$1" "$2" "$f" "$N" 2>/dev/null)
    status=$(echo "$out" | sed -n 's/.*: \(separate\|touching\|penetrating\), .*/\1/p')
    echo "| $1 / $2 | $name | $status | $(per "$tmp/cg" count_ours_collide "$N") | $(per "$tmp/cg" count_ccd_gjk "$N") |" \
         "$(per "$tmp/cg" count_ours_distance "$N") | $(per "$tmp/cg" count_ours_distance_exact "$N") |" \
         "$(per "$tmp/cg" count_ours_distance_lowest "$N") |" \
         "$(per "$tmp/cg" count_fcl_distance "$N") |" \
         "$(per "$tmp/cg" count_ours_depth "$N") | $(per "$tmp/cg" count_ours_depth_exact "$N") |" \
         "$(per "$tmp/cg" count_ccd_epa "$N") |"
  done
done
echo
echo "| pair | steps | ours distance_points / step | FCL distance / step |"
echo "|---|---:|---:|---:|"
steps=$((100 * N))
for pr in "${pairs[@]}"; do
  set -- $pr
  valgrind --tool=callgrind --callgrind-out-file="$tmp/ct" "$BIN" --count-trajectory "$1" "$2" "$steps" >/dev/null 2>&1
  echo "| $1 / $2 | $steps | $(per "$tmp/ct" count_ours_trajectory "$steps") | $(per "$tmp/ct" count_fcl_trajectory "$steps") |"
done
