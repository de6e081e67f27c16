#!/usr/bin/env bash
# Integration: DDS telemetry between processes. vdrive serves a6b and ds5c1
# with --telemetry at 100 Hz in its own namespace (lo up: Fast DDS discovers over loopback UDP and
# carries data over shared memory) on a veth end; vdrive-master runs a csp sine from the other
# end. A second process, `vdrive telemetry --csv --events-csv`, subscribes in the same namespace
# until the requests are done and the master has finished, then gets Ctrl-C (each request client
# is a new DDS participant whose discovery can take a second or more: a fixed window missed
# events on a busy machine). While the axes move, `vdrive telemetry inject encoder_error --slave 1` goes through the
# control topic; then `plant-set` changes slave 2's external load, by position and by its station
# address (0x1002), a subscriber with `--slave 0x1002` gets slave 2's rows only, and refusals are
# checked.
# Asserts: per-axis samples at the configured rate (time stamps 10 ms apart; per axis count within
# the subscription window +-2 samples of 100 Hz; a rate check, not a performance one), the axes
# move (position changes), the fault takes effect (603Fh of slave 1 becomes non-zero in Op in the
# samples, alarm_raised and fault_injected events arrive), plant_set is acknowledged and its event
# arrives, a bad request exits 2 naming the problem, no vdrive in a domain exits 1.
#
# Usage: bash telemetry_dds.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools awk

DOMAIN=$(( $$ % 200 + 20 ))   # apart from other runs on this machine
RATE=100
in_ns() { ip netns exec "$NS" "$@"; }
tlm() { in_ns "$VDRIVE" telemetry "$@" --domain "$DOMAIN"; }

# start_line, with lo up in the namespace before vdrive starts (DDS needs an interface).
make_veth_line lo
in_ns "$VDRIVE" run --iface "$S_IF" --no-control --no-status --telemetry --telemetry-rate "$RATE" --domain "$DOMAIN" \
  --drive a6b --drive ds5c1 >"$WORK/vdrive.log" 2>&1 &
VDRIVE_PID=$!
wait_for_line

ip netns exec "$NS" "$VDRIVE" telemetry --domain "$DOMAIN" --duration 60 --csv "$WORK/axes.csv" --events-csv "$WORK/events.csv" -q \
  >"$WORK/tlm.out" 2>&1 &
TLM_PID=$!
"$MASTER" op --iface "$M_IF" --dc --cycle-us 1000 --reply-timeout-us 200000 --sine --frequency 0.5 --seconds 8 \
  >"$WORK/op.txt" 2>"$WORK/op.err" &
