#!/usr/bin/env bash
# Integration: `vdrive run` serves a6b, ds5c1, ds1000a inside a network
# namespace on one end of a veth pair; `vdrive-master op --dc --cycle-us 1000 --cycles 10000` on
# the other end takes the line to Op with distributed clocks (1 ms is a cycle every product
# supports: A6B 125 us-10 ms, DS5C1 and DS1000A-EC from 1 ms) and must run 10,000 cycles with zero
# wrong working counters. The mailbox traffic (SDO uploads of 1C12h/1C13h, 1C32h writes) is
# captured and tshark must decode it (ecat_mailbox) without "Malformed" or error expert info.
#
# Usage: bash op_three_slaves.sh <path-to-vdrive> <build-dir> [cycle-us] [cycles].
# Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
CYCLE_US=${3:-1000}
CYCLES=${4:-10000}

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools tshark

start_line --rt-priority 80 --drive a6b --drive ds5c1 --drive ds1000a
start_capture "$WORK/op.pcapng"
wait_for_line

# --reply-timeout-us: on a shared, loaded host (CI, a build machine) veth delivery runs in
# ksoftirqd at normal priority and a reply can come tens of ms late even with SCHED_FIFO on both
# ends; a late reply is still checked for its working counter. OP_EXTRA adds options.
"$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us "$CYCLE_US" --cycles "$CYCLES" \
  --reply-timeout-us 200000 ${OP_EXTRA:-} >"$WORK/op.txt" 2>"$WORK/op.err"
rc=$?
cat "$WORK/op.txt" "$WORK/op.err"
[ $rc -eq 0 ] || fail "vdrive-master op exited $rc"
grep -Eq "^summary: $CYCLES cycles of $CYCLE_US us, working counter [0-9]+ expected, 0 wrong, 0 lost, 0 not all in Op" "$WORK/op.txt" \
  || fail "summary is not $CYCLES cycles with zero wrong working counters"

stop_capture

mailbox=$(tshark -r "$WORK/op.pcapng" -Y ecat_mailbox 2>/dev/null | wc -l)
[ "$mailbox" -gt 0 ] || fail "no mailbox traffic captured"
if tshark -r "$WORK/op.pcapng" -Y ecat_mailbox -V 2>/dev/null | grep -q "Malformed"; then
  fail "tshark found malformed mailbox frames"
fi
expert=$(tshark -r "$WORK/op.pcapng" -Y ecat_mailbox -q -z expert,error 2>/dev/null)
if echo "$expert" | grep -q "Errors ("; then
  echo "$expert"
  fail "tshark reports error-level expert info in mailbox traffic"
fi
# The whole capture too (process data, DC, state changes): cheap, and the same rule.
if tshark -r "$WORK/op.pcapng" -q -z expert,error 2>/dev/null | grep -q "Errors ("; then
  fail "tshark reports error-level expert info in the capture"
fi
echo "tshark: $mailbox mailbox frames decoded, none malformed, no expert errors in any frame"
echo "PASS"
