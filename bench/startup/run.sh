#!/usr/bin/env bash
# Start-up time: how long a master takes to bring a line of three drives
# (a6b, ds5c1, ds1000a, served by `vdrive run` in a network namespace on one end of a veth pair it
# makes itself) from power-on state to Op. One command:
#
#   bench/startup/run.sh [BUILD_DIR]          (root; BUILD_DIR default ./build)
#
# Measured: from the master's process start to the line it prints once every slave reports Op
# (`vdrive-master op`: "Op"; SOEM simple_test: "Operational state reached for all slaves."),
# timestamped as it is read (bash $EPOCHREALTIME, masters run line-buffered through stdbuf).
# vdrive is restarted before every run, so each start-up begins from Init with a fresh line.
# Environment: RUNS=5; SOEM_SIMPLE_TEST=PATH also times SOEM's simple_test (built by hand, see
# docs/performance.md). Exit 0, 1 a run failed, 77 not root.
set -u

BUILD=$(cd "${1:-build}" && pwd) || { echo "no build directory ${1:-build}"; exit 1; }
VDRIVE="$BUILD/vdrive/vdrive"
MASTER="$BUILD/master/vdrive-master"
RUNS=${RUNS:-5}
SOEM_SIMPLE_TEST=${SOEM_SIMPLE_TEST:-}
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root (network namespace, veth, raw sockets)"; exit 77; }
for f in "$VDRIVE" "$MASTER"; do [ -x "$f" ] || { echo "missing $f (build it first)"; exit 1; }; done

NS="vdsu-$$"
M_IF="vdsum$$"
S_IF="vdsus$$"
WORK=$(mktemp -d)
VDRIVE_PID=""
stop_line() {
  [ -n "$VDRIVE_PID" ] && kill "$VDRIVE_PID" 2>/dev/null && wait "$VDRIVE_PID" 2>/dev/null
  VDRIVE_PID=""
}
cleanup() {
  stop_line
  ip link del "$M_IF" 2>/dev/null
  ip netns del "$NS" 2>/dev/null
  rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

ip netns add "$NS" || exit 1
ip link add "$M_IF" type veth peer name "$S_IF" || exit 1
ip link set "$S_IF" netns "$NS"
ip link set "$M_IF" up
ip -n "$NS" link set "$S_IF" up

start_line() {
  ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" --no-control --drive a6b --drive ds5c1 --drive ds1000a \
    >"$WORK/vdrive.log" 2>&1 &
  VDRIVE_PID=$!
  local _
  for _ in $(seq 1 50); do   # until its socket is open (the log says "serving")
    grep -q "serving" "$WORK/vdrive.log" 2>/dev/null && return 0
    kill -0 "$VDRIVE_PID" 2>/dev/null || break
    sleep 0.1
  done
  cat "$WORK/vdrive.log"; echo "vdrive did not start"; exit 1
}

# time_to_op LABEL PATTERN COMMAND...: milliseconds from start to the first output line matching
# PATTERN, appended to $WORK/LABEL; the rest of the output goes to $WORK/LABEL.log.
time_to_op() {
  local label=$1 pattern=$2; shift 2
  local start=$EPOCHREALTIME line t=""
  while IFS= read -r line; do
    echo "$line" >>"$WORK/$label.log"
    if [ -z "$t" ] && [[ $line =~ $pattern ]]; then t=$EPOCHREALTIME; fi
  done < <(stdbuf -oL "$@" 2>&1)
  [ -n "$t" ] || { tail -20 "$WORK/$label.log"; echo "FAILED: $label never reached Op"; return 1; }
  awk -v a="$start" -v b="$t" 'BEGIN { printf "%.1f\n", (b - a) * 1000 }' >>"$WORK/$label"
}

echo "load average before: $(cat /proc/loadavg)"
status=0
for _ in $(seq 1 "$RUNS"); do
  start_line
  time_to_op "vdrive-master op" '^Op$' "$MASTER" op --iface "$M_IF" --cycles 1 || status=1
  stop_line
  start_line
  time_to_op "vdrive-master op --dc" '^Op$' "$MASTER" op --iface "$M_IF" --dc --cycles 1 || status=1
  stop_line
  if [ -n "$SOEM_SIMPLE_TEST" ]; then
    start_line
    # simple_test runs 10,000 cycles after Op; the time to Op is all that is read here.
    time_to_op "SOEM simple_test" 'Operational state reached for all slaves' timeout 60 "$SOEM_SIMPLE_TEST" "$M_IF" || status=1
    stop_line
  fi
done
echo "load average after: $(cat /proc/loadavg)"

echo "| master | runs | min ms | median ms | max ms |"
echo "|---|---|---|---|---|"
for label in "vdrive-master op" "vdrive-master op --dc" "SOEM simple_test"; do
  [ -f "$WORK/$label" ] || continue
  sort -n "$WORK/$label" | awk -v l="$label" '{ v[NR] = $1 } END {
    printf "| %s | %d | %.1f | %.1f | %.1f |\n", l, NR, v[1], (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2), v[NR] }'
done
exit $status
