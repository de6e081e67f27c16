# Sourced by the integration scripts: a line of drives served by `vdrive run` inside a network
# namespace on one end of a veth pair, the master end in the root namespace, and a trap that
# removes everything made here (processes, namespace, veth, temporary files) whatever happens.
#
# The caller sets VDRIVE and MASTER, then calls:
#   require_tools TOOL...     skip (exit 77) unless root and every TOOL is installed
#   make_veth_line [lo]       namespace + veth, nothing served yet (lo: the namespace's loopback up,
#                             which DDS telemetry needs)
#   start_line [ARGS...]      make_veth_line + `vdrive run --iface S_IF ARGS...` (log: $WORK/vdrive.log)
#   restart_line [ARGS...]    stop that `vdrive run` and start another on the same veth pair
#   start_capture FILE        tshark on the master end, into FILE, until stop_capture
#   wait_for_line [ARGS...]   retry `vdrive-master scan --iface M_IF ARGS...` until it answers
#                             (its output: $WORK/scan.out, errors: $WORK/scan.err)
#   stop_capture
#   alarms_followed_host_stalls   whether vdrive raised alarms and every one came right after a
#                             host stall (its log ends such lines "after a host stall of N ms"):
#                             a run that failed so failed for the host, not for vdrive
#   sine_failed_for_host OUT  whether a failed `vdrive-master op --sine` (its output in OUT) failed
#                             for the host: the master itself sent a cycle 2 ms or more late (its
#                             "worst lateness"; a drive then gets a set-point 2 cycles ahead at
#                             once), or alarms_followed_host_stalls
# Names: NS, M_IF (master end), S_IF (drives' end), WORK (temporary directory).

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

require_tools() {
  [ "$(id -u)" -eq 0 ] || skip "needs root (network namespaces, veth, raw sockets)"
  local tool
  for tool in ip "$@"; do
    command -v "$tool" >/dev/null || skip "$tool not installed"
  done
  [ -x "$VDRIVE" ] || fail "vdrive not found at $VDRIVE"
  [ -x "$MASTER" ] || fail "vdrive-master not found at $MASTER"
}

NS="vdt-$$"
M_IF="vdtm$$"          # master end, root namespace (IFNAMSIZ: at most 15 characters)
S_IF="vdts$$"          # drives' end, inside $NS
WORK=$(mktemp -d)
VDRIVE_PID=""
TSHARK_PID=""

cleanup() {
  [ -n "$TSHARK_PID" ] && kill "$TSHARK_PID" 2>/dev/null && wait "$TSHARK_PID" 2>/dev/null
  [ -n "$VDRIVE_PID" ] && kill "$VDRIVE_PID" 2>/dev/null && wait "$VDRIVE_PID" 2>/dev/null
  ip link del "$M_IF" 2>/dev/null
  ip netns del "$NS" 2>/dev/null
  rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

make_veth_line() {
  ip netns add "$NS" || fail "cannot create namespace $NS"
  [ "${1:-}" = lo ] && ip -n "$NS" link set lo up
  ip link add "$M_IF" type veth peer name "$S_IF" || fail "cannot create veth pair"
  ip link set "$S_IF" netns "$NS" || fail "cannot move $S_IF into $NS"
  ip link set "$M_IF" up
  ip -n "$NS" link set "$S_IF" up
}

start_line() {
  make_veth_line
  ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" "$@" >"$WORK/vdrive.log" 2>&1 &
  VDRIVE_PID=$!
}

restart_line() {
  kill "$VDRIVE_PID" 2>/dev/null; wait "$VDRIVE_PID" 2>/dev/null
  ip netns exec "$NS" "$VDRIVE" run --iface "$S_IF" "$@" >"$WORK/vdrive.log" 2>&1 &
  VDRIVE_PID=$!
}

start_capture() {
  tshark -i "$M_IF" -f "ether proto 0x88a4" -w "$1" >"$WORK/tshark.log" 2>&1 &
  TSHARK_PID=$!
  local _
  for _ in $(seq 1 100); do   # tshark reports "Capturing on" once the capture runs
    grep -q "Capturing on" "$WORK/tshark.log" 2>/dev/null && return 0
    kill -0 "$TSHARK_PID" 2>/dev/null || { cat "$WORK/tshark.log"; fail "tshark did not start"; }
    sleep 0.1
  done
}

stop_capture() {
  sleep 0.5                   # let tshark write the last frames
  kill -INT "$TSHARK_PID"; wait "$TSHARK_PID" 2>/dev/null; TSHARK_PID=""
}

# vdrive needs a moment to open its socket: retry the scan until it answers (or give up).
wait_for_line() {
  local _
  for _ in $(seq 1 20); do
    kill -0 "$VDRIVE_PID" 2>/dev/null || { cat "$WORK/vdrive.log"; fail "vdrive run exited early"; }
    "$MASTER" scan --iface "$M_IF" "$@" >"$WORK/scan.out" 2>"$WORK/scan.err" && return 0
    sleep 0.25
  done
  cat "$WORK/scan.err" "$WORK/vdrive.log"
  fail "no line answers on $M_IF (vdrive-master scan $*)"
}

alarms_followed_host_stalls() {
  local alarms
  alarms=$(grep -E "\] slave [0-9]+ @0x[0-9A-F]{4} [^:]*: alarm " "$WORK/vdrive.log")
  [ -n "$alarms" ] && ! echo "$alarms" | grep -qv "after a host stall of "
}

sine_failed_for_host() {
  local late
  late=$(sed -n 's/.* worst lateness \([0-9]*\) us .*/\1/p' "$1" | head -1)
  [ -n "$late" ] && [ "$late" -ge 2000 ] && return 0
  alarms_followed_host_stalls
}
