#!/usr/bin/env bash
# Integration: `vdrive run --network tests/products/networks/bench.yaml` serves a bench described
# once (a coupler with a digital input and output terminal on its E-bus port and an ESI drive on its
# second port, cabled as a tree) inside a network namespace; `vdrive-master scan` on the other end
# of the veth pair must find the four slaves in the order a frame visits them, and `vdrive-master op --dc` must run them in Op with zero wrong working counters.
# A network file with a mistake must be refused with its file, line and field, exit 2.
#
# Usage: bash network_bench.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
BENCH="$(cd "$(dirname "$0")/../products/networks" && pwd)/bench.yaml"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools python3

# A mistake first (no interface needed: the file is read before the link is opened).
printf 'slaves:\n  - {device: a6b, parnet: 1}\n' >"$WORK/typo.yaml"
err=$("$VDRIVE" run --iface lo --no-control --network "$WORK/typo.yaml" 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] || fail "a network file with a typo: exit $rc, expected 2 ($err)"
echo "$err" | grep -q "typo.yaml:2: slaves\[0\]: unknown key 'parnet', did you mean 'parent'?" \
  || fail "the typo is not named: $err"
echo "ok: typo -> $err"

start_line --network "$BENCH"
wait_for_line --state preop --json
cp "$WORK/scan.out" "$WORK/scan.json"
python3 - "$WORK/scan.json" <<'PY' || fail "scan result wrong"
import json, sys
scan = json.load(open(sys.argv[1]))
slaves = scan["slaves"]
expected = ["0x044C2C52", "0x03F03052", "0x07D83052", "0x00000402"]
assert [s["product_code"] for s in slaves] == expected, [s["product_code"] for s in slaves]
assert all(s["state"] == "Pre-Op" and not s["al_error"] for s in slaves), slaves
assert scan["state_reached"] is True
print("scan: coupler, its E-bus terminals, then the drive on port 1, all in Pre-Op")
PY

"$MASTER" op --iface "$M_IF" --dc --cycle-us 1000 --cycles 2000 --reply-timeout-us 200000 \
  >"$WORK/op.txt" 2>"$WORK/op.err"
rc=$?
cat "$WORK/op.txt" "$WORK/op.err"
[ $rc -eq 0 ] || fail "vdrive-master op exited $rc"
grep -Eq "^summary: 2000 cycles of 1000 us, working counter [0-9]+ expected, 0 wrong, 0 lost, 0 not all in Op" "$WORK/op.txt" \
  || fail "summary is not 2000 cycles with zero wrong working counters"
echo "PASS"
