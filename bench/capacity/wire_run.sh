#!/usr/bin/env bash
# Capacity over the wire, for a line served by one or more processes (`vdrive run --processes P`):
# the largest line (a6b, ds5c1, ds1000a in turn) that the project master runs in Op with DC at a
# 1 ms cycle for RTCYCLES real-time cycles. Each trial is a fresh namespace, veth pair and `vdrive
# run`; vdrive's parts run SCHED_FIFO 80 on CPUs 0..P-1, the master SCHED_FIFO 70, not pinned.
# For each P: N doubles from START while trials pass, then bisection.
#
# A trial passes (CRITERION):
#   on-time (default)  every frame answered (within REPLY_TIMEOUT_US, default 20000: on a VM whose
#                      wake-ups run milliseconds late now and then, a 1 ms timeout loses frames of
#                      the raw-socket echo too), 0 wrong working counters, every slave in Op
#                      throughout, and no missed deadline in any part once the line was in Op: no
#                      part's loop ran the line's timers (SYNC0, the control steps) a cycle late,
#                      no "host stall" in its log (docs/reliability.md "Host stalls";
#                      stalls_in_op.py);
#   headroom           the first three, and every part's serving thread busy for at most MAX_CPU
#                      percent (default 85) of its core while the master ran: the firmware keeps
#                      up with room left for the kernel's real-time throttling (at 95 %), the
#                      master and the VM's gaps, which the on-time criterion counts as misses
#                      (docs/reliability.md "Gaps of the VM itself");
#   op                 the first three only: the line answers and stays in Op, even when the
#                      firmware falls behind (frames overtake it, late control steps catch up).
# A failed trial runs once more (RETRY=1, 0 for none) and the trial passes if that run does: the
# host's noise only ever makes a trial fail, never pass.
# Each trial prints the master's summary, every part's host stalls (once in Op, and over the whole
# run), and the CPU each part's serving thread used while the master ran, from start-up to the
# last cycle (% of one core; 100 % means it never waited).
#
# Usage: bash bench/capacity/wire_run.sh [BUILD_DIR]      (root)
# Environment: PROCESSES (default "1 2"), RTCYCLES (10000), START (32), MAXN (512), CYCLE_US (1000),
#              REPLY_TIMEOUT_US (20000), CRITERION (on-time), MAX_CPU (85), RETRY (1),
#              VDRIVE_OPTS (extra `vdrive run` options), KEEP (a directory, made if need be: the
#              last run's vdrive.log and op.txt are copied into it).
set -u
BUILD=$(cd "${1:-build}" && pwd) || exit 1
VDRIVE="$BUILD/vdrive/vdrive"
HERE=$(cd "$(dirname "$0")" && pwd)
MASTER="$BUILD/master/vdrive-master"
PROCESSES=${PROCESSES:-1 2}
RTCYCLES=${RTCYCLES:-10000}
START=${START:-32}
MAXN=${MAXN:-512}
CYCLE_US=${CYCLE_US:-1000}
REPLY_TIMEOUT_US=${REPLY_TIMEOUT_US:-20000}
CRITERION=${CRITERION:-on-time}
RETRY=${RETRY:-1}
MAX_CPU=${MAX_CPU:-85}
case "$CRITERION" in on-time|headroom|op) ;; *) echo "wire_run.sh: CRITERION must be on-time, headroom or op, not '$CRITERION'" >&2; exit 2;; esac
case "$MAX_CPU" in [1-9]|[1-9][0-9]|100) ;; *) echo "wire_run.sh: MAX_CPU must be a percentage from 1 to 100, not '$MAX_CPU'" >&2; exit 2;; esac
case "$RETRY" in 0|1) ;; *) echo "wire_run.sh: RETRY must be 0 or 1, not '$RETRY'" >&2; exit 2;; esac
[ "$(id -u)" -eq 0 ] || { echo "wire_run.sh: needs root (namespaces, veth, SCHED_FIFO)" >&2; exit 77; }
for f in "$VDRIVE" "$MASTER"; do [ -x "$f" ] || { echo "wire_run.sh: $f not built" >&2; exit 1; }; done

