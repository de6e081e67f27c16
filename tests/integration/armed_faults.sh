#!/usr/bin/env bash
# Integration: a network file's armed fault. `vdrive run --network armed_fault.yaml` (an A6B whose
# encoder fails 300 ms after serving starts) serves a veth end in a namespace; the fault is logged
# with the file's line, listed by `vdrive fault list`, the drive reports its alarm in 603Fh to a
# master over CoE, and vdrive logs the alarm by name and the AL state changes. A fault the file
# cannot arm is refused before serving, exit 2.
#
# Usage: bash armed_faults.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
FILE="$(cd "$(dirname "$0")/../products/networks" && pwd)/armed_fault.yaml"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools

printf 'slaves:\n  - {name: x, device: a6b}\nfaults:\n  - {kind: jam, slave: y}\n' >"$WORK/bad.yaml"
err=$("$VDRIVE" run --iface lo --no-control --network "$WORK/bad.yaml" 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] || fail "an unknown slave in faults: exit $rc, expected 2 ($err)"
echo "$err" | grep -q "bad.yaml:4: faults\[0\].slave: no slave 'y'" || fail "the mistake is not named: $err"
echo "ok: $err"

CONTROL="$WORK/control.sock"
start_line --network "$FILE" --control "$CONTROL"
wait_for_line
sleep 0.6
out=$("$VDRIVE" fault list --control "$CONTROL") || fail "fault list failed: $out"
echo "$out"
echo "$out" | grep -q "encoder_error" || fail "the armed fault is not active"
grep -q "armed_fault.yaml:5: armed fault 1 (encoder_error slave 1)" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "the armed fault is not logged with its line"; }
out=$("$MASTER" sdo-read --iface "$M_IF" --slave 1 --index 0x603F --type u16) || fail "sdo-read 603Fh failed: $out"
echo "$out"
code=$(echo "$out" | sed -n 's/.*(\([0-9]*\))$/\1/p')   # "603F:00 = 0xFF15 (65301)"
[ -n "$code" ] || fail "sdo-read printed no value: $out"
[ "$code" -ne 0 ] || fail "the A6B reports no alarm after its encoder failed"
# vdrive run logs what happens on the line at info level: the alarm by the product's name, AL
# state changes a master asks for.
grep -q "slave 1 @0x1001 a6b: alarm 21.0 Encoder communication disconnect error protection (603Fh FF15h)" "$WORK/vdrive.log" \
  || { cat "$WORK/vdrive.log"; fail "the alarm is not logged by name"; }
"$MASTER" scan --iface "$M_IF" --state preop >/dev/null 2>&1 || fail "scan --state preop failed"
sleep 0.4
grep -q "slave 1 @0x1001 a6b: Init -> PreOp" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "the AL state change is not logged"; }
echo "PASS"
