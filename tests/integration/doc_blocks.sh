#!/usr/bin/env bash
# Integration: the command blocks the documents mark `<!-- runnable -->` run as written
# (tests/docs/doc_blocks.py), so the docs cannot rot: the quickstart's namespace, line, master,
# faults and clean-up; the telemetry document's line, master and subscriber; the plot example; and
# the others marked so. Needs root (the quickstart
# makes a network namespace and a veth pair, named as the document names them).
#
# Usage: bash doc_blocks.sh <path-to-vdrive> <build-dir>. Exit 77 = skipped.
set -u
BUILD=${2:?build directory}
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root (the quickstart's namespace and veth pair)"; exit 77; }
command -v python3 >/dev/null || { echo "SKIP: python3 not installed"; exit 77; }
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
# The quickstart and the telemetry document name their namespaces and veth pairs; one left from an
# earlier run would fail them.
clean_up() {
  pkill -f "vdrive run --netns vd --iface m2s" 2>/dev/null; ip link del m2m 2>/dev/null; ip netns del vd 2>/dev/null
  pkill -f "vdrive run --netns tdemo --iface tds" 2>/dev/null; ip link del tdm 2>/dev/null; ip netns del tdemo 2>/dev/null
}
clean_up
trap clean_up EXIT
python3 "$SOURCE/tests/docs/doc_blocks.py" "$SOURCE" "$BUILD"
