#!/usr/bin/env bash
# Integration: `vdrive-master sdo-read`, `sdo-write` and `od-list` against `vdrive run` (a6b,
# ds5c1, ds1000a) on a veth pair: each drive's 1018h:01 is its vendor ID, 1008h its name, a write
# of 6060h reads back, an unknown object gives the CoE abort 06020000h and exit 1, a value out of
# the type's range is refused before anything is sent, od-list lists the dictionary with 1018h.
#
# Usage: bash sdo_tools.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

[ "$(id -u)" -eq 0 ] || skip "needs root (network namespaces, veth, raw sockets)"
for tool in ip; do
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


ok=""
for _ in $(seq 1 20); do
  kill -0 "$VDRIVE_PID" 2>/dev/null || { cat "$WORK/vdrive.log"; fail "vdrive run exited early"; }
  if "$MASTER" scan --iface "$M_IF" >"$WORK/scan.txt" 2>&1; then ok=1; break; fi
  sleep 0.25
done
[ -n "$ok" ] || { cat "$WORK/scan.txt" "$WORK/vdrive.log"; fail "no line answers on $M_IF"; }

expect() {  # expect <exit> <stdout+stderr pattern> <args...>
  local want=$1 pattern=$2; shift 2
  out=$("$MASTER" "$@" 2>&1); rc=$?
  echo "\$ vdrive-master $*"; echo "$out"
  [ "$rc" -eq "$want" ] || fail "exit $rc (expected $want): vdrive-master $*"
  echo "$out" | grep -Eq "$pattern" || fail "output does not match '$pattern'"
}
vendors=(0x0000066F 0x00000556 0x00000973)
names=(MADLN15BE DS5C1 DS1000A-EC)
for n in 0 1 2; do
  expect 0 "^1018:01 = ${vendors[$n]} " sdo-read --iface "$M_IF" --slave $n --index 0x1018 --sub 1 --type u32
done
expect 0 "^1008:00 = DS5C1$" sdo-read --iface "$M_IF" --slave 1 --index 0x1008 --type string
expect 0 "^6060:00 <- 0x08 \(8\)$" sdo-write --iface "$M_IF" --slave 0 --index 0x6060 --type i8 8
expect 0 "^6060:00 = 0x08 \(8\)$" sdo-read --iface "$M_IF" --slave 0 --index 0x6060 --type i8
expect 1 "SDO abort 0x06020000 at 5FFF:00" sdo-read --iface "$M_IF" --slave 2 --index 0x5FFF
expect 1 "300 is out of range for u8" sdo-write --iface "$M_IF" --slave 0 --index 0x6040 --type u8 300
expect 1 "the line has 3 slaves" sdo-read --iface "$M_IF" --slave 3 --index 0x1000
expect 0 "^1018  RECORD" od-list --iface "$M_IF" --slave 2 --names
echo "PASS"
