#!/usr/bin/env bash
# Capacity over the wire, for a line served by one or more processes (`vdrive run --processes P`):
# the largest line (a6b, ds5c1, ds1000a in turn) that the project master runs in Op with DC at a
# 1 ms cycle for RTCYCLES real-time cycles with every frame answered (within REPLY_TIMEOUT_US,
# default 20000: on a VM whose wake-ups run milliseconds late now and then, a 1 ms timeout loses
# frames of the raw-socket echo too, so it would measure the host, not the line), 0 wrong working
# counters and every slave in Op throughout: the line keeps up, and no drive drops out. For each P: N doubles from START while
# trials pass, then bisection; each trial is a fresh namespace, veth pair and `vdrive run`.
# vdrive's parts run SCHED_FIFO 80 on CPUs 0..P-1; the master SCHED_FIFO 70, not pinned.
#
# Usage: bash bench/capacity/wire_run.sh [BUILD_DIR]      (root)
# Environment: PROCESSES (default "1 2"), RTCYCLES (10000), START (32), MAXN (512), CYCLE_US (1000),
#              REPLY_TIMEOUT_US (20000),
#              VDRIVE_OPTS (extra `vdrive run` options).
set -u
BUILD=$(cd "${1:-build}" && pwd) || exit 1
VDRIVE="$BUILD/vdrive/vdrive"
MASTER="$BUILD/master/vdrive-master"
PROCESSES=${PROCESSES:-1 2}
RTCYCLES=${RTCYCLES:-10000}
START=${START:-32}
MAXN=${MAXN:-512}
CYCLE_US=${CYCLE_US:-1000}
REPLY_TIMEOUT_US=${REPLY_TIMEOUT_US:-20000}
[ "$(id -u)" -eq 0 ] || { echo "wire_run.sh: needs root (namespaces, veth, SCHED_FIFO)" >&2; exit 77; }
for f in "$VDRIVE" "$MASTER"; do [ -x "$f" ] || { echo "wire_run.sh: $f not built" >&2; exit 1; }; done

NS="vdcap-$$"; M_IF="vdcm$$"; S_IF="vdcs$$"; PID=""
WORK=$(mktemp -d)
cleanup() {
  [ -n "$PID" ] && kill "$PID" 2>/dev/null && wait "$PID" 2>/dev/null
  ip link del "$M_IF" 2>/dev/null; ip netns del "$NS" 2>/dev/null; rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(uname -r); $(date -u '+%Y-%m-%d %H:%M UTC')"

drives() {  # N -> the --drive list
  local i ids=(a6b ds5c1 ds1000a) out=()
  for ((i = 0; i < $1; i++)); do out+=("${ids[i % 3]}"); done
  echo "${out[@]}"
}

# One trial: P processes, N drives. Prints the master's summary; succeeds when it is clean.
trial() {
  local p=$1 n=$2 summary
  ip netns add "$NS" && ip link add "$M_IF" type veth peer name "$S_IF" && ip link set "$S_IF" netns "$NS" || return 1
  ip link set "$M_IF" up; ip -n "$NS" link set "$S_IF" up
  # shellcheck disable=SC2046
  "$VDRIVE" run --netns "$NS" --iface "$S_IF" --processes "$p" --rt-priority 80 --no-status --no-control ${VDRIVE_OPTS:-} \
    --drive $(drives "$n") >"$WORK/vdrive.log" 2>&1 &
  PID=$!
  local found=0 _
  for _ in $(seq 1 60); do
    found=$("$MASTER" scan --iface "$M_IF" --json 2>/dev/null | python3 -c 'import json,sys; print(len(json.load(sys.stdin)["slaves"]))' 2>/dev/null || echo 0)
    [ "$found" = "$n" ] && break
    kill -0 "$PID" 2>/dev/null || break
    sleep 0.5
  done
  if [ "$found" = "$n" ]; then
    "$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us "$CYCLE_US" --cycles "$RTCYCLES" \
      --reply-timeout-us "$REPLY_TIMEOUT_US" >"$WORK/op.txt" 2>&1
    summary=$(grep '^summary:' "$WORK/op.txt" || tail -1 "$WORK/op.txt")
  else
    summary="the line did not answer with $n slaves (found $found)"
  fi
  kill "$PID" 2>/dev/null; wait "$PID" 2>/dev/null; PID=""
  ip link del "$M_IF" 2>/dev/null; ip netns del "$NS" 2>/dev/null
  echo "  processes $p, $n drives: $summary load $(cut -d' ' -f1 /proc/loadavg)" >&2
  echo "$summary" | grep -Eq "^summary: $RTCYCLES cycles .* 0 wrong, 0 lost, 0 not all in Op"
}

for p in $PROCESSES; do
  echo "processes $p: $RTCYCLES cycles of $CYCLE_US us per trial"
  good=0; bad=0; n=$START
  [ "$n" -lt "$p" ] && n=$p
  while [ "$n" -le "$MAXN" ]; do
    if trial "$p" "$n"; then good=$n; n=$((n * 2)); else bad=$n; break; fi
  done
  [ "$bad" -eq 0 ] && bad=$((MAXN + 1))
  [ "$good" -eq 0 ] && { echo "RESULT processes $p: even $START drives failed"; continue; }
  while [ $((bad - good)) -gt $(( good / 16 > 1 ? good / 16 : 1 )) ]; do
    mid=$(((good + bad) / 2))
    if trial "$p" "$mid"; then good=$mid; else bad=$mid; fi
  done
  if [ "$bad" -gt "$MAXN" ]; then limit="MAXN $MAXN reached"; else limit="$bad failed"; fi
  echo "RESULT processes $p: $good drives at $CYCLE_US us ($RTCYCLES cycles, 0 lost, 0 wrong; $limit)"
done
