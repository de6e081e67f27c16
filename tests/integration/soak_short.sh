#!/usr/bin/env bash
# Integration (shortened for CI): bench/soak/run.sh for 45 s — `vdrive run` with
# a6b, ds5c1, ds1000a in a network namespace behind a veth pair, `vdrive-master op --dc --sine` at
# 1 kHz on the other end — must end with no lost frames (master and vdrive counters), no wrong
# working counters, every slave in Op in every cycle, and vdrive's resident memory no more than
# 256 KiB above its value 5 s after Op. The hour-long run and its results: docs/performance.md.
#
# Usage: bash soak_short.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u
BUILD=${2:?build directory}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
INTERVAL=2 bash "$(dirname "$0")/../../bench/soak/run.sh" 45 "$BUILD" "$OUT"
