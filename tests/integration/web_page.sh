#!/usr/bin/env bash
# Integration: the web page in a real browser. `vdrive demo --web` runs in a namespace of its own
# (the demo makes its veth pair there; lo up for the web server and DDS), its master moving the
# three drives in csp; a `vdrive telemetry` subscriber records DDS events in the same namespace;
# headless Chromium, driven over the DevTools protocol by tests/web/cdp_page_check.py, opens the
# page there and uses it as a person would.
# Asserts, on the page: every slave box reaches Op; slave 1's plot receives new points and moves;
# the live stream brings at least 15 updates per second; the faults panel's button starts an
# overload on slave 1 and the axis panel shows the drive's alarm with a non-zero 603Fh; writing
# 6041h:00 through the object-dictionary panel is refused with abort 0x06010002. In DDS telemetry:
# the same alarm (alarm_raised of slave 1 with the page's 603Fh, and 603Fh in slave 1's samples)
# and the page's fault (fault_injected). A screenshot goes to $VDRIVE_WEB_SCREENSHOT if set.
#
# Usage: bash web_page.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
HERE=$(cd "$(dirname "$0")" && pwd)
CHECK="$HERE/../web/cdp_page_check.py"
PY=/usr/bin/python3      # Debian's interpreter, where python3-websocket lives
CHROMIUM=/usr/bin/chromium

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
[ "$(id -u)" -eq 0 ] || skip "needs root (network namespace, veth, raw sockets)"
command -v ip >/dev/null || skip "ip not installed"
[ -x "$CHROMIUM" ] || skip "chromium not installed"
"$PY" -c "import websocket" 2>/dev/null || skip "python3-websocket not installed"
[ -x "$VDRIVE" ] || fail "vdrive not found at $VDRIVE"
"$VDRIVE" demo --help | grep -q -- "--web" || skip "this vdrive has no --web"

NS="vdw-$$"
SUFFIX="w$$"                     # the demo's veth: vdrive-mw<pid>/vdrive-sw<pid>, inside $NS
PORT=8080                        # the namespace's own loopback: no clash with the host
DOMAIN=$(( $$ % 200 + 21 ))      # apart from other runs on this machine
WORK=$(mktemp -d)
DEMO_PID=""
TLM_PID=""
SHOT=${VDRIVE_WEB_SCREENSHOT:-$WORK/web.png}

# SIGTERM ends it cleanly (veth removed); a demo still busy after 10 s is killed.
stop_demo() {
  [ -n "$DEMO_PID" ] || return 0
  kill -TERM "$DEMO_PID" 2>/dev/null
  local _
  for _ in $(seq 1 100); do kill -0 "$DEMO_PID" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$DEMO_PID" 2>/dev/null
  wait "$DEMO_PID" 2>/dev/null
  DEMO_PID=""
}
cleanup() {
  [ -n "$TLM_PID" ] && kill -TERM "$TLM_PID" 2>/dev/null && wait "$TLM_PID" 2>/dev/null
  stop_demo
  # Whatever still runs in the namespace was started here (a browser left by a killed check).
  local pids
  mapfile -t pids < <(ip netns pids "$NS" 2>/dev/null)
  ((${#pids[@]})) && kill -KILL "${pids[@]}" 2>/dev/null
  ip netns del "$NS" 2>/dev/null    # takes the demo's veth pair with it if the demo did not
  rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM
in_ns() { ip netns exec "$NS" "$@"; }   # foreground only: $! of a function is its subshell

ip netns add "$NS" || fail "cannot create namespace $NS"
ip -n "$NS" link set lo up

# The sine lasts longer than the test: the master keeps the line in Op, moving, while the page
# is checked. --keep-running: the line stays up whatever the master's verdict after the fault.
ip netns exec "$NS" "$VDRIVE" demo --suffix "$SUFFIX" --web "127.0.0.1:$PORT" --domain "$DOMAIN" --sine-seconds 600 --keep-running \
  >"$WORK/demo.log" 2>&1 &
DEMO_PID=$!

ip netns exec "$NS" "$VDRIVE" telemetry --domain "$DOMAIN" --duration 200 --csv "$WORK/axes.csv" --events-csv "$WORK/events.csv" -q \
  >"$WORK/tlm.out" 2>&1 &
TLM_PID=$!

# The A6B's overload is Err16.0, 603Fh FF10h (docs/faults.md). The browser runs niced: the line's
# timing matters more than the page's on a small machine.
in_ns nice -n 10 "$PY" "$CHECK" --url "http://127.0.0.1:$PORT/" --slaves 3 --fault overload --fault-slave 1 \
  --expect-alarm 16.0 --screenshot "$SHOT" --result "$WORK/page.json" --chromium "$CHROMIUM"
rc=$?
if [ $rc -ne 0 ]; then
  echo "--- vdrive demo"; tail -40 "$WORK/demo.log"
  [ $rc -eq 77 ] && exit 77
  fail "the page check failed (exit $rc)"
fi
kill -0 "$DEMO_PID" 2>/dev/null || { cat "$WORK/demo.log"; fail "vdrive demo ended during the page check"; }

# The alarm's samples and events reach the subscriber. The overload stands (clearable 10 s after
# it occurs), so its samples keep coming: a subscriber starved by a busy host gets them late, not
# never. The recording is buffered; it is looked at every second, for at most 10 s.
page_code=$("$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["alarm"]["error_code"])' "$WORK/page.json")
slave1_shows() { awk -F, -v c="$page_code" 'NR > 1 && $2 == 1 && $12 == c { found = 1 } END { exit !found }' "$WORK/axes.csv"; }
for _ in $(seq 1 10); do sleep 1; slave1_shows && break; done
kill -TERM "$TLM_PID"
wait "$TLM_PID"
trc=$?
TLM_PID=""
[ $trc -eq 0 ] || { cat "$WORK/tlm.out"; fail "vdrive telemetry exited $trc"; }

# What the page showed, against DDS telemetry.
page_alarm=$("$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["alarm"]["code"])' "$WORK/page.json")
printf 'page: slave 1 alarm %s, 603Fh 0x%04X\n' "$page_alarm" "$page_code"
grep -qE "^[0-9]+,1,fault_injected,[0-9]+,0,\"fault [0-9]+ overload started\"" "$WORK/events.csv" \
  || { cat "$WORK/events.csv"; fail "DDS: no fault_injected event for the page's overload on slave 1"; }
grep -qE "^[0-9]+,1,alarm_raised,$page_code,[0-9]+," "$WORK/events.csv" \
  || { cat "$WORK/events.csv"; fail "DDS: no alarm_raised of slave 1 with 603Fh $page_code (the page's)"; }
slave1_shows || fail "DDS: slave 1's samples never show 603Fh $page_code ($(awk -F, 'NR > 1 && $2 == 1 { n++; if (!f) f = $1; l = $1; c = $12 }
  END { printf "%d samples of slave 1, from t=%.3f s to t=%.3f s, the last with 603Fh %s", n, f / 1e9, l / 1e9, c }' "$WORK/axes.csv");
  the alarm: $(grep -E "^[0-9]+,1,alarm_raised," "$WORK/events.csv" | head -1))"
echo "DDS: fault_injected and alarm_raised 603Fh $page_code on slave 1, as the page shows"
[ -s "$SHOT" ] || fail "no screenshot at $SHOT"
echo "screenshot: $SHOT"

stop_demo
echo PASS
