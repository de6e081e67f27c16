#!/usr/bin/env bash
# Capacity search: for each bus cycle T (1 ms, 250 us, 125 us), the largest number of
# drives one core carries with no missed sync deadline. Two stages per T:
#   1. virtual time (bench_capacity without --realtime, VCYCLES cycles per trial): N doubles from
#      1 while the 99.9th percentile of the per-cycle CPU time stays under T, then bisection
#      between the last N that passed and the first that failed;
#   2. real time (bench_capacity --realtime --rt-priority 90 on CPU $CPU, RTCYCLES cycles): the
#      N found must miss no deadline; while it misses, N drops by ~10% and runs again.
# 1 ms lines mix the three products; 250 us and 125 us lines are A6Bs (the only one of the three
# that runs cycles below 1 ms).
#
# Usage: bash bench/capacity/run.sh [BUILD_DIR]
# Environment: CYCLES_US (default "1000 250 125"), VCYCLES (default 5000), RTCYCLES (default
# 100000, the issue's count; 100 s per real-time trial at 1 ms), CPU (default 1), MAXN (256).
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=${1:-$HERE/../../build}
BIN="$BUILD/bench/bench_capacity"
CYCLES_US=${CYCLES_US:-1000 250 125}
VCYCLES=${VCYCLES:-5000}
RTCYCLES=${RTCYCLES:-100000}
CPU=${CPU:-1}
MAXN=${MAXN:-256}
[ -x "$BIN" ] || { echo "run.sh: $BIN not built (cmake --build build --target bench_capacity)" >&2; exit 2; }
[ "$(id -u)" -eq 0 ] || { echo "run.sh: the real-time stage needs root (SCHED_FIFO, mlockall)" >&2; exit 2; }

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(uname -r); $(date -u '+%Y-%m-%d %H:%M UTC')"

# Prints bench_capacity's line (with the load average) and succeeds when the trial passed.
virtual_ok() {  # N T
  local line p999
  line=$("$BIN" --drives "$1" --cycle-us "$2" --cycles "$VCYCLES" --cpu "$CPU") || { echo "  N=$1: did not run" >&2; return 1; }
  echo "  $line load $(cut -d' ' -f1 /proc/loadavg)" >&2
  p999=$(echo "$line" | sed -n 's/.* p999_us \([0-9.]*\) .*/\1/p')
  awk -v p="$p999" -v t="$2" 'BEGIN { exit !(p < t) }'
}
realtime_misses() {  # N T -> misses on stdout
  local line
  line=$("$BIN" --drives "$1" --cycle-us "$2" --cycles "$RTCYCLES" --cpu "$CPU" --realtime --rt-priority 90) || { echo 999999; return; }
  echo "  $line load $(cut -d' ' -f1 /proc/loadavg)" >&2
  echo "$line" | sed -n 's/.* misses \([0-9]*\) .*/\1/p'
}

for T in $CYCLES_US; do
  echo "cycle $T us: virtual-time search ($VCYCLES cycles per trial, p99.9 CPU time per cycle < $T us)"
  good=0; bad=0; n=1
  while [ $n -le "$MAXN" ]; do
    if virtual_ok $n "$T"; then good=$n; n=$((n * 2)); else bad=$n; break; fi
  done
  [ $bad -eq 0 ] && bad=$((MAXN + 1))
  while [ $((bad - good)) -gt 1 ]; do
    mid=$(((good + bad) / 2))
    if virtual_ok $mid "$T"; then good=$mid; else bad=$mid; fi
  done
  echo "cycle $T us: virtual-time bound $good drives; real-time check ($RTCYCLES cycles, SCHED_FIFO 90, CPU $CPU)"
  n=$good
  while [ "$n" -ge 1 ]; do
    misses=$(realtime_misses "$n" "$T")
    [ "$misses" -eq 0 ] && break
    n=$(( n * 9 / 10 < n - 1 ? n * 9 / 10 : n - 1 ))
  done
  echo "RESULT cycle $T us: $n drives with no missed deadline in $RTCYCLES real-time cycles"
done
