#!/usr/bin/env bash
# Integration: `vdrive run --busy-poll-us 200 --cpu 0` (receive ring and time
# slice by default), and then `vdrive run --no-rx-ring --slice-us 200` (recvfrom, frames
# overtaking the firmware through rationed poll() peeks), and then `vdrive run --batch-steps-us 2000`
# (control steps batched at the bus's events), serve a6b, ds5c1, ds1000a as before —
# `vdrive-master op --dc` runs 2,000 cycles with zero wrong working counters against each — and
# with batched steps every drive also follows a 4 s csp sine — and
# `--cpu` naming a CPU that does not exist is refused with exit 2 and a one-line error naming the
# option. (What these options save is measured by bench/turnaround/run.sh, not here.)
# Usage: bash run_speed_options.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools

# 2,000 DC cycles in Op against the line now serving, with zero wrong working counters. $1 names it.
op_clean() {
  "$MASTER" op --iface "$M_IF" --dc --cycles 2000 --reply-timeout-us 200000 >"$WORK/op.txt" 2>"$WORK/op.err"
  local rc=$?
  tail -3 "$WORK/op.txt"
  [ $rc -eq 0 ] || { cat "$WORK/op.err" "$WORK/vdrive.log"; fail "$1: vdrive-master op exited $rc"; }
  grep -Eq "^summary: 2000 cycles of 1000 us, working counter [0-9]+ expected, 0 wrong, 0 lost, 0 not all in Op" "$WORK/op.txt" \
    || fail "$1: summary is not 2000 cycles with zero wrong working counters"
  echo "ok: $1"
}

start_line --no-control --busy-poll-us 200 --cpu 0 --drive a6b --drive ds5c1 --drive ds1000a
wait_for_line
op_clean "--busy-poll-us 200 --cpu 0"

kill "$VDRIVE_PID" && wait "$VDRIVE_PID" 2>/dev/null
ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" --no-control --no-rx-ring --slice-us 200 --drive a6b --drive ds5c1 \
  --drive ds1000a >"$WORK/vdrive.log" 2>&1 &
VDRIVE_PID=$!
wait_for_line
op_clean "--no-rx-ring --slice-us 200"

# Batched control steps: the steps wait for the bus's events (SYNC0, frames) and run there. The
# drives must follow the master's sine as they do with each step on time.
batched_sine() {
  kill "$VDRIVE_PID" && wait "$VDRIVE_PID" 2>/dev/null
  ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" --no-control --rt-priority 80 --batch-steps-us 2000 --drive a6b \
    --drive ds5c1 --drive ds1000a >"$WORK/vdrive.log" 2>&1 &
  VDRIVE_PID=$!
  wait_for_line
  grep -q "control steps batched within 2000 us" "$WORK/vdrive.log" || fail "--batch-steps-us 2000: the log does not say so"
  op_clean "--batch-steps-us 2000"
  "$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us 1000 --reply-timeout-us 200000 \
    --sine --revolutions 0.1 --frequency 0.5 --seconds 4 >"$WORK/sine.txt" 2>"$WORK/sine.err"
  rc=$?
  cat "$WORK/sine.txt" "$WORK/sine.err"
}
batched_sine
# As in cia402_sine.sh: a sine that failed only for the host runs once more.
if [ $rc -ne 0 ] && sine_failed_for_host "$WORK/sine.txt"; then
  echo "the master ran late or every alarm followed a host stall: the sine runs once more"
  batched_sine
fi
[ $rc -eq 0 ] || fail "--batch-steps-us 2000: vdrive-master op --sine exited $rc"
ok=$(grep -Ec "^slave [0-9]+ @0x[0-9A-F]{4} [^:]*: ok, " "$WORK/sine.txt")
[ "$ok" -eq 3 ] || fail "--batch-steps-us 2000: $ok of 3 drives followed the sine"
echo "ok: --batch-steps-us 2000, 3 drives followed the sine"

err=$(ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" --no-control --cpu 1000 --drive a6b 2>&1 >/dev/null)
rc=$?
[ $rc -eq 2 ] || fail "--cpu 1000 exited $rc, expected 2: $err"
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "--cpu 1000: error is not one line: $err"
echo "$err" | grep -q -- "--cpu 1000" || fail "--cpu 1000: error does not name the option: $err"
echo "ok: --cpu 1000 -> $err"
echo "PASS"
