#!/usr/bin/env bash
# Integration: one line of three drives (a6b, ds5c1, ds1000a) served by two processes
# (`vdrive run --processes 2`: slaves 1-2 here, slave 3 in a child process behind a veth pair the
# run makes) must look to a master exactly as the same line served by one process: the same
# identities, station addresses and positions (`vdrive-master scan --json`), DC delays that
# increase along the line, and Op with DC at 1 ms with 0 wrong working counters. Then the child
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
require_tools python3

DRIVES=(--drive a6b ds5c1 ds1000a)

# Everything scan --json says of a slave but what depends on timing (delays) and state.
identities() {
  python3 -c '
import json, sys
for s in json.load(open(sys.argv[1]))["slaves"]:
    s.pop("delay_ns", None); s.pop("al_status", None); s.pop("al_status_code", None)
    print(json.dumps(s, sort_keys=True))' "$1"
}

delays() {
  python3 -c '
import json, sys
print(" ".join(str(s["delay_ns"]) for s in json.load(open(sys.argv[1]))["slaves"]))' "$1"
}

start_line "${DRIVES[@]}"
wait_for_line --json
cp "$WORK/scan.out" "$WORK/one.json"
identities "$WORK/one.json" >"$WORK/one.txt"
[ "$(wc -l <"$WORK/one.txt")" -eq 3 ] || { cat "$WORK/one.json"; fail "one process: not 3 slaves"; }

restart_line --processes 2 "${DRIVES[@]}"
wait_for_line --json
cp "$WORK/scan.out" "$WORK/two.json"
identities "$WORK/two.json" >"$WORK/two.txt"
diff "$WORK/one.txt" "$WORK/two.txt" || fail "two processes: the line does not look as in one process"
read -r d0 d1 d2 < <(delays "$WORK/two.json")
echo "delays in two processes: $d0 $d1 $d2 ns (one process: $(delays "$WORK/one.json"))"
[ "$d0" -eq 0 ] && [ "$d1" -gt "$d0" ] && [ "$d2" -gt "$d1" ] || fail "delays do not increase along the line: $d0 $d1 $d2"
grep -q "part 2 (slave 3) serves" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "no child part logged"; }

"$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us 1000 --cycles 3000 \
  --reply-timeout-us 200000 >"$WORK/op.txt" 2>"$WORK/op.err"
rc=$?
cat "$WORK/op.txt" "$WORK/op.err"
[ $rc -eq 0 ] || fail "vdrive-master op exited $rc"
grep -Eq "^summary: 3000 cycles of 1000 us, working counter [0-9]+ expected, 0 wrong, 0 lost, 0 not all in Op" "$WORK/op.txt" \
  || fail "op over two processes: not 3000 cycles with zero wrong working counters"

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
