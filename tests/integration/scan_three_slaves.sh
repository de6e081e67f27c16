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

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

[ "$(id -u)" -eq 0 ] || skip "needs root (network namespaces, veth, raw sockets)"
for tool in ip tshark python3; do
  command -v "$tool" >/dev/null || skip "$tool not installed"
done
[ -x "$VDRIVE" ] || fail "vdrive not found at $VDRIVE"
[ -x "$MASTER" ] || fail "vdrive-master not found at $MASTER"

NS="vdt-$$"
M_IF="vdtm$$"          # master end, root namespace (IFNAMSIZ: at most 15 characters)
S_IF="vdts$$"          # drives' end, inside $NS
WORK=$(mktemp -d)
VDRIVE_PID=""
TSHARK_PID=""

cleanup() {
  # Everything this script made, whatever point it reached.
  [ -n "$TSHARK_PID" ] && kill "$TSHARK_PID" 2>/dev/null && wait "$TSHARK_PID" 2>/dev/null
  [ -n "$VDRIVE_PID" ] && kill "$VDRIVE_PID" 2>/dev/null && wait "$VDRIVE_PID" 2>/dev/null
  ip link del "$M_IF" 2>/dev/null
  ip netns del "$NS" 2>/dev/null
  rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

ip netns add "$NS" || fail "cannot create namespace $NS"
ip link add "$M_IF" type veth peer name "$S_IF" || fail "cannot create veth pair"
ip link set "$S_IF" netns "$NS" || fail "cannot move $S_IF into $NS"
ip link set "$M_IF" up
ip -n "$NS" link set "$S_IF" up

ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" --drive a6b --drive ds5c1 --drive ds1000a \
  >"$WORK/vdrive.log" 2>&1 &
VDRIVE_PID=$!

tshark -i "$M_IF" -f "ether proto 0x88a4" -w "$WORK/scan.pcapng" >"$WORK/tshark.log" 2>&1 &
TSHARK_PID=$!
for _ in $(seq 1 100); do   # tshark reports "Capturing on" once the capture runs
  grep -q "Capturing on" "$WORK/tshark.log" 2>/dev/null && break
  kill -0 "$TSHARK_PID" 2>/dev/null || { cat "$WORK/tshark.log"; fail "tshark did not start"; }
  sleep 0.1
done

# vdrive needs a moment to open its socket: retry the scan until it answers (or give up).
ok=""
for _ in $(seq 1 20); do
  kill -0 "$VDRIVE_PID" 2>/dev/null || { cat "$WORK/vdrive.log"; fail "vdrive run exited early"; }
  if "$MASTER" scan --iface "$M_IF" --state preop --json >"$WORK/scan.json" 2>"$WORK/scan.err"; then
    ok=1
    break
  fi
  sleep 0.25
done
[ -n "$ok" ] || { cat "$WORK/scan.err" "$WORK/vdrive.log"; fail "vdrive-master scan did not succeed"; }
cat "$WORK/scan.json"

sleep 0.5                     # let tshark write the last frames
kill -INT "$TSHARK_PID"; wait "$TSHARK_PID" 2>/dev/null; TSHARK_PID=""

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
