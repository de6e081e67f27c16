#!/usr/bin/env bash
# Integration: the web page of a line over two processes shows the whole line. `vdrive run
# --processes 2 --netns NS --web` serves a6b and ds5c1 in part 1 and ds1000a in part 2, both
# with their interfaces inside the namespace and their pages on this namespace's loopback; the
# project master keeps the line in Op with DC and moves it. Through part 1's API: three slaves in
# Op with station addresses 0x1001-0x1003, slave 3 the ds1000a on port 1 of slave 2, its object
# 1018h:01 read from part 2, its plot points. In headless Chromium (tests/web/cdp_page_check.py)
# the page, used as a person would, for slave 3: every box reaches Op, slave 3's plot moves, the
# faults panel starts an overload at slave 3 (it acts in part 2 through the run's router) and its
# axis panel shows the DS1000A-EC's alarm, and a write of 6041h:00 is refused with 0x06010002.
# The API then shows slave 3's 603Fh FF01h, and the page's fault under its run-wide id. Part 2
# killed: its slaves are marked, and a request for slave 3 is a 503 naming the part. Part 1's
# status line shows all three slaves, and slave 3 as "?" once part 2 is gone. With
# --rt-priority only the serving threads are SCHED_FIFO (a browser loading a page served at the
# loop's priority once starved the line into SM watchdog errors).
#
# Usage: bash split_line_web.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
HERE=$(cd "$(dirname "$0")" && pwd)
CHECK="$HERE/../web/cdp_page_check.py"
PY=/usr/bin/python3      # Debian's interpreter, where python3-websocket lives
CHROMIUM=/usr/bin/chromium

# shellcheck source=lib/veth_line.sh
. "$HERE/lib/veth_line.sh"
require_tools curl
[ -x "$CHROMIUM" ] || skip "chromium not installed"
"$PY" -c "import websocket" 2>/dev/null || skip "python3-websocket not installed"

MASTER_PID=""
trap '[ -n "$MASTER_PID" ] && kill "$MASTER_PID" 2>/dev/null; cleanup' EXIT
PORT=$("$PY" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
API="http://127.0.0.1:$PORT/api/v1"
J='Content-Type: application/json'
jq_py() { "$PY" -c "import json, sys; d = json.load(sys.stdin); print($1)"; }

make_veth_line
# Not in the namespace: --netns opens the interfaces there, and the page stays here.
# Real-time priority for the line and the master: the browser's start must not starve them.
"$VDRIVE" run --netns "$NS" --iface "$S_IF" --processes 2 --control "$WORK/control.sock" --web "127.0.0.1:$PORT" \
  --rt-priority 80 --status --drive a6b ds5c1 ds1000a >"$WORK/vdrive.log" 2>&1 &
VDRIVE_PID=$!
wait_for_line
grep -q "\[part 2\].*web page on http://127.0.0.1:" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "part 2 serves no page of its own"; }

# Only each part's serving thread runs at the real-time priority: the pages' threads (and the
# control socket's, the status line's) take none, so a browser's requests cannot hold up a loop.
for part in 1 2; do
  pid=$([ $part = 1 ] && echo "$VDRIVE_PID" || pgrep -f -- "--run-part 2 " | head -1)
  fifo=$(ps -L -o cls= -p "$pid" | grep -c FF)
  echo "part $part: $fifo of $(ps -L -o cls= -p "$pid" | wc -l) threads SCHED_FIFO"
  [ "$fifo" -eq 1 ] || { ps -L -o tid,cls,rtprio,comm -p "$pid"; fail "part $part: $fifo SCHED_FIFO threads, not 1"; }
done

# The sine outlasts the page check; the master's verdict after the fault does not matter here.
"$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us 1000 --reply-timeout-us 200000 --sine --revolutions 0.1 --frequency 0.5 \
  --seconds 90 >"$WORK/op.txt" 2>"$WORK/op.err" &
MASTER_PID=$!

line_ok=""
for _ in $(seq 1 100); do
  curl -sf "$API/line" >"$WORK/line.json" 2>/dev/null &&
    line_ok=$(jq_py '",".join("%d:%s:%s:%#06x:%d" % (s["position"], s["product"], s["al_state_name"], s["address"], s["parent"])
                            for s in d["slaves"])' <"$WORK/line.json")
  [ "$line_ok" = "1:a6b:Op:0x1001:0,2:ds5c1:Op:0x1002:1,3:ds1000a:Op:0x1003:2" ] && break
  sleep 0.2
