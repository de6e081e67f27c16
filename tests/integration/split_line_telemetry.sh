#!/usr/bin/env bash
# Integration: DDS telemetry of a line over two processes (`vdrive run --processes 2 --telemetry`:
# slaves 1-2 in part 1, slave 3 in a child). Each part publishes its own slaves; a subscriber
# (`vdrive telemetry --csv --events-csv`) sees one line of three, as from one process: samples of
# slaves 1, 2 and 3 with station addresses 0x1001-0x1003, at the configured rate each. Requests on
# the control topic are taken by part 1 alone (one answer each): `vdrive telemetry inject` for
# slave 3 goes to part 2 through the run's router and answers with the run-wide id (fault 2);
# part 2's samples then show the ds1000a's over-voltage (603Fh FF05h) on slave 3, and its events
# say fault_injected (id 2) and alarm_raised at slave 3; `vdrive telemetry clear 2` ends it in
# part 2; a plant change for slave 3 is refused naming the processes.
#
# Usage: bash split_line_telemetry.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools awk

DOMAIN=$(( $$ % 200 + 22 ))   # apart from other runs on this machine
RATE=50
in_ns() { ip netns exec "$NS" "$@"; }
tlm() { in_ns "$VDRIVE" telemetry "$@" --domain "$DOMAIN"; }

# start_line, with lo up in the namespace before vdrive starts (DDS needs an interface).
make_veth_line lo
ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" --processes 2 --control "$WORK/control.sock" --no-status --telemetry \
  --telemetry-rate "$RATE" --domain "$DOMAIN" --drive a6b ds5c1 ds1000a >"$WORK/vdrive.log" 2>&1 &
VDRIVE_PID=$!
wait_for_line
grep -q "\[part 2\].*telemetry: DDS domain $DOMAIN, $RATE Hz, topics rt/vdrive/{axis_state,bus_state,events} (part 1 takes the requests)" \
  "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "part 2 does not publish telemetry"; }

# Not through in_ns: $! must be the subscriber itself, for the signal that ends it.
ip netns exec "$NS" "$VDRIVE" telemetry --domain "$DOMAIN" --duration 60 --csv "$WORK/axes.csv" --events-csv "$WORK/events.csv" -q \
  >"$WORK/tlm.out" 2>&1 &
TLM_PID=$!
MASTER_PID=""
trap '[ -n "$TLM_PID" ] && kill "$TLM_PID" 2>/dev/null; [ -n "$MASTER_PID" ] && kill "$MASTER_PID" 2>/dev/null; cleanup' EXIT
# The line in Op at 1 ms with DC for the whole test (a6b's 603Fh stays clean: no motion asked).
"$MASTER" op --iface "$M_IF" --dc --cycle-us 1000 --reply-timeout-us 200000 --cycles 8000 >"$WORK/op.txt" 2>"$WORK/op.err" &
MASTER_PID=$!
sleep 2
out=$(tlm inject over_voltage --slave 3 2>&1) || fail "telemetry inject for part 2's slave 3 failed: $out"
echo "inject at slave 3: $out"
[ "$out" = "fault 2 injected" ] || fail "part 2's first fault is not run-wide fault 2: '$out'"
sleep 1.5   # the alarm reaches the samples
out=$(tlm clear 2 2>&1) || fail "telemetry clear 2 failed: $out"
echo "clear 2: $out"
grep -q "\[part 2\].*fault 1 cleared" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "part 2 did not clear its fault 1 (run-wide 2)"; }
out=$(tlm plant-set --slave 3 --external-load 1 2>&1); rc=$?
echo "plant-set at slave 3: exit $rc, $out"
[ $rc -eq 2 ] && echo "$out" | grep -q "slave 3 is served by another process of this run" || fail "plant-set at slave 3: exit $rc, '$out'"
wait "$MASTER_PID"
MASTER_PID=""
sleep 0.5
kill -TERM "$TLM_PID"
wait "$TLM_PID" || { cat "$WORK/tlm.out"; fail "vdrive telemetry exited $?"; }
TLM_PID=""

# One line of three: every slave's samples, each with its station address, each at the rate.
for s in 1 2 3; do
  rows=$(awk -F, -v s="$s" 'NR > 1 && $2 == s' "$WORK/axes.csv" | wc -l)
  station=$(awk -F, -v s="$s" 'NR > 1 && $2 == s { print $NF; exit }' "$WORK/axes.csv")
  echo "slave $s: $rows samples, station $station"
  [ "$station" = $((0x1000 + s)) ] || fail "slave $s's samples have station $station"
  [ "$rows" -ge $((RATE * 6)) ] || fail "slave $s: only $rows samples at $RATE Hz"
done
awk -F, 'NR > 1 && $2 > 3' "$WORK/axes.csv" | grep -q . && fail "samples of a slave beyond the line's three"
awk -F, 'NR > 1 && $2 == 3 && $12 == 65285 { found = 1 } END { exit !found }' "$WORK/axes.csv" \
  || fail "slave 3's samples never show over-voltage 603Fh FF05h (65285)"
grep -qE '^[0-9]+,3,fault_injected,2,0,"fault 2 over_voltage started"' "$WORK/events.csv" \
  || { cat "$WORK/events.csv"; fail "no fault_injected event at slave 3 with run-wide id 2"; }
grep -qE '^[0-9]+,3,alarm_raised,65285,' "$WORK/events.csv" || { cat "$WORK/events.csv"; fail "no alarm_raised at slave 3"; }
grep -qE '^[0-9]+,0,fault_cleared,2,' "$WORK/events.csv" || { cat "$WORK/events.csv"; fail "no fault_cleared of run-wide fault 2"; }
echo "PASS"