MASTER_PID=$!
sleep 2.5   # the line is in Op and moving
out=$(tlm inject encoder_error --slave 1 2>&1) || fail "telemetry inject failed: $out"
echo "$out"
[ "$out" = "fault 1 injected" ] || fail "telemetry inject printed '$out'"
out=$(tlm plant-set --slave 2 --external-load 0.25 2>&1) || fail "telemetry plant-set failed: $out"
[ "$out" = "slave 2: external load 0.25" ] || fail "plant-set printed '$out'"
out=$(tlm plant-set --slave 7 --external-load 1 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "there is no slave 7" || fail "plant-set on a missing slave: exit $rc, '$out'"
# A slave by its station address: the master gave slave 2 0x1002.
out=$(tlm plant-set --slave 0x1002 --external-load 0.5 2>&1) || fail "telemetry plant-set by address failed: $out"
[ "$out" = "slave 0x1002: external load 0.5" ] || fail "plant-set by address printed '$out'"
out=$(tlm plant-set --slave 0x1007 --external-load 1 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "no slave has station address 0x1007 (the line has 0x1001, 0x1002)" \
  || fail "plant-set on a missing address: exit $rc, '$out'"
ip netns exec "$NS" "$VDRIVE" telemetry --domain "$DOMAIN" --slave 0x1002 --count 20 --duration 10 --csv "$WORK/by_address.csv" -q \
  || fail "telemetry --slave 0x1002 exited $?"
rows=$(awk -F, 'NR > 1' "$WORK/by_address.csv" | wc -l)
others=$(awk -F, 'NR > 1 && ($2 != 2 || $NF != 4098)' "$WORK/by_address.csv" | wc -l)
[ "$rows" -eq 20 ] && [ "$others" -eq 0 ] || { cat "$WORK/by_address.csv"; fail "--slave 0x1002: $rows rows, $others not slave 2 at 0x1002"; }
out=$(tlm inject no_such_kind 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q 'unknown fault kind "no_such_kind"' || fail "unknown fault kind: exit $rc, '$out'"
wait "$MASTER_PID"
cat "$WORK/op.txt"
sleep 0.5   # the last events (the line leaving Op) reach the subscriber
kill -INT "$TLM_PID"
wait "$TLM_PID" || { cat "$WORK/tlm.out"; fail "vdrive telemetry exited $?"; }

head -1 "$WORK/axes.csv" | grep -q "^time_ns,slave,al_state,al_status_code,statusword,controlword,mode,position,velocity,torque,following_error,error_code," \
  || fail "CSV header: $(head -1 "$WORK/axes.csv")"
for s in 1 2; do
  # Count and spacing of one axis's samples: the window is first..last time stamp.
  read -r n first last gaps < <(awk -F, -v s=$s -v p=$((1000000000 / RATE)) '
    NR > 1 && $2 == s { if (n) { d = $1 - prev; if (d < p / 2 || d > 3 * p / 2) bad++ } else first = $1; prev = $1; n++ }
    END { print n, first, prev, bad + 0 }' "$WORK/axes.csv")
  expected=$(( (last - first) / (1000000000 / RATE) + 1 ))
  echo "slave $s: $n samples over $(( (last - first) / 1000000 )) ms, expected $expected at $RATE Hz, $gaps intervals off by more than half a period"
  [ "$n" -ge $(( 4 * RATE )) ] || fail "slave $s: only $n samples at $RATE Hz"
  [ $(( n - expected )) -le 2 ] && [ $(( expected - n )) -le 2 ] || fail "slave $s: $n samples, $expected expected at $RATE Hz"
  # Samples are due every period and stamped when the loop takes them (a few us late): an
  # interval off by half a period means one was skipped or doubled.
  [ "$gaps" -le $(( n / 50 )) ] || fail "slave $s: $gaps of $n sample intervals are not $((1000 / RATE)) ms (+-50 %)"
done
moves=$(awk -F, 'NR > 1 && $2 == 2 && $7 == 8 { v[$8] = 1 } END { print length(v) }' "$WORK/axes.csv")
[ "$moves" -gt 50 ] || fail "slave 2 did not move in csp ($moves positions)"
alarm=$(awk -F, 'NR > 1 && $2 == 1 && $3 == 8 && $12 != 0 { print $12; exit }' "$WORK/axes.csv")
[ -n "$alarm" ] || fail "603Fh of slave 1 never changed in Op after the encoder fault"
printf 'slave 1 603Fh after the fault: 0x%04X\n' "$alarm"
grep -q ",1,fault_injected,1,0,\"fault 1 encoder_error started\"" "$WORK/events.csv" || { cat "$WORK/events.csv"; fail "no fault_injected event"; }
grep -q ",1,alarm_raised,$alarm,0," "$WORK/events.csv" || { cat "$WORK/events.csv"; fail "no alarm_raised event with 603Fh $alarm"; }
grep -q ',2,plant_set,0,0,"external load 0.25"' "$WORK/events.csv" || { cat "$WORK/events.csv"; fail "no plant_set event"; }
grep -q ',2,plant_set,0,0,"external load 0.5"' "$WORK/events.csv" || { cat "$WORK/events.csv"; fail "no plant_set event for 0x1002"; }
grep -q ",1,al_state,8,4," "$WORK/events.csv" || { cat "$WORK/events.csv"; fail "no AL state event for Op"; }

# Nobody in another domain: exit 1, naming the topic and the domain.
other=$(( (DOMAIN + 1) % 233 ))
out=$(in_ns "$VDRIVE" telemetry clear all --domain "$other" --timeout 1 2>&1); rc=$?
[ $rc -eq 1 ] && echo "$out" | grep -q "no vdrive answered on rt/vdrive/control_request in DDS domain $other" || fail "no server: exit $rc, '$out'"
out=$(in_ns "$VDRIVE" telemetry --domain 999 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "domain 999" || fail "--domain 999: exit $rc, '$out'"
echo "PASS"
