#!/usr/bin/env bash
# The container wiring of docs/docker.md without Docker: two network namespaces stand for the
# vdrive and the master container (network_mode: none), each with a process inside to name it
# by, as Docker's State.Pid names a container.
# - docker/veth-between.sh (given pid:N) cables them: an end in each, renamed, up; its refusals
#   (bad arguments, one namespace twice, a name already taken) exit 2/1 and change nothing;
# - docker/entrypoint.sh: runs its arguments; VDRIVE_WAIT_IFACE waits for an interface that
#   appears later and brings it up, or exits 3 naming it; VDRIVE_WAIT_LINE waits for a line to
#   answer; a bad VDRIVE_WAIT_TIMEOUT is exit 2;
# - end to end: `vdrive run` in one namespace, started through the entrypoint, and
#   `vdrive-master scan` in the other find the three drives over that veth.
# Usage: bash docker_network_test.sh <path-to-vdrive> <build-dir> <source-dir>. Root; 77 = skipped.
set -u
VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
SRC=${3:?source directory}
MASTER="$BUILD/master/vdrive-master"
skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
[ "$(id -u)" -eq 0 ] || skip "needs root (network namespaces, veth)"
for t in ip nsenter; do command -v $t >/dev/null || skip "$t not installed"; done
[ -x "$VDRIVE" ] && [ -x "$MASTER" ] || fail "vdrive or vdrive-master not built"
VETH="$SRC/docker/veth-between.sh"
ENTRY="$SRC/docker/entrypoint.sh"

