#!/usr/bin/env bash
# Run each libFuzzer target for a set time: scripts/fuzz.sh BUILD_DIR SECONDS [TARGET...]
# (targets: off obj ply stl wrl trajectory vector solid_writer; default all).
#
# Each target starts from its committed seed corpus (tests/fuzz/corpus/NAME/,
# never modified) and the regression inputs (tests/fuzz/regressions/NAME/),
# and grows a working corpus in BUILD_DIR/fuzz-corpus/NAME/.  A crash, a
# sanitizer report, a violated property or an input taking more than 10 s
# stops the target; the input is saved in BUILD_DIR/fuzz-artifacts/NAME/ and
# the script exits 1 after the other targets ran.  Such an input belongs in
# tests/fuzz/regressions/NAME/ with the fix (the normal test suite reads every
# file there).
set -uo pipefail
build=${1:?usage: scripts/fuzz.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: scripts/fuzz.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(off obj ply stl wrl trajectory vector solid_writer)
root=$(cd "$(dirname "$0")/.." && pwd)
failed=()
for t in "${targets[@]}"; do
  exe=$build/bin/fuzz_$t
  [ -x "$exe" ] || exe=$build/tests/fuzz/fuzz_$t
  if [ ! -x "$exe" ]; then echo "fuzz.sh: no fuzz_$t in $build" >&2; exit 2; fi
  work=$build/fuzz-corpus/$t
  artifacts=$build/fuzz-artifacts/$t
  mkdir -p "$work" "$artifacts"
  seeds=("$root/tests/fuzz/corpus/$t")
  [ -d "$root/tests/fuzz/regressions/$t" ] && seeds+=("$root/tests/fuzz/regressions/$t")
  echo "== fuzz_$t: ${seconds} s"
  # -max_len: 64 KiB, enough for every header and several elements of each
  # format; -rss_limit_mb: an input that makes the reader allocate beyond
  # this is a finding too (counts that lie must be refused before allocating).
  if ! "$exe" "$work" "${seeds[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/" 2>"$build/fuzz-$t.log"; then
    failed+=("$t")
    tail -n 40 "$build/fuzz-$t.log" >&2
    echo "fuzz_$t FAILED; inputs in $artifacts/" >&2
  else
    grep -E "^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::new_units_added)" "$build/fuzz-$t.log" | tr '\n' ' '
    echo
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: findings in: ${failed[*]}" >&2
  exit 1
fi
