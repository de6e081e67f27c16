#!/usr/bin/env bash
# Integration: one line of three drives (a6b, ds5c1, ds1000a) served by two processes
# (`vdrive run --processes 2`: slaves 1-2 here, slave 3 in a child process behind a veth pair the
# run makes) must look to a master exactly as the same line served by one process: the same
# identities, station addresses and positions (`vdrive-master scan --json`), DC delays that
# increase along the line, and Op with DC at 1 ms with 0 wrong working counters. Faults through
# part 1's control socket reach every part (part_router.hpp): one for slave 3 acts in the child
# (its drive reports the alarm in 603Fh to the master, its log names its local slave 1), `fault
# list` shows both parts' faults with whole-line positions and run-wide ids, a station address
# finds the part that has it, clearing by id and --all reaches the right part. Then the child
# is killed: the first part loses link on its port 1 and closes the line there, so a scan finds
# two slaves, vdrive run names the part that ended, and a fault for it is an error naming the
# part, not a hang. At the end the run's veth pairs and the parts' control sockets are gone.
#
# Usage: bash split_line.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
# shellcheck source=lib/split_line_checks.sh
. "$(dirname "$0")/lib/split_line_checks.sh"
require_tools python3

DRIVES=(--drive a6b ds5c1 ds1000a)

start_line "${DRIVES[@]}"
scan_line one
[ "$(wc -l <"$WORK/one.txt")" -eq 3 ] || { cat "$WORK/one.json"; fail "one process: not 3 slaves"; }

CONTROL="$WORK/control.sock"
restart_line --processes 2 --control "$CONTROL" "${DRIVES[@]}"
scan_line two
diff "$WORK/one.txt" "$WORK/two.txt" || fail "two processes: the line does not look as in one process"
expect_delays_increase "$WORK/two.json" "in two processes (one process: $(scan_delays "$WORK/one.json"))"
grep -q "part 2 (slave 3) serves" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "no child part logged"; }

expect_clean_op "op over two processes"

# Faults through part 1's control socket reach every part. Part 2 has its own socket beside it.
[ -S "$WORK/control.part2.sock" ] || { ls -l "$WORK"; fail "part 2 has no control socket at $WORK/control.part2.sock"; }
fault() { "$VDRIVE" fault "$@" --control "$CONTROL" 2>&1; }
alarm_of_slave3() {
  "$MASTER" sdo-read --iface "$M_IF" --slave 3 --index 0x603F --type u16 2>&1 | sed -n 's/.*(\([0-9]*\))$/\1/p'
}
before=$(alarm_of_slave3)
[ -n "$before" ] || fail "sdo-read 603Fh of slave 3 printed no value"
out=$(fault inject over_voltage --slave 3) || fail "a fault for part 2's slave 3: '$out'"
[ "$out" = "fault 2 injected" ] || fail "part 2's first fault is not run-wide fault 2: '$out'"
out=$(fault inject overload --slave 2) || fail "a fault for part 1's slave 2: '$out'"
[ "$out" = "fault 1 injected" ] || fail "part 1's first fault is not run-wide fault 1: '$out'"
sleep 0.2
after=$(alarm_of_slave3)
echo "slave 3 603Fh: $before before the fault, $after after"
[ "$after" = "65285" ] || fail "slave 3 (ds1000a) does not report over-voltage FF05h (65285) in 603Fh: '$after' (before: $before)"
grep -q "\[part 2\].*fault 1 injected: over_voltage slave 1" "$WORK/vdrive.log" \
  || { cat "$WORK/vdrive.log"; fail "part 2 did not log the fault at its own slave 1"; }
grep -q "fault 2 injected in part 2 (slave 3): over_voltage slave 3" "$WORK/vdrive.log" \
  || { cat "$WORK/vdrive.log"; fail "part 1 did not log where the fault went"; }
