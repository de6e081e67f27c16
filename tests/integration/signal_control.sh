#!/usr/bin/env bash
# Integration: signals of a served network from outside. `vdrive run --network signal_bench.yaml`
# (a coupler, a digital input and output terminal, and an A6B whose home switch is wired to input
# channel 1) serves a veth end in a namespace; `vdrive signal` lists the file's named signals, sets
# the door contact and the A6B's home switch, and reads back what the wire carried; the A6B
# reports the home switch in 60FDh over CoE to a master; a value the switch cannot hold is exit 2.
#
# Usage: bash signal_control.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
BENCH="$(cd "$(dirname "$0")/../products/networks" && pwd)/signal_bench.yaml"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools

CONTROL="$WORK/control.sock"
start_line --network "$BENCH" --control "$CONTROL"
wait_for_line
sig() { "$VDRIVE" signal "$@" --control "$CONTROL"; }

out=$(sig list) || fail "signal list failed: $out"
echo "$out"
echo "$out" | grep -Pq '^door\tdi 0x6010:1\tBOOL\t0$' || fail "door is not listed as di 0x6010:1, BOOL, 0"
echo "$out" | grep -Pq '^x_home\tx.home\tconnection\t0$' || fail "x_home is not listed as x.home, 0"

out=$(sig set door on) || fail "signal set door failed: $out"
echo "$out" | grep -Pq '^door\tdi 0x6010:1\tBOOL\t1$' || fail "door did not read 1 after the set: $out"

sig set x.home 1 >/dev/null || fail "signal set x.home failed"
ok=""
for _ in $(seq 1 20); do   # the wire copies after the next firmware call
  [ "$(sig get 'di 0x6000:1' | cut -f3)" = "1" ] && { ok=1; break; }
  sleep 0.05
done
[ -n "$ok" ] || fail "the home switch did not reach input channel 1 through the wire"
echo "ok: x.home -> wire -> di 0x6000:1"

# The A6B is the fourth slave (position 3 for the master); 60FDh bit 2 is HOME.
out=$("$MASTER" sdo-read --iface "$M_IF" --slave 4 --index 0x60FD --type u32) || fail "sdo-read 60FDh failed: $out"
echo "$out"
v=$(echo "$out" | sed -n 's/.*(\([0-9]*\))$/\1/p')   # "60FD:00 = 0x00000004 (4)"
[ -n "$v" ] || fail "sdo-read printed no value: $out"
[ $(( v & 4 )) -eq 4 ] || fail "the A6B does not report HOME in 60FDh ($v)"

err=$(sig set x_home 2 2>&1); rc=$?
[ $rc -eq 2 ] || fail "an out-of-range value: exit $rc, expected 2 ($err)"
echo "$err" | grep -q "signal 'x_home': 2 is outside 0..1" || fail "the refusal does not name the range: $err"
err=$(sig get 'do 0x6000:1' 2>&1); rc=$?
[ $rc -eq 2 ] || fail "a missing entry: exit $rc, expected 2 ($err)"
echo "$err" | grep -q "has no object 6000h:01h" || fail "the refusal does not name the entry: $err"
echo "PASS"
