#!/usr/bin/env bash
# Integration: stored parameters survive `kill -9` at any moment of a 1010h store.
# `vdrive run --drive a6b` (the A6B has 1010h, docs/state-machine.md) keeps its parameter file in
# $VDRIVE_STATE_DIR. Generation 0 (6065h = 100000, 6067h = 1000) is stored first. Then, ITERATIONS
# times: generation i is written (6065h = 100000 + i, 6067h = 1000 + i, two SDO downloads), the
# store is requested (1010h:01 = "save" with `vdrive-master sdo-write`) and vdrive is killed with
# SIGKILL after a random delay within the time that request takes, so the kill lands before,
# during and after the file is written; vdrive is started again and must come up and answer, and
# both objects must hold one whole generation: the last stored one or the new one, never a mix and
# never the defaults (a torn file is ignored and would give defaults). The store writes a
# temporary file, fsyncs it and renames it over the old one (vdrive/firmware/coe/parameter_store.hpp).
# The unit test KilledAtAnyMomentOfASaveARestartLoadsOneWholeGeneration kills a saving process
# 60 times more tightly.
#
# Usage: bash store_kill9.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
# Environment: ITERATIONS (default 50).
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
ITERATIONS=${ITERATIONS:-50}

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools

export VDRIVE_STATE_DIR="$WORK/state"
sdo_write() { "$MASTER" sdo-write --iface "$M_IF" --slave 1 --type u32 --index "$1" "$2" >/dev/null 2>"$WORK/sdo.err"; }
# "6065:00 = 0x000186A1 (100001)" -> 100001
sdo_read() { "$MASTER" sdo-read --iface "$M_IF" --slave 1 --type u32 --index "$1" 2>"$WORK/sdo.err" | sed -n 's/.* = .*(\([0-9]*\))$/\1/p'; }
generation() {  # writes generation $1 (not stored)
  sdo_write 0x6065 $((100000 + $1)) && sdo_write 0x6067 $((1000 + $1)) || fail "writing generation $1: $(cat "$WORK/sdo.err")"
}
SAVE=0x65766173  # "save"

start_line --drive a6b
wait_for_line
generation 0
store() { "$MASTER" sdo-write --iface "$M_IF" --slave 1 --type u32 --index 0x1010 --sub 1 "$SAVE" >/dev/null 2>"$WORK/store.err"; }
start=$(date +%s%N)
store || fail "storing generation 0: $(cat "$WORK/store.err")"
took_us=$(( ($(date +%s%N) - start) / 1000 ))
ls "$VDRIVE_STATE_DIR"/a6b-*.params >/dev/null 2>&1 || fail "no parameter file in $VDRIVE_STATE_DIR after 1010h"
echo "a store request takes $took_us us from the command's start (scan, Pre-Op, download)"

committed=0
new=0 old=0
for i in $(seq 1 "$ITERATIONS"); do
  generation "$i"
  store &
  STORE_PID=$!
  # Uniform over the request's time: before, while and after vdrive writes the file.
  delay_us=$(( RANDOM * RANDOM % (took_us + 1) ))
  sleep "$(awk -v u="$delay_us" 'BEGIN { printf "%.6f", u / 1e6 }')"
  kill -KILL "$VDRIVE_PID"
  wait "$VDRIVE_PID" 2>/dev/null
  kill "$STORE_PID" 2>/dev/null
  wait "$STORE_PID" 2>/dev/null
  restart_line --drive a6b
  wait_for_line || fail "iteration $i: vdrive did not come up again"
  a=$(sdo_read 0x6065) b=$(sdo_read 0x6067)
  case "$a:$b" in [0-9]*:[0-9]*) ;; *) fail "iteration $i: reading 6065h/6067h failed: '$a' '$b' $(cat "$WORK/sdo.err")" ;; esac
  k=$((a - 100000))
  [ $((b - 1000)) -eq "$k" ] || fail "iteration $i: 6065h = $a and 6067h = $b are from two generations"
  if [ "$k" -eq "$i" ]; then
    new=$((new + 1)) committed=$i
  elif [ "$k" -eq "$committed" ]; then
    old=$((old + 1))
  else
    fail "iteration $i: generation $k loaded (6065h = $a), expected $committed (stored before) or $i (being stored)"
  fi
done
echo "PASS: $ITERATIONS kills during a 1010h store: $new restarts loaded the new generation, $old the one stored before; never a torn file or defaults"
