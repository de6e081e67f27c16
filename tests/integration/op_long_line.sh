#!/usr/bin/env bash
# Integration: a line whose process image does not fit one frame. `vdrive run` serves 80 drives
# (a6b, ds5c1, ds1000a in turn) in a network namespace; `vdrive-master op --dc` must cut the image
# into LRW pieces over several frames per cycle (it says how many), take every drive to Op and run
# the cycles with zero wrong working counters and no lost frame. Before the cyclic task split the
# image, no line past 71 drives reached Op.
#
# 2 ms cycles and `vdrive run` at normal priority: the machine this runs on is shared and has 2
# cores, one `vdrive run` thread carries about 71 drives (docs/performance.md), and this test is
# about the frames, not capacity. With `--rt-priority 80` and more drives than its core carries,
# the scan of 128 and of 200 drives failed (2 of 2) with an EEPROM acknowledge error, what the ESC
# reports when a command comes while one runs: most likely a reply later than the master's 20 ms
# made it send the read command again. At normal priority it did not happen in 8 scans; frames
# overtake the firmware, so a loaded loop still answers them.
#
# Usage: [CYCLE_US=2000] [VDRIVE_OPTS="..."] bash op_long_line.sh <path-to-vdrive> <build-dir> [drives] [cycles].
# Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"
DRIVES=${3:-80}
CYCLES=${4:-2000}
CYCLE_US=${CYCLE_US:-2000}

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools

products=(a6b ds5c1 ds1000a)
args=()
for ((i = 0; i < DRIVES; i++)); do args+=(--drive "${products[i % 3]}"); done
# shellcheck disable=SC2086
start_line ${VDRIVE_OPTS:-} --no-control "${args[@]}"
wait_for_line
found=$(grep -c "vendor=0x" "$WORK/scan.out")
[ "$found" -eq "$DRIVES" ] || { cat "$WORK/scan.out"; fail "scan found $found slaves, not $DRIVES"; }

"$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us "$CYCLE_US" --cycles "$CYCLES" \
  --reply-timeout-us 200000 >"$WORK/op.txt" 2>"$WORK/op.err"
rc=$?
grep -Ev "vendor=0x|^slave [0-9]+: |^note: slave " "$WORK/op.txt"; cat "$WORK/op.err"  # one line per drive is too many
[ $rc -eq 0 ] || { tail -20 "$WORK/vdrive.log"; fail "vdrive-master op exited $rc"; }
frames=$(sed -n 's/^cyclic frames: \([0-9]*\) per cycle.*/\1/p' "$WORK/op.txt")
[ -n "$frames" ] && [ "$frames" -ge 2 ] || fail "the master did not split the process image (cyclic frames: '${frames}')"
grep -Eq "^summary: $CYCLES cycles of $CYCLE_US us, working counter $((3 * DRIVES)) expected, 0 wrong, 0 lost, 0 not all in Op" "$WORK/op.txt" \
  || fail "summary is not $CYCLES cycles with zero wrong working counters"
echo "PASS: $DRIVES drives in Op, $frames frames per cycle, $CYCLES cycles, 0 wrong working counters"
