#!/usr/bin/env bash
# Integration: the test machine of issue 19 (tests/products/networks/machine.yaml: a coupler with a
# digital input, a digital output, an analog input and an analog output terminal and a junction on
# its E-bus; two A6B on the junction's port 3, a DS5C1 and the ESI servo on its port 2), served
# twice inside a network namespace: by `vdrive run --network machine.yaml`, then by
# `vdrive run --eni machine_eni.xml --esi-dir tests/products/esi`. Each time `vdrive-master scan`
# on the other end of the veth pair must find the ten slaves in the order a frame visits them and
# reconstruct the tree (parent, port, delay) from the receive times, and `vdrive-master op --dc`
# must run them in Op with zero wrong working counters.
#
# Usage: bash machine_bench.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
PRODUCTS="$(cd "$(dirname "$0")/../products" && pwd)"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools python3

check_scan() {  # $1: what serves the machine
  cp "$WORK/scan.out" "$WORK/scan.json"
  python3 - "$WORK/scan.json" "$1" <<'PY' || fail "$1: scan result wrong"
import json, sys
scan = json.load(open(sys.argv[1]))
slaves = scan["slaves"]
expected = ["0x044C2C52", "0x03F03052", "0x07D83052", "0x0C1E3052", "0x10063052", "0x04622C52",
            "0x60380005", "0x60380005", "0x10305070", "0x00000402"]
assert [s["product_code"] for s in slaves] == expected, [s["product_code"] for s in slaves]
# The terminals and the junction in a line on the coupler's E-bus (port 3); the two A6B behind
# the junction's port 3, the DS5C1 and the servo behind its port 2; 500 ns per hop and direction.
assert [s["parent"] for s in slaves] == [0, 1, 2, 3, 4, 5, 6, 7, 6, 9], [s["parent"] for s in slaves]
assert [s["parent_port"] for s in slaves] == [0, 3, 1, 1, 1, 1, 3, 1, 2, 1], [s["parent_port"] for s in slaves]
assert [s["delay_ns"] for s in slaves] == [0, 500, 1000, 1500, 2000, 2500, 3000, 3500, 5000, 5500], \
    [s["delay_ns"] for s in slaves]
assert all(s["state"] == "Pre-Op" and not s["al_error"] for s in slaves), slaves
assert scan["state_reached"] is True
print(sys.argv[2] + ": the ten slaves in frame order, the tree from the receive times, all in Pre-Op")
PY
}

run_op() {  # $1: what serves the machine
  "$MASTER" op --iface "$M_IF" --dc --cycle-us 1000 --cycles 2000 --reply-timeout-us 200000 \
    >"$WORK/op.txt" 2>"$WORK/op.err"
  local rc=$?
  cat "$WORK/op.txt" "$WORK/op.err"
  [ $rc -eq 0 ] || fail "$1: vdrive-master op exited $rc"
  grep -Eq "^summary: 2000 cycles of 1000 us, working counter [0-9]+ expected, 0 wrong, 0 lost, 0 not all in Op" "$WORK/op.txt" \
    || fail "$1: summary is not 2000 cycles with zero wrong working counters"
}

start_line --network "$PRODUCTS/networks/machine.yaml"
wait_for_line --state preop --json
check_scan "--network machine.yaml"
run_op "--network machine.yaml"

restart_line --eni "$PRODUCTS/networks/machine_eni.xml" --esi-dir "$PRODUCTS/esi"
wait_for_line --state preop --json
check_scan "--eni machine_eni.xml"
grep -q "analog_terminals.xml" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "the log does not say how the EL3102 was matched"; }
run_op "--eni machine_eni.xml"
echo "PASS"
