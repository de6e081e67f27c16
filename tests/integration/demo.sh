#!/usr/bin/env bash
# Integration: `vdrive demo` creates its veth pair, finds the three default drives, takes them to
# Pre-Op, then to Op with DC with no wrong working counter, enables each drive in csp and has it
# follow a sine inside its following-error window, exits 0 and leaves no interface behind.
# Usage: bash demo.sh <vdrive> <build-dir>.
set -u
VDRIVE=${1:?path to vdrive}
fail() { echo "FAIL: $*"; exit 1; }
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root"; exit 77; }
command -v ip >/dev/null || { echo "SKIP: ip not installed"; exit 77; }

SUFFIX="$$"                       # vdrive-m<pid>: at most 15 characters
OUT=$(mktemp)
trap 'ip link del "vdrive-m$SUFFIX" 2>/dev/null; rm -f "$OUT"' EXIT

timeout 60 "$VDRIVE" demo --suffix "$SUFFIX" >"$OUT" 2>&1
rc=$?
cat "$OUT"
[ "$rc" -eq 0 ] || fail "vdrive demo exited $rc"
[ "$(grep -cE '0x100[123] .*Pre-Op$' "$OUT")" -eq 3 ] || fail "three slaves in Pre-Op expected"
grep -qE '^Op with DC at 1000 us: [0-9]+ cycles, working counter [0-9]+ expected, 0 wrong, 0 lost' "$OUT" \
  || fail "cycles in Op with zero wrong working counters expected"
[ "$(grep -cE '^slave [123] @0x100[123] [^:]*: ok, ' "$OUT")" -eq 3 ] || fail "three drives following the sine expected"
# The host's stalls are counted (docs/reliability.md "Host stalls"), and each is named.
grep -qE '^host stalls: (none|[0-9]+, longest [0-9.]+ ms)$' "$OUT" || fail "no host stall count"
if ! grep -q '^host stalls: none$' "$OUT"; then grep -qE '^host stall [0-9.]+ ms \(threshold' "$OUT" || fail "a host stall counted but not named"; fi
# Live telemetry over DDS (on by default): each drive seen in Op in csp (mode 8), and moving
# (two different positions of one slave).
for s in 1 2 3; do
  grep -qE "^telemetry: t=[0-9.]+s slave $s @0x100$s Op .* mode=8 " "$OUT" || fail "no telemetry line of slave $s in Op, csp"
done
positions=$(grep -E "^telemetry: .* slave 2 @0x1002 Op .* mode=8 " "$OUT" | sed -n 's/.* pos=\(-\?[0-9]*\) .*/\1/p' | sort -u | wc -l)
[ "$positions" -ge 2 ] || fail "telemetry does not show slave 2 moving ($positions position(s))"
grep -q "MADLN15BE" "$OUT" && grep -q "DS5C1" "$OUT" && grep -q "DS1000A-EC" "$OUT" || fail "drive names missing"
ip link show "vdrive-m$SUFFIX" >/dev/null 2>&1 && fail "veth pair left behind"

# A name that is taken: a clear one-line error, non-zero exit, and the existing interface intact.
ip link add "vdrive-m$SUFFIX" type veth peer name "vdrive-s$SUFFIX" || fail "cannot create test veth"
err=$("$VDRIVE" demo --suffix "$SUFFIX" 2>&1 >/dev/null)
rc=$?
[ "$rc" -ne 0 ] || fail "demo succeeded although vdrive-m$SUFFIX exists"
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "error is not one line: $err"
echo "$err" | grep -q "exists" || fail "error does not say the name exists: $err"
ip link show "vdrive-m$SUFFIX" >/dev/null 2>&1 || fail "demo removed an interface it did not create"
echo PASS
