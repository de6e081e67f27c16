#!/usr/bin/env bash
# Frame turnaround benchmark, one command: makes its own network namespace and veth pair,
# then for every line size N measures, with the same master (bench_turnaround_master) and the same
# sample count, at 1 kHz and back-to-back:
#   vdrive   `vdrive run` serving N drives (products a6b, ds5c1, ds1000a in turn), taken to Op
#   echo     bench_echo_responder (the floor), its frame as long as vdrive's for that N
#   kickcat  KickCAT's network_simulator with N ecat402-drive slaves (only with KICKCAT_SIM)
# and prints one table with the ratios to the echo (and to KickCAT). Removes everything it made.
#
# Usage: bench/turnaround/run.sh [BUILD_DIR]            (root; BUILD_DIR default: ./build)
# Environment (all optional):
#   SAMPLES=10000      measured frames per run (after 500 warm-up frames)
#   DRIVES="1 3 16 64" line sizes
#   RATES="1000 0"     frames per second; 0 = back-to-back
#   KICKCAT_SIM=PATH   KickCAT's network_simulator (docs/performance.md says how it was built)
#   KICKCAT_SLAVE=PATH its slave config (default: simulation/slave_configs/ecat402-drive.json
#                      beside the build directory that holds network_simulator)
#   VDRIVE_OPTS="..."  extra `vdrive run` options (e.g. "--busy-poll-us 200 --cpu 1")
#   ECHO_OPTS="..."    extra echo options (e.g. "--busy-poll-us 200")
#   MASTER_OPTS="..."  extra master options (e.g. "--busy-poll-us 1000")
#   RT_PRIORITY=N      run the master and every responder (KickCAT too) under `chrt -f N`
#   OUT=DIR            keep the JSON results and logs in DIR (default: a temporary directory)
#   WEB_PAGE=1         also measure `vdrive run --web` with its live stream read by curl (label
#                      vdrive+stream: the server's whole cost) and with the page open in headless
#                      chromium on the same machine (vdrive+page: the server and a browser), docs/web.md
# Exit: 0 all measured, 1 a run failed, 77 not root.
set -u

BUILD=$(cd "${1:-build}" && pwd) || { echo "no build directory ${1:-build}"; exit 1; }
VDRIVE="$BUILD/vdrive/vdrive"
MASTER="$BUILD/bench/turnaround/bench_turnaround_master"
ECHO="$BUILD/bench/turnaround/bench_echo_responder"
SAMPLES=${SAMPLES:-10000}
DRIVES=${DRIVES:-"1 3 16 64"}
RATES=${RATES:-"1000 0"}
KICKCAT_SIM=${KICKCAT_SIM:-}
RT=()
[ -n "${RT_PRIORITY:-}" ] && RT=(chrt -f "$RT_PRIORITY")
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root (network namespace, veth, raw sockets)"; exit 77; }
for f in "$VDRIVE" "$MASTER" "$ECHO"; do [ -x "$f" ] || { echo "missing $f (build it first)"; exit 1; }; done
if [ -n "$KICKCAT_SIM" ]; then
  [ -x "$KICKCAT_SIM" ] || { echo "KICKCAT_SIM=$KICKCAT_SIM is not an executable"; exit 1; }
  KICKCAT_SLAVE=${KICKCAT_SLAVE:-$(dirname "$KICKCAT_SIM")/../../simulation/slave_configs/ecat402-drive.json}
  [ -f "$KICKCAT_SLAVE" ] || { echo "no KickCAT slave config at $KICKCAT_SLAVE (set KICKCAT_SLAVE)"; exit 1; }
fi

NS="vdta-$$"
M_IF="vdtam$$"
S_IF="vdtas$$"
KEEP=${OUT:-}
OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT"
RESULTS="$OUT/turnaround.jsonl"
: >"$RESULTS"
SERVER_PID=""
PAGE_PID=""

stop_page() {
  if [ -n "$PAGE_PID" ]; then
    kill "$PAGE_PID" 2>/dev/null
    wait "$PAGE_PID" 2>/dev/null
    PAGE_PID=""
  fi
}

