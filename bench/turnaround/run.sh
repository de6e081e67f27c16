#!/usr/bin/env bash
# Frame turnaround benchmark, one command: makes its own network namespace and veth pair, then
# measures, with the same master (bench_turnaround_master) and the same sample count, at 1 kHz and
# back-to-back, for every line size N:
#   vdrive   `vdrive run` serving N drives (products a6b, ds5c1, ds1000a in turn), taken to Op
#   echo     bench_echo_responder (the floor), its frame as long as vdrive's for that N
#   kickcat  KickCAT's network_simulator with N ecat402-drive slaves (only with KICKCAT_SIM)
# This VM's wake-up latency moves with the load on it by 5 x within minutes, so one measurement of
# each, one after the other, compares moments as much as responders. The responders therefore take
# turns in ROUNDS rounds (round 1: vdrive echo kickcat for each N, round 2: the same again, ...),
# and table.py reports each figure's median over the rounds with its spread (min-max), and the
# ratios pair by pair within each round (vdrive/echo, vdrive/kickcat: measured minutes apart at
# most) with their median. Removes everything it made.
#
# Usage: bench/turnaround/run.sh [BUILD_DIR]            (root; BUILD_DIR default: ./build)
# Environment (all optional):
#   ROUNDS=3           rounds (at least 3: a median and a spread need them)
#   SAMPLES=10000      measured frames per run (after 500 warm-up frames)
#   DRIVES="1 3 16 64" line sizes
#   RATES="1000 0"     frames per second; 0 = back-to-back
#   KICKCAT_SIM=PATH   KickCAT's network_simulator (docs/performance.md says how it was built)
#   KICKCAT_SLAVE=PATH its slave config (default: simulation/slave_configs/ecat402-drive.json
#                      beside the build directory that holds network_simulator)
#   VDRIVE_CMD="..."   the command that serves the line, before the options the script adds
#                      (--iface IF --no-control --drive ... $VDRIVE_OPTS); default "BUILD/vdrive/vdrive run"
#   PROCESSES="1 2"    line layouts measured each round: 1 is VDRIVE_CMD as it is (label vdrive),
#                      P > 1 adds `--processes P` to it (label vdrive-pP); default "1"
#   BATCH_US=US        also measure each round the one-process line with `--batch-steps-us US`
#                      (label vdrive-batched: control steps run at the bus's events, not at 8 kHz)
#   VDRIVE_READY=TEXT  what vdrive's log shows once it serves (default "serving")
#   VDRIVE_OPTS="..."  extra `vdrive run` options (e.g. "--busy-poll-us 200 --cpu 1")
#   ECHO_OPTS="..."    extra echo options (e.g. "--busy-poll-us 200")
#   MASTER_OPTS="..."  extra master options (e.g. "--busy-poll-us 1000")
#   RT_PRIORITY=N      run the master and every responder (KickCAT too) under `chrt -f N`
#   OUT=DIR            keep the JSON results and logs in DIR (default: a temporary directory)
#   WEB_PAGE=1         also measure `vdrive run --web` with its live stream read by curl (label
#                      vdrive+stream: the server's whole cost) and with the page open in headless
#                      chromium on the same machine (vdrive+page: the server and a browser), docs/web.md
# Exit: 0 all measured, 1 a run failed, 2 bad environment, 77 not root.
set -u

BUILD=$(cd "${1:-build}" && pwd) || { echo "no build directory ${1:-build}"; exit 1; }
VDRIVE="$BUILD/vdrive/vdrive"
MASTER="$BUILD/bench/turnaround/bench_turnaround_master"
ECHO="$BUILD/bench/turnaround/bench_echo_responder"
SAMPLES=${SAMPLES:-10000}
ROUNDS=${ROUNDS:-3}
PROCESSES=${PROCESSES:-1}
VDRIVE_READY=${VDRIVE_READY:-serving}
read -r -a VDRIVE_CMD_WORDS <<<"${VDRIVE_CMD:-$VDRIVE run}"
DRIVES=${DRIVES:-"1 3 16 64"}
RATES=${RATES:-"1000 0"}
KICKCAT_SIM=${KICKCAT_SIM:-}
RT=()
[ -n "${RT_PRIORITY:-}" ] && RT=(chrt -f "$RT_PRIORITY")
[[ "$ROUNDS" =~ ^[0-9]+$ ]] && [ "$ROUNDS" -ge 3 ] || { echo "ROUNDS=$ROUNDS: at least 3 rounds (a median and a spread)"; exit 2; }
for p in $PROCESSES; do [[ "$p" =~ ^[1-9][0-9]*$ ]] || { echo "PROCESSES=\"$PROCESSES\": whole numbers >= 1"; exit 2; }; done
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root (network namespace, veth, raw sockets)"; exit 77; }
for f in "$MASTER" "$ECHO" "${VDRIVE_CMD_WORDS[0]}"; do
  [ -x "$f" ] || command -v "$f" >/dev/null || { echo "missing $f (build it first)"; exit 1; }
