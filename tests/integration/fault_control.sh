#!/usr/bin/env bash
# Integration: runtime fault control while `vdrive run` serves a real master.
# vdrive serves a6b, ds5c1, ds1000a in a namespace on a veth end with its control socket at
# $WORK/ctl/line.sock; `vdrive-master op` runs 3000 cycles of 1 ms on the other end. Once the
# master is in Op, `vdrive fault inject drop --probability 1 --duration 300ms` cuts the wire:
# `vdrive fault list` must show the fault, the master must report lost frames / wrong working
# counters, and the fault must be gone by itself after its duration. Then a fault without a
# duration is injected, listed and cleared by id, and one on --slave 0x1002 (the address the
# master set) lands on slave 2. Refusals: an unknown kind exits 2 naming the
# kind; no server exits 1 naming the socket path; a peer of another uid (nobody, via setpriv) is
# denied with exit 4, first by the socket's 0600 mode and then, with the mode opened up, by the
# server's SO_PEERCRED check.
#
# Usage: bash fault_control.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools setpriv stdbuf

CTL="$WORK/ctl/line.sock"
fault() { "$VDRIVE" fault "$@" --control "$CTL"; }

start_line --control "$CTL" --drive a6b --drive ds5c1 --drive ds1000a
wait_for_line

# The socket and its directory belong to the server's user alone.
[ "$(stat -c %a "$WORK/ctl")" = 700 ] || fail "control directory mode is $(stat -c %a "$WORK/ctl"), not 700"
[ "$(stat -c %a "$CTL")" = 600 ] || fail "control socket mode is $(stat -c %a "$CTL"), not 600"
out=$(fault list) || fail "fault list on an idle line failed: $out"
[ "$out" = "no active faults" ] || fail "fault list on an idle line: '$out'"

# 1. drop p=1 for 300 ms while the master runs in Op.
# Line-buffered, so "Op" shows in op.txt as soon as the master reaches it.
stdbuf -oL "$MASTER" op --iface "$M_IF" --cycle-us 1000 --cycles 3000 --reply-timeout-us 20000 \
  >"$WORK/op.txt" 2>"$WORK/op.err" &
MASTER_PID=$!
for _ in $(seq 1 100); do
  grep -q "^Op$" "$WORK/op.txt" && break
  sleep 0.1
done
grep -q "^Op$" "$WORK/op.txt" || { cat "$WORK/op.txt" "$WORK/op.err"; fail "vdrive-master op did not reach Op"; }
sleep 0.3
out=$(fault inject drop --probability 1 --duration 300ms) || fail "fault inject drop failed: $out"
echo "$out"
id=$(echo "$out" | sed -n 's/^fault \([0-9]*\) injected$/\1/p')
[ -n "$id" ] || fail "fault inject printed no id: '$out'"
listed=$(fault list)
echo "$listed"
echo "$listed" | grep -Eq "^$id	drop .*p=1 for 300000 us	for [0-9]+ms	[0-9]+ms left$" || fail "fault list does not show fault $id: '$listed'"
sleep 0.6
listed=$(fault list)
[ "$listed" = "no active faults" ] || fail "fault $id still listed after its 300 ms: '$listed'"
wait "$MASTER_PID"
rc=$?
cat "$WORK/op.txt" "$WORK/op.err"
[ $rc -ne 0 ] || fail "vdrive-master op exited 0 although the wire dropped every frame for 300 ms"
summary=$(grep "^summary:" "$WORK/op.txt") || fail "vdrive-master op printed no summary"
lost=$(echo "$summary" | sed -n 's/.* \([0-9]*\) lost.*/\1/p')
wrong=$(echo "$summary" | sed -n 's/.* \([0-9]*\) wrong.*/\1/p')
[ "${lost:-0}" -gt 0 ] && [ "${wrong:-0}" -gt 0 ] || fail "no lost frames / wrong working counters in '$summary'"
# Not all 3000: the loss ended when the fault did.
[ "$lost" -lt 2000 ] || fail "$lost of 3000 frames lost: the fault did not end after 300 ms"
echo "master saw the cut: $summary"

