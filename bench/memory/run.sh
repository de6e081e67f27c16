#!/usr/bin/env bash
# Resident memory per drive: bench_memory for N = 1, 8, 64 drives (or the N given), one process
# each, then the per-drive slope between the smallest and the largest N, after start-up and in
# steady state in Op. Usage: bash bench/memory/run.sh [BUILD_DIR] [N...]
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=${1:-$HERE/../../build}
shift || true
SIZES=${*:-1 8 64}
BIN="$BUILD/bench/bench_memory"
[ -x "$BIN" ] || { echo "run.sh: $BIN not built (cmake --build build --target bench_memory)" >&2; exit 2; }
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(uname -r); $(date -u '+%Y-%m-%d %H:%M UTC'); load $(cut -d' ' -f1-3 /proc/loadavg)"
out=$(for n in $SIZES; do "$BIN" --drives "$n"; done)
echo "$out"
echo "$out" | awk '
  { n[NR] = $2; built[NR] = $6; op[NR] = $8; steady[NR] = $10 }
  END {
    if (NR < 2) exit
    d = n[NR] - n[1]
    printf "per drive (slope %d..%d drives): built %.0f KiB, in Op %.0f KiB, steady %.0f KiB\n", n[1], n[NR],
           (built[NR] - built[1]) / d, (op[NR] - op[1]) / d, (steady[NR] - steady[1]) / d
  }'