NS_A="vdka-$$" NS_B="vdkb-$$"
WORK=$(mktemp -d)
PIDS=()
cleanup() {
  local p
  for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done
  ip netns del "$NS_A" 2>/dev/null; ip netns del "$NS_B" 2>/dev/null   # takes the veth with it
  ip link del "vdkx$$" 2>/dev/null
  rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

ip netns add "$NS_A" && ip netns add "$NS_B" || fail "cannot create namespaces"
ip netns exec "$NS_A" sleep 600 & PIDS+=($!); PID_A=$!
ip netns exec "$NS_B" sleep 600 & PIDS+=($!); PID_B=$!
sleep 0.2
# veth-between.sh makes its pair under the temporary names vb<pid>a/vb<pid>b in this namespace;
# none may be left here (other interfaces come and go: other tests share the host).
leftovers() { ip -o link | awk -F': ' '{print $2}' | cut -d@ -f1 | grep -E '^vb[0-9]+[ab]$'; }
[ -z "$(leftovers)" ] || fail "temporary veth names already present: $(leftovers)"

# --- refusals -----------------------------------------------------------------------------------
expect_exit() {  # CODE TEXT CMD...: the command exits CODE and says TEXT on stderr
  local code=$1 text=$2; shift 2
  "$@" >"$WORK/out" 2>"$WORK/err"; local rc=$?
  [ $rc -eq "$code" ] || fail "$* exited $rc, expected $code: $(cat "$WORK/err")"
  grep -q -- "$text" "$WORK/err" || fail "$*: message '$(cat "$WORK/err")' lacks '$text'"
}
expect_exit 2 usage bash "$VETH" "pid:$PID_A" ecat0
expect_exit 2 usage bash "$VETH" "pid:x" ecat0 "pid:$PID_B" ecat0
expect_exit 1 "bad interface name" bash "$VETH" "pid:$PID_A" "much-too-long-name" "pid:$PID_B" ecat0
expect_exit 1 "share one network namespace" bash "$VETH" "pid:$PID_A" e0 "pid:$PID_A" e1
expect_exit 1 "is not running" bash "$VETH" "pid:999999999" e0 "pid:$PID_B" e1
ip -n "$NS_B" link add taken type veth peer name taken-peer || fail "cannot make an interface in $NS_B"
expect_exit 1 "already has an interface 'taken'" bash "$VETH" "pid:$PID_A" ecat0 "pid:$PID_B" taken
ip -n "$NS_B" link del taken
[ -z "$(leftovers)" ] || fail "a refused veth-between left an interface behind: $(leftovers)"
[ -z "$(ip -n "$NS_A" -o link show type veth)" ] || fail "a refused veth-between left a veth in $NS_A"
echo "ok: veth-between.sh refusals"

# --- entrypoint ---------------------------------------------------------------------------------
[ "$(bash -c "\"$ENTRY\" echo hello")" = hello ] || fail "entrypoint does not run its arguments"
expect_exit 2 "VDRIVE_WAIT_TIMEOUT" env VDRIVE_WAIT_IFACE=x VDRIVE_WAIT_TIMEOUT=soon "$ENTRY" true
expect_exit 3 "interface 'ecat0' did not appear within 1 s" \
  nsenter -t "$PID_A" -n env VDRIVE_WAIT_IFACE=ecat0 VDRIVE_WAIT_TIMEOUT=1 "$ENTRY" true
echo "ok: entrypoint without and with a missing interface"

# --- cable them, serve through the entrypoint, scan from the other side ------------------------
# vdrive's end: the entrypoint waits (as in the vdrive-line container) before vdrive run starts.
nsenter -t "$PID_A" -n env VDRIVE_WAIT_IFACE=ecat0 VDRIVE_WAIT_TIMEOUT=30 \
  "$ENTRY" "$VDRIVE" run --iface ecat0 --no-control --drive a6b --drive ds5c1 --drive ds1000a \
  >"$WORK/vdrive.log" 2>&1 &
VD=$!; PIDS+=($VD)
sleep 0.5
kill -0 $VD 2>/dev/null || { cat "$WORK/vdrive.log"; fail "the entrypoint did not wait for ecat0"; }
bash "$VETH" "pid:$PID_A" ecat0 "pid:$PID_B" ecat0 >"$WORK/veth.out" 2>&1 || { cat "$WORK/veth.out"; fail "veth-between.sh"; }
grep -q "pid:$PID_A:ecat0 <-> pid:$PID_B:ecat0" "$WORK/veth.out" || fail "veth-between.sh said: $(cat "$WORK/veth.out")"
for ns in "$NS_A" "$NS_B"; do
  ip -n "$ns" -o link show ecat0 | grep -q "state UP\|,UP" || fail "ecat0 in $ns is not up: $(ip -n "$ns" -o link show ecat0)"
  ip -n "$ns" -d -o link show ecat0 | grep -q " veth " || fail "ecat0 in $ns is not a veth"
done
[ -z "$(leftovers)" ] || fail "veth-between.sh left an interface in the host namespace: $(leftovers)"
# The master's end waits for the line to answer (VDRIVE_WAIT_LINE), then scans.
nsenter -t "$PID_B" -n env PATH="$(dirname "$MASTER"):$PATH" \
  VDRIVE_WAIT_IFACE=ecat0 VDRIVE_WAIT_LINE=1 VDRIVE_WAIT_TIMEOUT=30 \
  "$ENTRY" "$MASTER" scan --iface ecat0 >"$WORK/scan.out" 2>&1 || { cat "$WORK/scan.out" "$WORK/vdrive.log"; fail "scan over the veth"; }
cat "$WORK/scan.out"
for name in MADLN15BE DS5C1 DS1000A-EC; do grep -q "$name" "$WORK/scan.out" || fail "scan did not find $name"; done
kill -0 $VD 2>/dev/null || { cat "$WORK/vdrive.log"; fail "vdrive run ended"; }
# A second cable with a name taken on one side is refused and leaves nothing behind.
expect_exit 1 "already has an interface 'ecat0'" bash "$VETH" "pid:$PID_A" ecat0 "pid:$PID_B" ecat1
[ -z "$(leftovers)" ] || fail "a refused veth-between left an interface behind: $(leftovers)"
echo "ok: entrypoint + veth-between + vdrive run + vdrive-master scan"
echo PASS