# 2. A fault until cleared: listed, cleared by id, gone.
out=$(fault inject delay --delay 2ms --direction to_master) || fail "fault inject delay failed: $out"
id=$(echo "$out" | sed -n 's/^fault \([0-9]*\) injected$/\1/p')
fault list | grep -Eq "^$id	delay .*master 2000000 ns	for .*	until cleared$" || fail "delay fault $id not listed: $(fault list)"
out=$(fault clear "$id") || fail "fault clear $id failed: $out"
[ "$(fault list)" = "no active faults" ] || fail "fault $id still listed after clear"
out=$(fault clear "$id" 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "no active fault $id" || fail "clearing a cleared fault: exit $rc, '$out'"
fault inject corrupt --probability 0.5 >/dev/null && fault inject reorder >/dev/null || fail "two wire faults"
[ "$(fault clear --all)" = "2 fault(s) cleared" ] || fail "fault clear --all did not clear 2"
"$MASTER" scan --iface "$M_IF" >/dev/null 2>&1 || fail "the line does not answer after clear --all"

# A slave named by the station address the master set (scan: 0x1001-0x1003) is found by position.
fault inject overload --slave 0x1002 >/dev/null || fail "overload on 0x1002"
fault list | grep -q "overload slave 2" || fail "0x1002 is not slave 2: $(fault list)"
[ "$(fault clear --all)" = "1 fault(s) cleared" ] || fail "fault clear --all did not clear the overload"
out=$(fault inject overload --slave 0x1009 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "no slave has station address 0x1009 (the line has 0x1001, 0x1002, 0x1003)" \
  || fail "overload on 0x1009: exit $rc, '$out'"
out=$(fault inject overload --slave 0 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "positions count from 1" || fail "overload on slave 0: exit $rc, '$out'"

# 3. Refusals.
out=$(fault inject wobble 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q 'unknown fault kind "wobble"' || fail "unknown kind: exit $rc, '$out'"
out=$(fault inject drop --probability 2 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q 'probability' || fail "probability 2: exit $rc, '$out'"
out=$(fault inject overload 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q '"slave" is missing' || fail "overload without slave: exit $rc, '$out'"
out=$(fault inject overload --slave 9 2>&1); rc=$?
[ $rc -eq 2 ] || fail "overload on slave 9 of 3: exit $rc, '$out'"
out=$("$VDRIVE" fault list --iface vdt-none 2>&1); rc=$?
[ $rc -eq 1 ] && echo "$out" | grep -q "vdt-none.sock" || fail "no server: exit $rc, '$out'"

# Another uid: the 0600 socket in a 0700 directory keeps it out ...
out=$(setpriv --reuid=nobody --regid=nogroup --clear-groups "$VDRIVE" fault list --control "$CTL" 2>&1); rc=$?
[ $rc -eq 4 ] || fail "uid nobody through the 0600 socket: exit $rc, '$out'"
# ... and with the modes opened up, the server's SO_PEERCRED check still does.
chmod 0755 "$WORK" "$WORK/ctl" && chmod 0666 "$CTL"
out=$(setpriv --reuid=nobody --regid=nogroup --clear-groups "$VDRIVE" fault inject drop --control "$CTL" 2>&1); rc=$?
[ $rc -eq 4 ] && echo "$out" | grep -q "may not control this vdrive" || fail "uid nobody past SO_PEERCRED: exit $rc, '$out'"
[ "$(fault list)" = "no active faults" ] || fail "the denied request injected a fault"

# The socket goes with the server.
kill "$VDRIVE_PID"; wait "$VDRIVE_PID"; VDRIVE_PID=""
[ ! -e "$CTL" ] || fail "control socket left behind after vdrive run exited"
grep -q "fault control on $CTL" "$WORK/vdrive.log" || fail "vdrive run did not log its control socket"
echo "PASS"
