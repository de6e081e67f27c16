#!/usr/bin/env bash
# Integration: the web page's API around the real program, with plain HTTP (curl), as a test in
# pytest or a shell script would use it (docs/web.md).
#  1. `vdrive run --web 127.0.0.1:PORT` in a namespace; `vdrive-master op --sine` takes the line to
#     Op: the API shows both drives in Op and Operation enabled; a fault posted to the API raises
#     the A6B's Err16.0 (603Fh FF10h), seen in /api/v1/line and as an alarm event; a write of the
#     read-only 6041h is refused with the master's abort code 0x06010002.
#  2. `vdrive run --web 0.0.0.0:PORT` logs a token and a warning; a change without it is 401, with
#     it 201.
#  3. `vdrive scenario run --veth --web`: the page shows the scenario, its log and its expectations
#     as they are met, and its steps in the event log.
#
# Usage: bash web_api.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
SRC="$(cd "$(dirname "$0")/../.." && pwd)"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools curl python3

PORT=$((20000 + $$ % 20000))
api() { ip netns exec "$NS" curl -s --max-time 5 "$@"; }
json() { python3 -c "import json,sys; d=json.load(sys.stdin); print($1)"; }

start_line --drive a6b --drive ds5c1 --web "127.0.0.1:$PORT" --no-control
ip -n "$NS" link set lo up
wait_for_line
grep -q "web page on http://127.0.0.1:$PORT/" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "vdrive run did not log the page's address"; }

"$MASTER" op --iface "$M_IF" --dc --cycle-us 1000 --reply-timeout-us 200000 --sine --revolutions 0.25 --frequency 0.5 \
  --seconds 8 >"$WORK/op.txt" 2>"$WORK/op.err" &
OP_PID=$!
ok=""
for _ in $(seq 1 80); do
  states=$(api "http://127.0.0.1:$PORT/api/v1/line" | json "' '.join(s['al_state_name'] + '/' + s['drive']['state'] for s in d['slaves'])")
  [ "$states" = "Op/Operation enabled Op/Operation enabled" ] && { ok=1; break; }
  sleep 0.1
done
[ -n "$ok" ] || fail "the API never showed both drives in Op and Operation enabled (last: $states)"
echo "ok: $states"

code=$(api -o "$WORK/fault.json" -w '%{http_code}' -X POST -H 'Content-Type: application/json' \
  -d '{"kind":"overload","slave":1,"duration":"2s"}' "http://127.0.0.1:$PORT/api/v1/faults")
[ "$code" = 201 ] || fail "POST /api/v1/faults: HTTP $code $(cat "$WORK/fault.json")"
alarm=""
for _ in $(seq 1 30); do
  alarm=$(api "http://127.0.0.1:$PORT/api/v1/line" | json "(d['slaves'][0]['drive']['alarm'] or {}).get('code')")
  [ "$alarm" = "16.0" ] && break
  sleep 0.1
done
[ "$alarm" = "16.0" ] || fail "the A6B's alarm on the API is '$alarm', expected 16.0"
api "http://127.0.0.1:$PORT/api/v1/events?kind=alarm_raised&slave=1" | grep -q "FF10h" || fail "no alarm_raised event with FF10h"
echo "ok: overload -> Err16.0 on the API"

code=$(api -o "$WORK/write.json" -w '%{http_code}' -X PUT -H 'Content-Type: application/json' -d '{"value":1}' \
  "http://127.0.0.1:$PORT/api/v1/slaves/1/objects/0x6041/0")
[ "$code" = 409 ] || fail "PUT 6041h: HTTP $code, expected 409"
grep -q '"abort_code":"0x06010002"' "$WORK/write.json" || fail "PUT 6041h: $(cat "$WORK/write.json")"
echo "ok: 6041h write refused with 0x06010002"
wait "$OP_PID" 2>/dev/null

# 2. Served to other machines: a token guards changes.
restart_line --drive a6b --web "0.0.0.0:$PORT" --no-control
token=""
for _ in $(seq 1 50); do
  token=$(sed -n "s/.*web page on http:.*#token=\([0-9a-f]*\).*/\1/p" "$WORK/vdrive.log")
  [ -n "$token" ] && break
  sleep 0.1
done
[ -n "$token" ] || { cat "$WORK/vdrive.log"; fail "vdrive run --web 0.0.0.0 logged no token"; }
grep -q "served to other machines" "$WORK/vdrive.log" || fail "no warning that the page is served to other machines"
code=$(api -o /dev/null -w '%{http_code}' -X POST -H 'Content-Type: application/json' -d '{"kind":"jam","slave":1}' \
  "http://127.0.0.1:$PORT/api/v1/faults")
[ "$code" = 401 ] || fail "a change without the token: HTTP $code, expected 401"
code=$(api -o /dev/null -w '%{http_code}' -X POST -H 'Content-Type: application/json' -H "Authorization: Bearer $token" \
  -d '{"kind":"jam","slave":1}' "http://127.0.0.1:$PORT/api/v1/faults")
[ "$code" = 201 ] || fail "a change with the token: HTTP $code, expected 201"
echo "ok: the token guards changes"
kill "$VDRIVE_PID" 2>/dev/null; wait "$VDRIVE_PID" 2>/dev/null; VDRIVE_PID=""

# 3. A real-time scenario on the page.
ip netns exec "$NS" "$VDRIVE" scenario run "$SRC/scenarios/fault_overload.yaml" --veth --web "127.0.0.1:$PORT" \
  >"$WORK/scenario.out" 2>&1 &
SC_PID=$!
seen=""
for _ in $(seq 1 200); do
  seen=$(api "http://127.0.0.1:$PORT/api/v1/line" 2>/dev/null | json \
    "'%s %d %d' % (d['scenario']['name'], sum(e['state'] == 'met' for e in d['scenario']['expectations']), len(d['scenario']['log'])) if d.get('scenario') else ''" 2>/dev/null)
  case "$seen" in fault_overload\ [1-9]*)
    steps=$(api "http://127.0.0.1:$PORT/api/v1/events?kind=scenario" 2>/dev/null | json "len(d['events'])" 2>/dev/null)
    break ;;
  esac
  kill -0 "$SC_PID" 2>/dev/null || break
  sleep 0.05
done
wait "$SC_PID"; rc=$?
cat "$WORK/scenario.out"
[ $rc -eq 0 ] || fail "the scenario failed (exit $rc)"
case "$seen" in
  fault_overload\ [1-9]*) echo "ok: the page showed the scenario with met expectations ($seen)" ;;
  *) fail "the page never showed the scenario with a met expectation (last: '$seen')" ;;
esac
[ "${steps:-0}" -gt 0 ] || fail "the scenario's steps are not in the page's event log"
echo "ok: $steps scenario steps in the event log"
echo "PASS"