done
echo "line through part 1's page: $line_ok"
[ "$line_ok" = "1:a6b:Op:0x1001:0,2:ds5c1:Op:0x1002:1,3:ds1000a:Op:0x1003:2" ] \
  || { cat "$WORK/line.json" "$WORK/vdrive.log"; fail "part 1's page does not show the whole line in Op"; }

# Part 1's status line (once a second into the log) counts part 2's slave too.
status_shows() { local _; for _ in $(seq 1 30); do grep -q "^status: $1" "$WORK/vdrive.log" && return 0; sleep 0.2; done; return 1; }
status_shows "3 slaves 1:Op 2:Op 3:Op |" || { grep "^status:" "$WORK/vdrive.log" | tail -3; fail "part 1's status line does not show the whole line in Op"; }
echo "status line: $(grep "^status: 3 slaves 1:Op 2:Op 3:Op" "$WORK/vdrive.log" | tail -1 | cut -c1-60)"

vendor=$(curl -sf "$API/slaves/3/objects/0x1018/1" | jq_py 'd["value"]') || fail "1018h:01 of slave 3 not read"
direct=$(curl -sf "$API/slaves/0x1003/objects/0x1018/1" | jq_py 'd["value"]')
echo "slave 3 1018h:01 = $vendor (by address: $direct)"
[ -n "$vendor" ] && [ "$vendor" != 0 ] && [ "$vendor" = "$direct" ] || fail "slave 3's vendor id: '$vendor' / '$direct'"
points=$(curl -sf "$API/samples?slave=3" | jq_py 'len(d["axes"][0]["t"])')
echo "slave 3: $points plot points"
[ "${points:-0}" -gt 5 ] || fail "slave 3 has no plot points on part 1's page"

nice -n 10 "$PY" "$CHECK" --url "http://127.0.0.1:$PORT/" --slaves 3 --fault overload --fault-slave 3 \
  --result "$WORK/page.json" --chromium "$CHROMIUM"
rc=$?
if [ $rc -ne 0 ]; then
  echo "--- vdrive run (host stalls: $(grep -c "host stall" "$WORK/vdrive.log"))"; grep -v "host stall\|^status:" "$WORK/vdrive.log" | tail -40
  echo "--- vdrive-master op"; tail -n 5 "$WORK/op.txt" "$WORK/op.err"
  [ $rc -eq 77 ] && exit 77
  fail "the page check failed (exit $rc)"
fi
page_code=$("$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["alarm"]["error_code"])' "$WORK/page.json")
api_code=$(curl -sf "$API/line" | jq_py 'd["slaves"][2]["drive"]["error_code"]')
echo "slave 3: 603Fh $page_code on the page, $api_code in the API"
[ "$page_code" = 65281 ] && [ "$api_code" = 65281 ] || fail "slave 3 does not show the DS1000A-EC's overload FF01h (65281)"
grep -q "\[part 2\].*fault 1 injected: overload slave 1" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "the page's fault did not act in part 2"; }
faults=$(curl -sf "$API/faults" | jq_py '" ".join("%d:%s" % (f["id"], f["description"]) for f in d["faults"])')
echo "active faults: $faults"
echo "$faults" | grep -q "^2:overload slave 3" || fail "the page's fault is not listed as run-wide fault 2 at slave 3"
curl -sf "$API/events?kind=fault_injected&slave=3" | jq_py 'd["events"][0]["text"]' | grep -q "fault 2 overload started" \
  || fail "no fault_injected event of slave 3 with run-wide id 2 on part 1's page"

# Part 2 ends: its slave is marked on part 1's page, and its requests are refused naming it.
kill -KILL "$(pgrep -f -- "--run-part 2 " | head -1)" || fail "no part 2 process"
marked=""
for _ in $(seq 1 50); do
  marked=$(curl -sf "$API/line" | jq_py 'd["slaves"][2]["al_state_name"]')
  [ "$marked" = "no answer" ] && break
  sleep 0.2
done
[ "$marked" = "no answer" ] || fail "slave 3 after part 2 ended: '$marked'"
status_shows "3 slaves 1:[A-Za-z+E()0-9]* 2:[A-Za-z+E()0-9]* 3:? |" || { grep "^status:" "$WORK/vdrive.log" | tail -3; fail "part 1's status line does not show part 2's slave as '?'"; }
refusal=$(curl -s -w ' %{http_code}' "$API/slaves/3/objects/0x1000/0")
echo "slave 3 after part 2 ended: $refusal"
echo "$refusal" | grep -q 'part 2 (slave 3) does not answer.* 503$' || fail "a request for slave 3 is not refused naming part 2"
echo PASS
