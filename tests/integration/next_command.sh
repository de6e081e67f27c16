#!/usr/bin/env bash
# Integration (issue 24 item 7, as a user would): one `vdrive-master` command after another
# against `vdrive run` serving a6b, ds5c1, ds1000a on a veth pair. Each command is a new master
# that finds the line where the previous one left it: Pre-Op after sdo-read, Init after op. The
# next command must leave no drive in Fault: no 603Fh alarm, 6041h bit 3 clear, and no alarm in
# vdrive run's log. Before the fix, the scan's reset cleared the mailbox SyncManagers of slaves
# still in Pre-Op (A6B Err81.1, DS5C1 E-811, 603Fh FF51h) and `op --sine` left Op with the drives
# enabled (A6B Err88.2, DS5C1 E-882).
#
# Usage: bash next_command.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools

start_line --rt-priority 80 --drive a6b --drive ds5c1 --drive ds1000a
wait_for_line

# "603F:00 = 0x0000 (0)" -> 0
read_u16() {
  local out
  out=$("$MASTER" sdo-read --iface "$M_IF" --slave "$1" --index "$2" --type u16 2>&1) || fail "sdo-read $2 of slave $1: $out"
  echo "$out" | sed -n 's/.*(\([0-9]*\))$/\1/p'
}

# Every drive as the next command finds it; $1 says after what.
expect_no_fault() {
  local slave code status
  for slave in 1 2 3; do
    code=$(read_u16 "$slave" 0x603F)
    status=$(read_u16 "$slave" 0x6041)
    [ -n "$code" ] && [ -n "$status" ] || fail "$1: slave $slave: no value read"
    [ "$code" -eq 0 ] || fail "$1: slave $slave has 603Fh $(printf '%04Xh' "$code")"
    [ $((status & 0x0008)) -eq 0 ] || fail "$1: slave $slave is in Fault (6041h $(printf '%04Xh' "$status"))"
  done
  if grep -E "alarm|AL error" "$WORK/vdrive.log"; then
    fail "$1: vdrive run logged an alarm"
  fi
}

out=$("$MASTER" sdo-read --iface "$M_IF" --slave 1 --index 0x1018 --sub 1 --type u32) || fail "first sdo-read: $out"
echo "$out"
echo "$out" | grep -q "^1018:01 = 0x0000066F" || fail "1018h:01 of the A6B: $out"
expect_no_fault "after sdo-read (the line left in Pre-Op)"

# --rt-priority, --reply-timeout-us: as cia402_sine.sh and op_three_slaves.sh (a loaded host).
"$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us 1000 --reply-timeout-us 200000 \
  --sine --revolutions 0.1 --frequency 0.5 --seconds 2 >"$WORK/op.txt" 2>"$WORK/op.err"
rc=$?
cat "$WORK/op.txt" "$WORK/op.err"
[ $rc -eq 0 ] || fail "vdrive-master op --sine exited $rc"
expect_no_fault "after op --sine"
echo "PASS"
