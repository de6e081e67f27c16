#!/usr/bin/env bash
# Soak: `vdrive run` serves a6b, ds5c1, ds1000a in a network namespace on one end of a
# veth pair; `vdrive-master op --dc --cycle-us 1000 --sine --seconds SECONDS` on the other end takes
# the line to Op with distributed clocks and moves every drive in csp for SECONDS at 1 kHz.
# vdrive's resident memory (VmRSS) is sampled every INTERVAL seconds. At the end it checks:
#   - no lost frames and no wrong working counters: the master's summary line says 0 wrong, 0 lost,
#     0 not all in Op, and vdrive's own counters at exit say frames in == frames out, 0 dropped,
#     0 send failures;
#   - no resident-memory growth: the largest sample after the baseline is at most
#     RSS_SLACK_KIB (default 256 KiB) above the baseline, the first sample taken BASELINE_S
#     seconds (default 5) after the master reported Op. Start-up (profiles, dictionaries, plants,
#     first touches of stacks and buffers) happens before that; anything that grows with time in
#     Op (a leak, a growing queue or log buffer) shows as a steady climb past the slack.
# The drives' verdicts from the sine program (following error within 6065h, no fault) are reported
# in result.txt but are not a check here: on a loaded host a master cycle can start tens of ms
# late (veth delivery runs in ksoftirqd), and a drive then rightly reports a following error or a
# sync fault. vdrive-master exits 2 for that; the soak accepts exit 2 only with a clean summary.
#
# Usage: bash bench/soak/run.sh [SECONDS] [BUILD_DIR] [OUT_DIR]
#   SECONDS default 3600; BUILD_DIR default build/ next to this checkout; OUT_DIR (kept): rss.csv
#   (seconds since start, RSS KiB), master.txt, vdrive.log, result.txt. Default: a new
#   /tmp/vdrive-soak-<date> directory. Needs root; exit 77 = skipped, 1 = a check failed.
# Environment: INTERVAL (default 5), RSS_SLACK_KIB, BASELINE_S.
set -u

SECONDS_TO_RUN=${1:-3600}
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=${2:-$HERE/../../build}
OUT=${3:-/tmp/vdrive-soak-$(date -u +%Y%m%dT%H%M%SZ)}
INTERVAL=${INTERVAL:-5}
RSS_SLACK_KIB=${RSS_SLACK_KIB:-256}
BASELINE_S=${BASELINE_S:-5}
VDRIVE="$BUILD/vdrive/vdrive"
MASTER="$BUILD/master/vdrive-master"

case "$SECONDS_TO_RUN" in ''|*[!0-9]*) echo "run.sh: SECONDS must be a whole number of seconds, got '$SECONDS_TO_RUN'" >&2; exit 2 ;; esac
[ "$SECONDS_TO_RUN" -ge 10 ] && [ "$SECONDS_TO_RUN" -le 3600 ] || { echo "run.sh: SECONDS must be 10..3600" >&2; exit 2; }
[ -x "$VDRIVE" ] || VDRIVE="$BUILD/vdrive"   # single-directory builds

# shellcheck source=../../tests/integration/lib/veth_line.sh
. "$HERE/../../tests/integration/lib/veth_line.sh"
# shellcheck source=soak_lib.sh
. "$HERE/soak_lib.sh"
require_tools stdbuf
mkdir -p "$OUT" || fail "cannot create $OUT"

soak_header "$OUT/result.txt" "soak: $SECONDS_TO_RUN s, 3 drives (a6b ds5c1 ds1000a), DC at 1 kHz, csp sine"

start_line --rt-priority 80 --drive a6b --drive ds5c1 --drive ds1000a
wait_for_line

# Line-buffered so that the "Op" line shows up while the run goes on (it marks the baseline).
stdbuf -oL "$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us 1000 --sine --seconds "$SECONDS_TO_RUN" \
  --reply-timeout-us 200000 >"$OUT/master.txt" 2>"$OUT/master.err" &
MASTER_PID=$!

echo "seconds,rss_kib" >"$OUT/rss.csv"
t0=$(date +%s)
op_at=""
while kill -0 "$MASTER_PID" 2>/dev/null; do
  rss_sample "$VDRIVE_PID" "$OUT/rss.csv" "$t0" || fail "vdrive exited during the soak"
  [ -z "$op_at" ] && grep -qx "Op" "$OUT/master.txt" && op_at=$(( $(date +%s) - t0 ))
  sleep "$INTERVAL"
done
wait "$MASTER_PID"
master_rc=$?
end_rss=$(rss_kib "$VDRIVE_PID")
kill -INT "$VDRIVE_PID"; wait "$VDRIVE_PID" 2>/dev/null; VDRIVE_PID=""
cp "$WORK/vdrive.log" "$OUT/vdrive.log"

read -r baseline max_after growth _ <<<"$(rss_growth "$OUT/rss.csv" "$(( ${op_at:-999999} + BASELINE_S ))")"
[ "$baseline" = none ] && baseline=""
summary=$(grep "^summary:" "$OUT/master.txt")
stopped=$(grep -o "stopped: .*" "$OUT/vdrive.log" | tail -n 1)
soak_footer "$OUT/result.txt"
{
  echo "master: exit $master_rc; $summary"
  echo "vdrive: $stopped"
  grep -E "^slave [0-9]+ @0x|worst lateness" "$OUT/master.txt"
  echo "rss: baseline ${baseline:-none} KiB (${BASELINE_S} s after Op), largest after it ${max_after} KiB, at the end ${end_rss:-?} KiB, slack ${RSS_SLACK_KIB} KiB, $(($(wc -l <"$OUT/rss.csv") - 1)) samples"
} >>"$OUT/result.txt"
cat "$OUT/result.txt"

[ $master_rc -eq 0 ] || [ $master_rc -eq 1 ] || { cat "$OUT/master.err"; fail "vdrive-master op exited $master_rc"; }
echo "$summary" | grep -Eq "^summary: [0-9]+ cycles of 1000 us, working counter [0-9]+ expected, 0 wrong, 0 lost, 0 not all in Op" \
  || fail "the master saw wrong working counters, lost frames or a slave out of Op"
in=$(echo "$stopped" | sed -n 's/^stopped: \([0-9]*\) frames in, \([0-9]*\) out, \([0-9]*\) dropped, \([0-9]*\) send failures.*/\1 \2 \3 \4/p')
set -- $in
[ $# -eq 4 ] || fail "vdrive did not log its frame counters at exit"
[ "$1" -eq "$2" ] && [ "$3" -eq 0 ] && [ "$4" -eq 0 ] || fail "vdrive lost frames: $stopped"
[ -n "$baseline" ] || fail "no RSS sample ${BASELINE_S} s after Op (run too short?)"
[ "$growth" -le "$RSS_SLACK_KIB" ] || fail "resident memory grew by $growth KiB in Op (slack $RSS_SLACK_KIB KiB)"
echo "PASS: no lost frames, no wrong working counters, RSS growth in Op $growth KiB (<= $RSS_SLACK_KIB KiB); results in $OUT"