NS="vdcap-$$"; M_IF="vdcm$$"; S_IF="vdcs$$"; PID=""
WORK=$(mktemp -d)
cleanup() {
  [ -n "$PID" ] && kill "$PID" 2>/dev/null && wait "$PID" 2>/dev/null
  ip link del "$M_IF" 2>/dev/null; ip netns del "$NS" 2>/dev/null; [ -n "${KEEP:-}" ] && mkdir -p "$KEEP" && cp "$WORK"/* "$KEEP"/; rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(uname -r); $(date -u '+%Y-%m-%d %H:%M UTC')"

drives() {  # N -> the --drive list
  local i ids=(a6b ds5c1 ds1000a) out=()
  for ((i = 0; i < $1; i++)); do out+=("${ids[i % 3]}"); done
  echo "${out[@]}"
}

# Time on a CPU (ns, the scheduler's own sum, /proc/PID/task/TID/schedstat) of each process's main
# thread, the one that serves. Not utime + stime: those are sampled at the scheduler tick, and a
# loop that wakes 8,000 times a second in step with the tick is charged whole ticks it mostly slept.
serving_ns() {
  local p
  for p in "$@"; do cut -d' ' -f1 "/proc/$p/task/$p/schedstat" 2>/dev/null || echo 0; done
}

# One run of a trial: P processes, N drives. Prints what it saw; succeeds when it passes.
run_once() {
  local p=$1 n=$2 summary stalls="" cpu="" ok=1 busiest=100
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
    # Part 1 forks the others (part_processes.cpp), so they are its children.
    local parts=("$PID") t0 t1 ns0 ns1
    mapfile -t -O 1 parts < <(pgrep -P "$PID" | sort -n)
    t0=$(date +%s%N); mapfile -t ns0 < <(serving_ns "${parts[@]}")
    "$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us "$CYCLE_US" --cycles "$RTCYCLES" \
      --reply-timeout-us "$REPLY_TIMEOUT_US" >"$WORK/op.txt" 2>&1
    t1=$(date +%s%N); mapfile -t ns1 < <(serving_ns "${parts[@]}")
    local k share
    busiest=0
    for k in "${!parts[@]}"; do
      share=$(( (${ns1[k]:-0} - ${ns0[k]:-0}) * 100 / (t1 - t0) ))
      cpu+=" $share%"; [ "$share" -gt "$busiest" ] && busiest=$share
    done
    summary=$(grep '^summary:' "$WORK/op.txt" || tail -1 "$WORK/op.txt")
  else
    summary="the line did not answer with $n slaves (found $found)"
  fi
  kill "$PID" 2>/dev/null; wait "$PID" 2>/dev/null; PID=""
  ip link del "$M_IF" 2>/dev/null; ip netns del "$NS" 2>/dev/null
  # Part by part: "none" or "K, longest X ms"; over the whole run, and once the line was in Op.
  stalls=$(grep -o 'host stalls: [^(]*' "$WORK/vdrive.log" | sed 's/host stalls: //; s/ *$//' | paste -sd'/' -)
  local in_op on_time=1
  in_op=$(python3 "$HERE/stalls_in_op.py" "$WORK/vdrive.log" "$p") || on_time=0
  echo "$summary" | grep -Eq "^summary: $RTCYCLES cycles .* 0 wrong, 0 lost, 0 not all in Op" || ok=0
  if [ "$CRITERION" = on-time ] && [ "$on_time" = 0 ]; then ok=0; fi
  if [ "$CRITERION" = headroom ] && [ "$busiest" -gt "$MAX_CPU" ]; then ok=0; fi
  echo "  processes $p, $n drives: $summary; host stalls part by part in Op: $in_op (whole run: ${stalls:-not reported}); serving CPU:${cpu:- not measured}; load $(cut -d' ' -f1 /proc/loadavg)$([ "$ok" = 1 ] && echo ' -> pass' || echo ' -> fail')" >&2
  [ "$ok" = 1 ]
}

# One trial: a run, and one more when it failed and RETRY is 1.
trial() {
  run_once "$1" "$2" && return 0
  [ "$RETRY" = 1 ] || return 1
  echo "  (once more: the host's noise only ever fails a run)" >&2
  run_once "$1" "$2"
}

for p in $PROCESSES; do
  echo "processes $p: $RTCYCLES cycles of $CYCLE_US us per trial, criterion $CRITERION$([ "$CRITERION" = headroom ] && echo " (at most $MAX_CPU % of a core)")"
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
  echo "RESULT processes $p: $good drives at $CYCLE_US us ($RTCYCLES cycles, criterion $CRITERION; $limit)"
done