done
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

# measure LABEL N LINE [MASTER ARGS...]: one run per rate into $RESULTS, marked with $ROUND.
measure() {
  local label=$1 n=$2 line=$3; shift 3
  local rate
  for rate in $RATES; do
    # shellcheck disable=SC2086
    "${RT[@]}" "$MASTER" --iface "$M_IF" --line "$line" --label "$label/$n" --rate-hz "$rate" --samples "$SAMPLES" \
      --json "$OUT/run.json" ${MASTER_OPTS:-} "$@" 2>>"$OUT/master.err" || {
      cat "$OUT/master.err"; echo "FAILED: $label N=$n at rate $rate (round $ROUND)"; return 1; }
    sed "s/}\$/,\"round\":$ROUND}/" "$OUT/run.json" >>"$RESULTS"
    rm -f "$OUT/run.json"
  done
}

drive_args() {  # N drives, products in turn
  local n=$1 i products=(a6b ds5c1 ds1000a)
  for ((i = 0; i < n; i++)); do printf -- '--drive %s ' "${products[i % 3]}"; done
}

# vdrive_line LABEL N P [EXTRA vdrive OPTIONS...]: the line of N drives in P processes, served
# until stop_server. P = 1 runs VDRIVE_CMD as it is, so it works with any vdrive.
vdrive_line() {
  local label=$1 n=$2 p=$3; shift 3
  local split=()
  [ "$p" -gt 1 ] && split=(--processes "$p")
  # shellcheck disable=SC2046,SC2086
  start_server "$label-$n-r$ROUND" "$VDRIVE_READY" "${VDRIVE_CMD_WORDS[@]}" "${split[@]}" --iface "$S_IF" --no-control \
    $(drive_args "$n") ${VDRIVE_OPTS:-} "$@"
}

vdrive_label() { [ "$1" -gt 1 ] && echo "vdrive-p$1" || echo vdrive; }

echo "load average before: $(cat /proc/loadavg)"
status=0
for ((ROUND = 1; ROUND <= ROUNDS; ROUND++)); do
  echo "round $ROUND of $ROUNDS ($(date -u +%H:%M:%S) UTC, load average $(cut -d' ' -f1-3 /proc/loadavg))"
  for n in $DRIVES; do
    for p in $PROCESSES; do
      label=$(vdrive_label "$p")
      vdrive_line "$label" "$n" "$p"
      measure "$label" "$n" op || status=1
      stop_server
    done
    if [ -n "${BATCH_US:-}" ]; then
      vdrive_line vdrive-batched "$n" 1 --batch-steps-us "$BATCH_US"
      measure vdrive-batched "$n" op || status=1
      stop_server
    fi
    if [ -n "${WEB_PAGE:-}" ]; then
      vdrive_line vdrive-web "$n" 1 --web 127.0.0.1:8377
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
    # The echo's frame as long as this round's first vdrive line's for this N.
    image=$(grep "\"label\":\"$(vdrive_label "${PROCESSES%% *}")/$n\".*\"round\":$ROUND}" "$RESULTS" | head -1 |
      sed -n 's/.*"image_bytes":\([0-9]*\).*/\1/p')
    # shellcheck disable=SC2086
    start_server "echo-$n-r$ROUND" "" "$ECHO" --iface "$S_IF" ${ECHO_OPTS:-}
    measure echo "$n" echo --image-bytes "${image:-64}" || status=1
    stop_server
    if [ -n "$KICKCAT_SIM" ]; then
      slaves=()
      for ((i = 0; i < n; i++)); do slaves+=("$KICKCAT_SLAVE"); done
      start_server "kickcat-$n-r$ROUND" "Opening nominal interface" "$KICKCAT_SIM" -i "$S_IF" -s "${slaves[@]}"
      measure kickcat "$n" op || status=1
      stop_server
    fi
  done
done
echo "load average after: $(cat /proc/loadavg)"

python3 "$(dirname "$0")/table.py" "$RESULTS"
[ -n "$KEEP" ] && echo "results: $RESULTS"
exit $status
