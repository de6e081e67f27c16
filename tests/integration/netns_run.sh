#!/usr/bin/env bash
# Integration (issue 24 item 3): the quickstart's layout, the drives' end of the veth inside a
# namespace, served by `vdrive run --netns NS --iface S_IF --telemetry` started in the root
# namespace: the master on the root end finds the line, and `vdrive telemetry` and `vdrive fault`
# in the root namespace reach the run (DDS and the control socket stay where the user is). A
# subscriber in a domain where nothing publishes says so and exits 1.
#
# Usage: bash netns_run.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools

DOMAIN=$((100 + $$ % 100))
ip netns add "$NS" || fail "cannot create namespace $NS"
ip link add "$M_IF" type veth peer name "$S_IF" || fail "cannot create veth pair"
ip link set "$S_IF" netns "$NS" || fail "cannot move $S_IF into $NS"
ip link set "$M_IF" up
ip -n "$NS" link set "$S_IF" up
"$VDRIVE" run --netns "$NS" --iface "$S_IF" --drive a6b ds5c1 --telemetry --domain "$DOMAIN" --no-status \
  >"$WORK/vdrive.log" 2>&1 &
VDRIVE_PID=$!
wait_for_line
grep -q "serving 2 slave(s) on $S_IF in namespace $NS" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "the log does not name the namespace"; }

timeout 60 "$VDRIVE" telemetry --domain "$DOMAIN" --count 20 --quiet --csv "$WORK/t.csv" 2>"$WORK/t.err"
rc=$?
cat "$WORK/t.err"
[ $rc -eq 0 ] || fail "vdrive telemetry in the root namespace exited $rc"
rows=$(($(wc -l <"$WORK/t.csv") - 1))
[ "$rows" -ge 20 ] || fail "vdrive telemetry received $rows samples, not 20"

out=$("$VDRIVE" fault inject --iface "$S_IF" overload --slave 2 2>&1) || fail "vdrive fault from the root namespace: $out"
echo "$out" | grep -q "injected" || fail "vdrive fault: $out"

timeout 60 "$VDRIVE" telemetry --domain "$((DOMAIN + 1))" --duration 1 --quiet 2>"$WORK/none.err"
rc=$?
cat "$WORK/none.err"
[ $rc -eq 1 ] || fail "a subscriber that heard nothing exited $rc, not 1"
grep -q "no telemetry heard in domain $((DOMAIN + 1))" "$WORK/none.err" || fail "a subscriber that heard nothing did not say so"
echo "PASS"
