#!/usr/bin/env bash
# Virtual-time speed: simulated seconds per wall second for 1 and 8 drives in csp with
# plants, DC at 1 ms (bench_virtual_speed), with the machine and load; then, if valgrind is
# installed, the instructions per 1 ms cycle of one A6B (callgrind, the timed part only): a count
# that does not depend on the load, for before/after comparisons of optimisations.
# Usage: bash bench/virtual_speed/run.sh [BUILD_DIR] [SIM_SECONDS]
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=${1:-$HERE/../../build}
SIM=${2:-10}
BIN="$BUILD/bench/bench_virtual_speed"
[ -x "$BIN" ] || { echo "run.sh: $BIN not built (cmake --build build --target bench_virtual_speed)" >&2; exit 2; }
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(uname -r); $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$BIN" --drives 1 --drives 8 --seconds "$SIM"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
if command -v valgrind >/dev/null; then
  out=$(mktemp)
  # Warm-up (1000 cycles) and the timed 1000 cycles are both inside run_cycles: 2000 cycles.
  valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*run_cycles*' --callgrind-out-file="$out" \
    "$BIN" --drives 1 --seconds 1 >/dev/null 2>"$out.log"
  ir=$(sed -n 's/.*I *refs: *\([0-9,]*\).*/\1/p' "$out.log" | tr -d ,)
  echo "callgrind, 1 A6B: $((ir / 2000)) instructions per 1 ms cycle"
  rm -f "$out" "$out.log"
fi
