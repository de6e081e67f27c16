#!/usr/bin/env bash
# Integration: `vdrive run` serves a6b, ds5c1, ds1000a inside a network namespace on one end of a
# veth pair; `vdrive-master scan --state preop --json` on the other end (root namespace) must find
# the three drives with their manuals' identities at 0x1001..0x1003 in Pre-Op, and tshark must
# decode every captured frame without "Malformed" or error-level expert info.
#
# Usage: bash scan_three_slaves.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools tshark python3

start_line --drive a6b --drive ds5c1 --drive ds1000a
start_capture "$WORK/scan.pcapng"
wait_for_line --state preop --json
cp "$WORK/scan.out" "$WORK/scan.json"
cat "$WORK/scan.json"

stop_capture

# Identities from the manuals: A6B 1018h (vendor 066Fh), DS5C1 1018h (00000556h/10305070h),
# DS1000A-EC 1018h (00000973h/00004A39h).
python3 - "$WORK/scan.json" <<'PY' || fail "scan result wrong"
import json, sys
scan = json.load(open(sys.argv[1]))
expected = [("0x1001", "0x0000066F", "0x60380005"),
            ("0x1002", "0x00000556", "0x10305070"),
            ("0x1003", "0x00000973", "0x00004A39")]
slaves = scan["slaves"]
assert len(slaves) == 3, f"{len(slaves)} slaves"
# Positions from 1, as every command takes them; parent 0 is the master.
assert [s["position"] for s in slaves] == [1, 2, 3], slaves
assert [s["parent"] for s in slaves] == [0, 1, 2], slaves
for s, (station, vendor, product) in zip(slaves, expected):
    assert s["station"] == station, s
    assert s["vendor_id"] == vendor, s
    assert s["product_code"] == product, s
    assert s["state"] == "Pre-Op", s
    assert not s["al_error"], s
    assert s["name"], s
assert scan["state_reached"] is True
print("scan: 3 slaves, identities and Pre-Op as expected")
PY

frames=$(tshark -r "$WORK/scan.pcapng" 2>/dev/null | wc -l)
[ "$frames" -gt 0 ] || fail "nothing captured"
if tshark -r "$WORK/scan.pcapng" -V 2>/dev/null | grep -q "Malformed"; then
  tshark -r "$WORK/scan.pcapng" 2>/dev/null | grep Malformed | head
  fail "tshark found malformed frames"
fi
expert=$(tshark -r "$WORK/scan.pcapng" -q -z expert,error 2>/dev/null)
if echo "$expert" | grep -q "Errors ("; then
  echo "$expert"
  fail "tshark reports error-level expert info"
fi
echo "tshark: $frames frames, no malformed frames, no expert errors"
echo "PASS"
