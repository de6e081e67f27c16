#!/usr/bin/env bash
# Integration: `vdrive run --eni bench_eni.xml --esi-dir tests/products/esi` serves the network a
# master's ENI describes (the bench's coupler, terminals and ESI drive, matched to the ESI files of
# the search directory, plus an A6B model matched to the built-in A6B and served with the ENI's
# product code) as a tree; `vdrive-master scan`
# on the other end of the veth pair finds the five slaves in the ENI's order and identities.
#
# Usage: bash eni_bench.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
PRODUCTS="$(cd "$(dirname "$0")/../products" && pwd)"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools python3

start_line --eni "$PRODUCTS/networks/bench_eni.xml" --esi-dir "$PRODUCTS/esi"
wait_for_line --state preop --json
cp "$WORK/scan.out" "$WORK/scan.json"
grep -q "built-in product a6b" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "the log does not say how the A6B was matched"; }
python3 - "$WORK/scan.json" <<'PY' || fail "scan result wrong"
import json, sys
scan = json.load(open(sys.argv[1]))
slaves = scan["slaves"]
expected = ["0x044C2C52", "0x03F03052", "0x07D83052", "0x00000402", "0x613C0005"]
assert [s["product_code"] for s in slaves] == expected, [s["product_code"] for s in slaves]
assert [s["parent"] for s in slaves] == [0, 1, 2, 1, 4], [s["parent"] for s in slaves]
assert all(s["state"] == "Pre-Op" and not s["al_error"] for s in slaves), slaves
print("scan: the ENI's five slaves in its order, the tree as its PreviousPorts say, all in Pre-Op")
PY
echo "PASS"
