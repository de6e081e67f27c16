#!/usr/bin/env bash
# Integration: `vdrive run --eni eni_only.xml` with no ESI at all serves the ENI's two slaves (a
# CoE module with RxPDO 1601h and TxPDO 1A00h, and a simple input terminal) from the ENI alone,
# with a warning each; `vdrive-master` on the other end of the veth pair scans them with the ENI's
# identities, maps them from their SII (the ENI's own mapping) and runs them in Op with DC.
#
# Usage: bash eni_only.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
PRODUCTS="$(cd "$(dirname "$0")/../products" && pwd)"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools python3

start_line --eni "$PRODUCTS/networks/eni_only.xml"
wait_for_line --state preop --json
cp "$WORK/scan.out" "$WORK/scan.json"
grep -q "served from the ENI alone" "$WORK/vdrive.log" || { cat "$WORK/vdrive.log"; fail "no warning that the slaves are served from the ENI alone"; }
python3 - "$WORK/scan.json" <<'PY' || fail "scan result wrong"
import json, sys
scan = json.load(open(sys.argv[1]))
slaves = scan["slaves"]
assert [s["product_code"] for s in slaves] == ["0x00001234", "0x00005678"], [s["product_code"] for s in slaves]
assert all(s["state"] == "Pre-Op" and not s["al_error"] for s in slaves), slaves
print("scan: the ENI's two slaves with its identities, in Pre-Op")
PY

"$MASTER" op --iface "$M_IF" --dc --cycle-us 1000 --cycles 1000 --reply-timeout-us 200000 \
  >"$WORK/op.txt" 2>"$WORK/op.err"
rc=$?
cat "$WORK/op.txt" "$WORK/op.err"
[ $rc -eq 0 ] || fail "vdrive-master op exited $rc"
grep -Eq "^summary: 1000 cycles of 1000 us, working counter [0-9]+ expected, 0 wrong, 0 lost, 0 not all in Op" "$WORK/op.txt" \
  || fail "summary is not 1000 cycles with zero wrong working counters"
echo "PASS"
