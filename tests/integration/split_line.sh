#!/usr/bin/env bash
# Integration: one line of three drives (a6b, ds5c1, ds1000a) served by two processes
# (`vdrive run --processes 2`: slaves 1-2 here, slave 3 in a child process behind a veth pair the
# run makes) must look to a master exactly as the same line served by one process: the same
# identities, station addresses and positions (`vdrive-master scan --json`), DC delays that
# increase along the line, and Op with DC at 1 ms with 0 wrong working counters. A fault for slave
# 3 through part 1's control socket is refused naming the other process. Then the child
# is killed: the first part loses link on its port 1 and closes the line there, so a scan finds
# two slaves, and vdrive run names the part that ended. At the end the run's veth pairs are gone.
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
wait_for_line --json
cp "$WORK/scan.out" "$WORK/one.json"
scan_identities "$WORK/one.json" >"$WORK/one.txt"
[ "$(wc -l <"$WORK/one.txt")" -eq 3 ] || { cat "$WORK/one.json"; fail "one process: not 3 slaves"; }

restart_line --processes 2 "${DRIVES[@]}"
wait_for_line --json
cp "$WORK/scan.out" "$WORK/two.json"
scan_identities "$WORK/two.json" >"$WORK/two.txt"
diff "$WORK/one.txt" "$WORK/two.txt" || fail "two processes: the line does not look as in one process"
expect_delays_increase "$WORK/two.json" "in two processes (one process: $(scan_delays "$WORK/one.json"))"
grep -q "part 2 (slave 3) serves" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "no child part logged"; }

expect_clean_op "op over two processes"

# Faults through part 1's control socket reach its own slaves; one for slave 3 says where it is.
out=$(ip netns exec "$NS" "$VDRIVE" fault inject --iface "$S_IF" overload --slave 3 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "slave 3 is served by another process of this run (--processes); faults reach this process's slaves, 1 to 2" \
  || fail "a fault for part 2's slave: exit $rc, '$out'"
out=$(ip netns exec "$NS" "$VDRIVE" fault inject --iface "$S_IF" overload --slave 2 --duration 10ms 2>&1) \
  || fail "a fault for part 1's slave 2: '$out'"

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

kill "$VDRIVE_PID"; wait "$VDRIVE_PID"; rc=$?; VDRIVE_PID=""
[ $rc -eq 1 ] || { cat "$WORK/vdrive.log"; fail "vdrive run with a part ended exited $rc, not 1"; }
left=$(ip -n "$NS" -o link show | grep -c " vd[0-9]*p" || true)
[ "$left" -eq 0 ] || { ip -n "$NS" link show; fail "the run's veth pairs were not removed"; }
echo "PASS"