stop_server() {
  if [ -n "$SERVER_PID" ]; then
    kill "$SERVER_PID" 2>/dev/null
    wait "$SERVER_PID" 2>/dev/null
    SERVER_PID=""
  fi
}
cleanup() {
  stop_page
  stop_server
  ip link del "$M_IF" 2>/dev/null
  ip netns del "$NS" 2>/dev/null
  [ -z "$KEEP" ] && rm -rf "$OUT"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

ip netns add "$NS" || exit 1
ip link add "$M_IF" type veth peer name "$S_IF" || exit 1
ip link set "$S_IF" netns "$NS"
ip link set "$M_IF" up
ip -n "$NS" link set "$S_IF" up
ip -n "$NS" link set lo up

# start_server NAME READY COMMAND...: a responder in the namespace (log: $OUT/NAME.log); waits
# until its log matches READY (empty: a fixed moment), then one more second for its socket.
start_server() {
  local name=$1 ready=$2; shift 2
  ip netns exec "$NS" "${RT[@]}" "$@" >"$OUT/$name.log" 2>&1 &
  SERVER_PID=$!
  local _
  for _ in $(seq 1 600); do   # a line of 64 drives takes seconds to build on a loaded host
    [ -z "$ready" ] || grep -q "$ready" "$OUT/$name.log" 2>/dev/null && break
    kill -0 "$SERVER_PID" 2>/dev/null || break
    sleep 0.1
  done
  sleep 1
  kill -0 "$SERVER_PID" 2>/dev/null || { cat "$OUT/$name.log"; echo "$name exited early"; exit 1; }
}

# measure LABEL N LINE [MASTER ARGS...]: one run per rate into $RESULTS.
measure() {
  local label=$1 n=$2 line=$3; shift 3
  local rate
  for rate in $RATES; do
    # shellcheck disable=SC2086
    "${RT[@]}" "$MASTER" --iface "$M_IF" --line "$line" --label "$label/$n" --rate-hz "$rate" --samples "$SAMPLES" \
      --json "$RESULTS" ${MASTER_OPTS:-} "$@" 2>>"$OUT/master.err" || {
      cat "$OUT/master.err"; echo "FAILED: $label N=$n at rate $rate"; return 1; }
  done
}

drive_args() {  # N drives, products in turn
  local n=$1 i products=(a6b ds5c1 ds1000a)
  for ((i = 0; i < n; i++)); do printf -- '--drive %s ' "${products[i % 3]}"; done
}

echo "load average before: $(cat /proc/loadavg)"
status=0
for n in $DRIVES; do
  # shellcheck disable=SC2046,SC2086
  start_server "vdrive-$n" "serving" "$VDRIVE" run --iface "$S_IF" --no-control $(drive_args "$n") ${VDRIVE_OPTS:-}
  measure vdrive "$n" op || status=1
  stop_server
  if [ -n "${WEB_PAGE:-}" ]; then
    # shellcheck disable=SC2046,SC2086
    start_server "vdrive-web-$n" "serving" "$VDRIVE" run --iface "$S_IF" --no-control --web 127.0.0.1:8377 $(drive_args "$n") ${VDRIVE_OPTS:-}
    # The stream alone: what the server does for an open page, without a browser's rendering.
    ip netns exec "$NS" curl -sN http://127.0.0.1:8377/api/v1/stream >/dev/null 2>&1 &
    PAGE_PID=$!
    sleep 2
    measure vdrive+stream "$n" op || status=1
    stop_page
    # The page rendering in a headless browser in the namespace for the whole measurement.
    ip netns exec "$NS" chromium --headless=new --no-sandbox --disable-gpu --user-data-dir="$OUT/chromium" \
      --remote-debugging-port=0 http://127.0.0.1:8377/ >"$OUT/chromium-$n.log" 2>&1 &
    PAGE_PID=$!
    sleep 3
    echo "page: $(ip netns exec "$NS" ss -Htn state established '( sport = :8377 )' | wc -l) connection(s) open to the web server"
    measure vdrive+page "$n" op || status=1
    stop_page
    stop_server
  fi
  image=$(grep "\"label\":\"vdrive/$n\"" "$RESULTS" | head -1 | sed -n 's/.*"image_bytes":\([0-9]*\).*/\1/p')
  # shellcheck disable=SC2086
  start_server "echo-$n" "" "$ECHO" --iface "$S_IF" ${ECHO_OPTS:-}
  measure echo "$n" echo --image-bytes "${image:-64}" || status=1
  stop_server
  if [ -n "$KICKCAT_SIM" ]; then
    slaves=()
    for ((i = 0; i < n; i++)); do slaves+=("$KICKCAT_SLAVE"); done
    start_server "kickcat-$n" "Opening nominal interface" "$KICKCAT_SIM" -i "$S_IF" -s "${slaves[@]}"
    measure kickcat "$n" op || status=1
    stop_server
  fi
done
echo "load average after: $(cat /proc/loadavg)"

python3 "$(dirname "$0")/table.py" "$RESULTS"
[ -n "$KEEP" ] && echo "results: $RESULTS"
exit $status
