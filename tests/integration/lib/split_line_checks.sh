# Sourced by the tests of a line spread over processes or hosts (split_line.sh, two_hosts.sh):
# what a master must see of it, checked as the master sees it. Needs fail() and MASTER, M_IF,
# WORK from veth_line.sh.
#   scan_identities FILE      every field `vdrive-master scan --json` gives per slave but the ones
#                             that depend on timing and state, one line per slave
#   scan_delays FILE          the slaves' DC delays, space-separated
#   expect_delays_increase FILE WHAT
#   expect_clean_op WHAT      Op with DC at 1 ms for 3,000 cycles, 0 wrong working counters
#   scan_line NAME            waits for the line now serving and keeps its scan as $WORK/NAME.json
#                             and its identities as $WORK/NAME.txt

scan_identities() {
  python3 -c '
import json, sys
for s in json.load(open(sys.argv[1]))["slaves"]:
    for k in ("delay_ns", "al_status", "al_status_code"): s.pop(k, None)
    print(json.dumps(s, sort_keys=True))' "$1"
}

scan_delays() {
  python3 -c 'import json, sys; print(" ".join(str(s["delay_ns"]) for s in json.load(open(sys.argv[1]))["slaves"]))' "$1"
}

expect_delays_increase() {
  local d0 d1 d2
  read -r d0 d1 d2 < <(scan_delays "$1")
  echo "delays $2: $d0 $d1 $d2 ns"
  [ "$d0" -eq 0 ] && [ "$d1" -gt "$d0" ] && [ "$d2" -gt "$d1" ] || fail "$2: delays do not increase along the line: $d0 $d1 $d2"
}

expect_clean_op() {
  local rc
  "$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us 1000 --cycles 3000 \
    --reply-timeout-us 200000 >"$WORK/op.txt" 2>"$WORK/op.err"
  rc=$?
  cat "$WORK/op.txt" "$WORK/op.err"
  [ $rc -eq 0 ] || fail "$1: vdrive-master op exited $rc"
  grep -Eq "^summary: 3000 cycles of 1000 us, working counter [0-9]+ expected, 0 wrong, 0 lost, 0 not all in Op" "$WORK/op.txt" \
    || fail "$1: not 3000 cycles with zero wrong working counters"
}

scan_line() {
  wait_for_line --json
  cp "$WORK/scan.out" "$WORK/$1.json"
  scan_identities "$WORK/$1.json" >"$WORK/$1.txt"
}
