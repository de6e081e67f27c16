#!/usr/bin/env bash
# Integration (shortened for CI): bench/soak/fault_soak.sh for 60 s — `vdrive run` with a6b,
# ds5c1, ds1000a in a network namespace behind a veth pair, `vdrive-master op --dc --sine
# --recover` at 1 kHz on the other end — injects every fault kind of the soak once (wire drops,
# corruption, a cut wire, a cable break that heals, a missing working counter, a lost SYNC, a drive
# alarm on each product, a jam, a load change; then the SII error and the mailbox losses): each
# must have its documented reaction, the line must be back in Op with every drive enabled within
# 5 s after each, vdrive must still run and its resident memory stay within 256 KiB of its value
# 10 s after Op. The hour-long run and its results: docs/reliability.md.
#
# Usage: bash fault_soak_short.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u
BUILD=${2:?build directory}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
INTERVAL=2 bash "$(dirname "$0")/../../bench/soak/fault_soak.sh" 60 "$BUILD" "$OUT"
