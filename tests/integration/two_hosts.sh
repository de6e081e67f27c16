#!/usr/bin/env bash
# Integration: a line spread over two hosts, or virtual drives in front of real ones. Two network
# namespaces stand in for two machines: host A (the master's cable on one NIC, a second NIC
# cabled on) runs `vdrive run --iface IN --next-iface OUT` with a6b and ds5c1; host B, cabled to
# A's second NIC, runs `vdrive run --iface IN` with ds1000a, and stands for real slaves as well as
# for another vdrive. The master must see one line of three (identities as one process serves
# them, DC delays increasing along the line, Op with DC at 1 ms with 0 wrong working counters);
# with B's link down the line ends at A's last slave (2 slaves), and comes back with it.
#
# Usage: bash two_hosts.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
# shellcheck source=lib/split_line_checks.sh
. "$(dirname "$0")/lib/split_line_checks.sh"
require_tools python3

NS_B="vdtb-$$"
A_OUT="vdta$$"   # host A's second NIC
B_IN="vdtb$$"    # host B's NIC
B_PID=""
cleanup_both() {
  [ -n "$B_PID" ] && kill "$B_PID" 2>/dev/null && wait "$B_PID" 2>/dev/null
  ip netns del "$NS_B" 2>/dev/null
  cleanup
}
trap cleanup_both EXIT

slaves() { python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["slaves"]))' "$1"; }

# One process first: what the master should see.
start_line --drive a6b ds5c1 ds1000a
scan_line one
kill "$VDRIVE_PID"; wait "$VDRIVE_PID" 2>/dev/null

# The cable between the hosts.
ip netns add "$NS_B" || fail "cannot create namespace $NS_B"
ip link add "$A_OUT" type veth peer name "$B_IN" || fail "cannot create the veth between the hosts"
ip link set "$A_OUT" netns "$NS" && ip link set "$B_IN" netns "$NS_B" || fail "cannot move the veth ends"
ip -n "$NS" link set "$A_OUT" up
ip -n "$NS_B" link set "$B_IN" up
ip netns exec "$NS_B" "$VDRIVE" run --iface "$B_IN" --drive ds1000a --no-control >"$WORK/b.log" 2>&1 &
B_PID=$!
ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" --next-iface "$A_OUT" --drive a6b ds5c1 >"$WORK/vdrive.log" 2>&1 &
VDRIVE_PID=$!
scan_line two
diff "$WORK/one.txt" "$WORK/two.txt" || fail "over two hosts the line does not look as in one process"
expect_delays_increase "$WORK/scan.out" "over two hosts"
grep -q "the line goes on through $A_OUT (port 1 of slave 2; link up)" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "host A did not say where the line goes on"; }

expect_clean_op "op over two hosts"

# Host B unplugged: the line ends at host A's last slave; plugged in again: three.
ip -n "$NS_B" link set "$B_IN" down
sleep 0.1
wait_for_line --json
[ "$(slaves "$WORK/scan.out")" -eq 2 ] || { cat "$WORK/scan.out"; fail "with host B's link down the scan did not find 2 slaves"; }
for _ in $(seq 1 30); do grep -q "onward link down: the line ends at the last slave here" "$WORK/vdrive.log" && break; sleep 0.1; done
grep -q "onward link down: the line ends at the last slave here" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "host A did not log its onward link going down"; }
ip -n "$NS_B" link set "$B_IN" up
sleep 0.1
wait_for_line --json
[ "$(slaves "$WORK/scan.out")" -eq 3 ] || { cat "$WORK/scan.out"; fail "with host B's link up again the scan did not find 3 slaves"; }

kill -INT "$VDRIVE_PID"; wait "$VDRIVE_PID"; VDRIVE_PID=""
grep -Eq "onward through $A_OUT: [1-9][0-9]* frames sent on, [1-9][0-9]* came back" "$WORK/vdrive.log" \
  || { cat "$WORK/vdrive.log"; fail "host A's summary does not count the frames that went on and came back"; }
echo "PASS"
