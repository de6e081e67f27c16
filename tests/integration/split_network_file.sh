#!/usr/bin/env bash
# Integration: a network file spread over processes. A file of three drives (the third an A6B with
# station alias 7 and an encoder fault armed on it) says `processes: 2`; `vdrive run --network FILE` then
# serves slaves 1-2 itself and slave 3 in a second process, and a master sees the line as it sees
# the same file in one process (`vdrive-master scan --json`), with DC delays
# increasing along it and 3,000 clean cycles in Op. The fault armed on slave 3 acts in the part
# that serves it: its 603Fh reads an alarm, slave 1's none, and part 2 logs the alarm as slave 3's.
# `vdrive signal` through part 1's control socket lists both parts' named signals, sets part 2's
# by name and reads it back by whole-line position (3.home). A file whose wire would join two parts
# is refused before serving, exit 2, naming the wire's line.
#
# Usage: bash split_network_file.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
# shellcheck source=lib/split_line_checks.sh
. "$(dirname "$0")/lib/split_line_checks.sh"
require_tools python3

printf 'slaves:\n  - {name: a, device: a6b}\n  - {name: b, device: ds5c1}\n  - {name: c, device: ds1000a}\n'\
'wires:\n  - {from: a.home, to: c.probe1}\nprocesses: 2\n' >"$WORK/crossing.yaml"
err=$("$VDRIVE" run --iface lo --no-control --network "$WORK/crossing.yaml" 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] || fail "a wire across parts: exit $rc, expected 2 ($err)"
echo "$err" | grep -q "crossing.yaml:6: wires\[0\] (a.home -> c.probe1): joins slave 1 (part 1, slaves 1-2) and slave 3 (part 2, slave 3)" \
  || fail "the wire is not named: $err"
echo "ok: $err"

LINE='slaves:\n  - {name: a, device: ds5c1}\n  - {name: b, device: ds1000a}\n  - {name: c, device: a6b, alias: 7}\n'
printf "$LINE" >"$WORK/one.yaml"
printf "${LINE}faults:\n  - {kind: encoder_error, slave: c, at: 300ms}\nprocesses: 2\nsignals:\n  first_home: a.home\n  door: c.home\n" >"$WORK/two.yaml"

start_line --no-control --network "$WORK/one.yaml"
scan_line one
[ "$(wc -l <"$WORK/one.txt")" -eq 3 ] || { cat "$WORK/one.json"; fail "one process: not 3 slaves"; }

CONTROL="$WORK/control.sock"
restart_line --control "$CONTROL" --network "$WORK/two.yaml"
scan_line two
diff "$WORK/one.txt" "$WORK/two.txt" || fail "the file in two processes does not look as in one"
expect_delays_increase "$WORK/two.json" "in two processes (one process: $(scan_delays "$WORK/one.json"))"
grep -q "the line of 3 slaves in 2 processes" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "the file's processes: 2 was not used"; }
grep -q "part 2 (slave 3) serves" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "no child part logged"; }

sleep 0.6
alarm() { "$MASTER" sdo-read --iface "$M_IF" --slave "$1" --index 0x603F --type u16 | sed -n 's/.*(\([0-9]*\))$/\1/p'; }
a3=$(alarm 3); a1=$(alarm 1)
echo "603Fh: slave 1 $a1, slave 3 $a3"
[ -n "$a3" ] && [ "$a3" -ne 0 ] || { cat "$WORK/vdrive.log"; fail "slave 3 reports no alarm: the fault armed on it did not act"; }
[ "$a1" = 0 ] || fail "slave 1 reports alarm $a1: the fault acted on the wrong slave"
grep -q "two.yaml:6: armed fault 1 (encoder_error slave 1)" "$WORK/vdrive.log" \
  || { cat "$WORK/vdrive.log"; fail "part 2 did not arm the fault on its first slave"; }
# Part 2 logs its slave by its place in the whole line.
grep -Eq "\[part 2\] \[info\] slave 3 (@0x1003 )?a6b: alarm 21.0" "$WORK/vdrive.log" \
  || { cat "$WORK/vdrive.log"; fail "part 2 does not log slave 3's alarm as slave 3"; }

# Part 1's socket reaches part 2's named signal and its slave at its whole-line position.
sig() { "$VDRIVE" signal "$@" --control "$CONTROL" 2>&1; }
out=$(sig list) || fail "signal list: '$out'"
printf '%s\n' "$out" | grep -Pq "^first_home\ta.home\tconnection\t" || fail "signal list lacks part 1's first_home: '$out'"
printf '%s\n' "$out" | grep -Pq "^door\tc.home\tconnection\t" || fail "signal list lacks part 2's door: '$out'"
out=$(sig set door on) || fail "signal set door on (part 2's): '$out'"
[ "$out" = "$(printf 'door\tc.home\tconnection\t1')" ] || fail "signal set door on: '$out'"
out=$(sig get 3.home) || fail "signal get 3.home (part 2's slave 1): '$out'"
[ "$out" = "$(printf '3.home\tc.home\tconnection\t1')" ] || fail "signal get 3.home does not see door's write: '$out'"
out=$(sig get window); rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q "no part of this run's line has signal 'window'" || fail "signal get window: exit $rc, '$out'"
echo "ok: signals of part 2 through part 1's socket"

restart_line --no-control --network "$WORK/one.yaml" --processes 2
scan_line flag
diff "$WORK/one.txt" "$WORK/flag.txt" || fail "--processes 2 with the file: the line does not look as in one process"
expect_clean_op "op over a network file in two processes"
echo "PASS"