out=$(fault list) || fail "fault list: '$out'"
echo "$out"
echo "$out" | grep -Pq "^1\toverload slave 2\t" || fail "list lacks part 1's fault 1 at slave 2"
echo "$out" | grep -Pq "^2\tover_voltage slave 3\t" || fail "list lacks part 2's fault as run-wide 2 at slave 3"
out=$(fault clear 2) || fail "fault clear 2: '$out'"
out=$(fault list) || fail "fault list after clear 2: '$out'"
echo "$out" | grep -q "slave 3" && fail "fault 2 still listed after clear 2: '$out'"
echo "$out" | grep -Pq "^1\toverload slave 2\t" || fail "clear 2 took part 1's fault too: '$out'"
out=$(fault clear 2); rc=$?
[ $rc -eq 2 ] && [ "$out" = "vdrive: error: no active fault 2" ] || fail "clearing fault 2 twice: exit $rc, '$out'"
# A station address part 1 does not have: the part that has it serves it (the master set 0x1003).
out=$(fault inject overload --slave 0x1003) || fail "a fault for station address 0x1003: '$out'"
[ "$out" = "fault 4 injected" ] || fail "part 2's second fault is not run-wide fault 4: '$out'"
fault list | grep -Pq "^4\toverload slave 3\t" || fail "the fault at 0x1003 is not listed at slave 3: '$(fault list)'"
out=$(fault inject overload --slave 0x1009); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "no part of this run's line has station address 0x1009" \
  || fail "an address no part has: exit $rc, '$out'"
out=$(fault clear --all) || fail "fault clear --all: '$out'"
[ "$out" = "2 fault(s) cleared" ] || fail "clear --all did not clear both parts' faults: '$out'"
[ "$(fault list)" = "no active faults" ] || fail "faults left after clear --all: '$(fault list)'"

# The second part ends: the line closes at slave 2.
child=$(pgrep -P "$VDRIVE_PID" -f "run --iface vd") || fail "no child process of vdrive run"
kill -9 "$child"
for _ in $(seq 1 40); do
  grep -q "part 2 (slave 3) ended" "$WORK/vdrive.log" && break
  sleep 0.1
done
grep -q "part 2 (slave 3) ended: killed by signal 9" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "the ended part was not named"; }
sleep 0.1  # the first part reads its port 1's link every 10 ms
wait_for_line --json
n=$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["slaves"]))' "$WORK/scan.out")
[ "$n" -eq 2 ] || { cat "$WORK/scan.out"; fail "after part 2 ended, scan finds $n slaves, not 2"; }
# Its faults are an error naming it, at once; part 1's own still work.
start=$(date +%s%N)
out=$(fault inject overload --slave 3); rc=$?
[ $rc -eq 1 ] && echo "$out" | grep -q "part 2 (slave 3) does not answer" || fail "a fault for the ended part: exit $rc, '$out'"
out=$(fault list); rc=$?
[ $rc -eq 1 ] && echo "$out" | grep -q "part 2 (slave 3) does not answer" || fail "list with the ended part: exit $rc, '$out'"
[ $(( ($(date +%s%N) - start) / 1000000 )) -lt 4000 ] || fail "the ended part's errors took over 4 s"
out=$(fault inject overload --slave 1) || fail "part 1's slave after part 2 ended: '$out'"

kill "$VDRIVE_PID"; wait "$VDRIVE_PID"; rc=$?; VDRIVE_PID=""
[ $rc -eq 1 ] || { cat "$WORK/vdrive.log"; fail "vdrive run with a part ended exited $rc, not 1"; }
left=$(ip -n "$NS" -o link show | grep -c " vd[0-9]*p" || true)
[ "$left" -eq 0 ] || { ip -n "$NS" link show; fail "the run's veth pairs were not removed"; }
[ ! -e "$CONTROL" ] && [ ! -e "$WORK/control.part2.sock" ] || { ls -l "$WORK"; fail "a control socket of the run was left behind"; }
echo "PASS"
