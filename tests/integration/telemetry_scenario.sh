#!/usr/bin/env bash
# Integration: DDS telemetry while a scenario runs. `vdrive scenario run --veth
# --telemetry --telemetry-rate 100` runs data/telemetry_scenario.yaml in real time in its own
# namespace (lo up for DDS discovery); a second process, `vdrive telemetry --csv`, subscribes
# until the fault request has been answered (then Ctrl-C: a request client's DDS discovery can
# take a second or more, so a fixed window could end before the fault); meanwhile `vdrive telemetry inject encoder_error --slave 1` goes through the control topic.
# Asserts: per-axis samples at the configured rate (count within +-2 of 100 Hz over the window),
# slave 2 moves, 603Fh of slave 1 becomes non-zero in the samples, and the scenario passes — its
# own expectation is that slave 1's 603Fh becomes non-zero, so the fault took effect in the run.
#
# Usage: bash telemetry_scenario.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
SCENARIO="$(cd "$(dirname "$0")" && pwd)/data/telemetry_scenario.yaml"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools awk

DOMAIN=$(( $$ % 200 + 20 ))
RATE=100
in_ns() { ip netns exec "$NS" "$@"; }

ip netns add "$NS" || fail "cannot create namespace $NS"
ip -n "$NS" link set lo up
# The scenario makes its own veth pair inside the namespace (removed with it).
in_ns "$VDRIVE" scenario run "$SCENARIO" --veth --telemetry --telemetry-rate "$RATE" --domain "$DOMAIN" \
  >"$WORK/scenario.out" 2>"$WORK/scenario.err" &
SCENARIO_PID=$!
sleep 1
ip netns exec "$NS" "$VDRIVE" telemetry --domain "$DOMAIN" --duration 60 --csv "$WORK/axes.csv" -q >"$WORK/tlm.out" 2>&1 &
TLM_PID=$!
sleep 3
out=$(in_ns "$VDRIVE" telemetry inject encoder_error --slave 1 --domain "$DOMAIN" 2>&1) || fail "telemetry inject failed: $out"
[ "$out" = "fault 1 injected" ] || fail "telemetry inject printed '$out'"
sleep 1   # samples after the fault reach the subscriber
kill -INT "$TLM_PID"
wait "$TLM_PID" || { cat "$WORK/tlm.out"; fail "vdrive telemetry exited $?"; }
wait "$SCENARIO_PID"; rc=$?
cat "$WORK/scenario.out"
[ $rc -eq 0 ] || { cat "$WORK/scenario.err"; fail "the scenario failed (exit $rc)"; }
grep -q "telemetry: [1-9][0-9]* samples published, 0 dropped" "$WORK/scenario.err" || { cat "$WORK/scenario.err"; fail "no telemetry summary"; }

for s in 1 2; do
  read -r n first last < <(awk -F, -v s=$s 'NR > 1 && $2 == s { if (!n) first = $1; last = $1; n++ } END { printf "%d %s %s\n", n, first, last }' "$WORK/axes.csv")
  expected=$(( (last - first) / (1000000000 / RATE) + 1 ))
  echo "slave $s: $n samples over $(( (last - first) / 1000000 )) ms, expected $expected at $RATE Hz"
  [ "$n" -ge $(( 3 * RATE )) ] || fail "slave $s: only $n samples at $RATE Hz"
  [ $(( n - expected )) -le 2 ] && [ $(( expected - n )) -le 2 ] || fail "slave $s: $n samples, $expected expected at $RATE Hz"
done
moves=$(awk -F, 'NR > 1 && $2 == 2 && $7 == 8 { v[$8] = 1 } END { print length(v) }' "$WORK/axes.csv")
[ "$moves" -gt 50 ] || fail "slave 2 did not move in csp ($moves positions)"
alarm=$(awk -F, 'NR > 1 && $2 == 1 && $12 != 0 { print $12; exit }' "$WORK/axes.csv")
[ -n "$alarm" ] || fail "603Fh of slave 1 never changed in the telemetry after the encoder fault"
printf 'slave 1 603Fh after the fault: 0x%04X\n' "$alarm"

# --telemetry in virtual time is refused, naming the options it needs.
out=$("$VDRIVE" scenario run "$SCENARIO" --telemetry 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q -- "--telemetry needs a real-time run (--veth or --iface)" || fail "virtual --telemetry: exit $rc, '$out'"
echo "PASS"
