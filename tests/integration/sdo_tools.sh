#!/usr/bin/env bash
# Integration: `vdrive-master sdo-read`, `sdo-write` and `od-list` against `vdrive run` (a6b,
# ds5c1, ds1000a) on a veth pair: each drive's 1018h:01 is its vendor ID, 1008h its name, a write
# of 6060h reads back, an unknown object gives the CoE abort 06020000h and exit 1, a value out of
# the type's range is refused before anything is sent, od-list lists the dictionary with 1018h.
# --slave takes the position as scan prints it (1 = first) or the station address (0x1003); a
# slave the line does not have is exit 1 naming the ones it has, a malformed one exit 2.
#
# Usage: bash sdo_tools.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools

start_line --drive a6b --drive ds5c1 --drive ds1000a
wait_for_line

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
  expect 0 "^1018:01 = ${vendors[$n]} " sdo-read --iface "$M_IF" --slave $((n + 1)) --index 0x1018 --sub 1 --type u32
done
# A slave named by its station address, as scan prints it.
expect 0 "^1008:00 = DS1000A-EC$" sdo-read --iface "$M_IF" --slave 0x1003 --index 0x1008 --type string
expect 0 "^1008:00 = DS5C1$" sdo-read --iface "$M_IF" --slave 2 --index 0x1008 --type string
expect 0 "^6060:00 <- 0x08 \(8\)$" sdo-write --iface "$M_IF" --slave 1 --index 0x6060 --type i8 8
expect 0 "^6060:00 = 0x08 \(8\)$" sdo-read --iface "$M_IF" --slave 1 --index 0x6060 --type i8
expect 1 "SDO abort 0x06020000 at 5FFF:00" sdo-read --iface "$M_IF" --slave 3 --index 0x5FFF
expect 1 "300 is out of range for u8" sdo-write --iface "$M_IF" --slave 1 --index 0x6040 --type u8 300
expect 1 "there is no slave 4: the line has slaves 1 to 3" sdo-read --iface "$M_IF" --slave 4 --index 0x1000
expect 1 "no slave has station address 0x1009 \(the line has 0x1001, 0x1002, 0x1003\)" sdo-read --iface "$M_IF" --slave 0x1009 --index 0x1000
expect 2 "positions count from 1" sdo-read --iface "$M_IF" --slave 0 --index 0x1000
expect 2 "'two' names no slave" sdo-read --iface "$M_IF" --slave two --index 0x1000
expect 0 "^1018  RECORD" od-list --iface "$M_IF" --slave 3 --names
echo "PASS"
