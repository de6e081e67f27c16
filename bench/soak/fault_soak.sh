#!/usr/bin/env bash
# Fault soak: faults injected one after another while the line runs, and a master that recovers.
# `vdrive run` serves a6b, ds5c1, ds1000a in a network namespace on one end of a veth pair;
# `vdrive-master op --dc --cycle-us 1000 --sine --recover` on the other end moves every drive in
# csp at 1 kHz with distributed clocks and rides out what follows (acknowledges AL errors and
# requests Op again, resets faulted drives and enables them again, moving on from where they stand).
#
# While the master runs, `vdrive fault inject` breaks, one at a time with healing time between:
#   drop (50 ms, and 400 ms: a cut wire), corrupt, link_down (the cable into slave 3 breaks and
#   heals), wkc_error, sync_lost, a drive alarm on each product, jam, collision, load_change;
# between the master's runs (rounds), when the line is served to acyclic requests only:
#   sii_error (the master cannot read the SII), lost_reply (once: the master's repeat request
#   brings it back; twice: the request times out), duplicate_reply, sdo_abort.
# For each fault it checks the reaction docs/faults.md documents for it (lost frames, wrong
# working counters, the AL status code the line left Op with, the drive's 603Fh and vdrive's alarm
# line with the vendor's code and name, a failed scan or SDO) and that afterwards the line is back
# in Op with every drive in Operation enabled within BOUND_S seconds. vdrive's VmRSS is sampled
# every INTERVAL seconds (bench/soak/soak_lib.sh). At the end vdrive must still run, and the
# master's runs must have ended without a drive or the line staying out beyond the bound.
#
# Usage: bash bench/soak/fault_soak.sh [SECONDS] [BUILD_DIR] [OUT_DIR]
#   SECONDS default 3600 (60..3600): rounds of the master (at most ROUND_S each) until it is up;
#   BUILD_DIR default build/ next to this checkout; OUT_DIR (kept): result.txt (summary),
#   faults.tsv (one row per fault), rss.csv, master-N.txt, vdrive.log. Default: a new
#   /tmp/vdrive-fault-soak-<date> directory. Needs root; exit 0 pass, 1 a check failed, 77 skipped.
# Environment: ROUND_S (default 600), BOUND_S (5), INTERVAL (5), RSS_SLACK_KIB (256), BASELINE_S
#   (10: the RSS baseline is the first sample this long after the first Op).
set -u

SECONDS_TO_RUN=${1:-3600}
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=${2:-$HERE/../../build}
OUT=${3:-/tmp/vdrive-fault-soak-$(date -u +%Y%m%dT%H%M%SZ)}
ROUND_S=${ROUND_S:-600}
BOUND_S=${BOUND_S:-5}
INTERVAL=${INTERVAL:-5}
RSS_SLACK_KIB=${RSS_SLACK_KIB:-256}
BASELINE_S=${BASELINE_S:-10}
VDRIVE="$BUILD/vdrive/vdrive"
MASTER="$BUILD/master/vdrive-master"

case "$SECONDS_TO_RUN" in ''|*[!0-9]*) echo "fault_soak.sh: SECONDS must be a whole number of seconds, got '$SECONDS_TO_RUN'" >&2; exit 2 ;; esac
[ "$SECONDS_TO_RUN" -ge 60 ] && [ "$SECONDS_TO_RUN" -le 3600 ] || { echo "fault_soak.sh: SECONDS must be 60..3600" >&2; exit 2; }
[ -x "$VDRIVE" ] || VDRIVE="$BUILD/vdrive"   # single-directory builds

# shellcheck source=../../tests/integration/lib/veth_line.sh
. "$HERE/../../tests/integration/lib/veth_line.sh"
# shellcheck source=soak_lib.sh
. "$HERE/soak_lib.sh"
require_tools stdbuf
mkdir -p "$OUT" || fail "cannot create $OUT"

SAMPLER_PID=""
MASTER_PID=""
stop_helpers() {
  [ -n "$SAMPLER_PID" ] && kill "$SAMPLER_PID" 2>/dev/null && wait "$SAMPLER_PID" 2>/dev/null
  [ -n "$MASTER_PID" ] && kill "$MASTER_PID" 2>/dev/null && wait "$MASTER_PID" 2>/dev/null
  SAMPLER_PID="" MASTER_PID=""
}
trap 'stop_helpers; cleanup' EXIT

CTL="$WORK/ctl/line.sock"
fault() { "$VDRIVE" fault "$@" --control "$CTL"; }
now() { date +%s.%3N; }
VLOG="$WORK/vdrive.log"

soak_header "$OUT/result.txt" "fault soak: $SECONDS_TO_RUN s, 3 drives (a6b ds5c1 ds1000a), DC at 1 kHz, csp sine, recovering master, bound $BOUND_S s"
printf 'round\tfault\tresult\treaction\tback_ms\n' >"$OUT/faults.tsv"
echo "seconds,rss_kib" >"$OUT/rss.csv"

# The A6B's parameter file (1010h) goes to the run's own directory, not /var/lib/vdrive.
export VDRIVE_STATE_DIR="$WORK/state"
start_line --rt-priority 80 --control "$CTL" --drive a6b --drive ds5c1 --drive ds1000a
wait_for_line
T0=$(date +%s)
( while rss_sample "$VDRIVE_PID" "$OUT/rss.csv" "$T0"; do sleep "$INTERVAL"; done ) &
SAMPLER_PID=$!

FAILS=0
ROUND=0
record() {  # record FAULT RESULT REACTION BACK_MS
  printf '%s\t%s\t%s\t%s\t%s\n' "$ROUND" "$1" "$2" "$3" "$4" >>"$OUT/faults.tsv"
  printf 'round %s: %-22s %-4s %s%s\n' "$ROUND" "$1" "$2" "$3" "${4:+, back in $4 ms}"
  [ "$2" = ok ] || FAILS=$((FAILS + 1))
}
alive() { kill -0 "$VDRIVE_PID" 2>/dev/null || { cat "$VLOG"; fail "vdrive exited (round $ROUND)"; }; }

# --- Faults while the master runs -------------------------------------------------------------

MOUT=""
# The master's last status line: "@T status: C cycles, W wrong, L lost, N not all in Op, line in
# Op, 3/3 drives enabled" ("line out of Op" when it is not).
last_status() { grep " status: " "$MOUT" | tail -n 1; }
status_field() { echo "$1" | sed -n "s/.* \([0-9]*\) $2.*/\1/p"; }
status_time() { echo "$1" | sed -n 's/^@\([0-9.]*\) .*/\1/p'; }
ready() { echo "$1" | grep -q "line in Op, 3/3 drives enabled"; }
later() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a > b) }'; }

# Waits (up to BOUND_S) for a status line stamped after $1 that shows the line in Op and every
# drive enabled.
wait_ready_after() {
  local deadline=$(( $(date +%s) + BOUND_S + 1 )) s
  while [ "$(date +%s)" -le "$deadline" ]; do
    s=$(last_status)
    [ -n "$s" ] && later "$(status_time "$s")" "$1" && ready "$s" && return 0
    kill -0 "$MASTER_PID" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}

# op_fault NAME CHECKS SECONDS INJECT-ARGS...: inject, let it act for SECONDS (its duration; one-shot
# faults 0), then check the reaction and the return to Op. CHECKS, joined by "+":
#   lost            the master lost frames in the fault's time
#   wrong           the master counted wrong working counters
#   al:CODE         a slave left Op with AL status code CODE (hex, 4 digits; the master's "left Op"
#                   lines or vdrive's log say so) and the master brought the line back
#   drive:STATION:C drive STATION (hex) went out of Operation enabled with 603Fh C and was enabled
#                   again, and vdrive logged its alarm with that 603Fh
#   steady          no drive went out and the line never left Op
op_fault() {
  local name=$1 checks=$2 seconds=$3
  shift 3
  alive
  local t_ready
  t_ready=$(now)
  if ! wait_ready_after "$(awk -v t="$t_ready" 'BEGIN { printf "%.3f", t - 1 }')"; then
    record "$name" FAIL "the line was not in Op with every drive enabled before it" ""
    return
  fi
  local m0 v0 s0 out
  m0=$(wc -l <"$MOUT") v0=$(wc -l <"$VLOG") s0=$(last_status)
  out=$(fault inject "$@" 2>&1) || { record "$name" FAIL "vdrive fault inject $*: $out" ""; return; }
  sleep "$seconds"
  local t1
  t1=$(now)
  sleep 0.5  # a one-shot fault, and the drives' reaction to the end of one, act within this
  local back=ok
  wait_ready_after "$(awk -v t="$t1" 'BEGIN { printf "%.3f", t + 0.5 }')" || back=FAIL
  local s1 mlines vlines
  s1=$(last_status)
  mlines=$(tail -n +"$((m0 + 1))" "$MOUT")
  vlines=$(tail -n +"$((v0 + 1))" "$VLOG")
  local lost=$(( $(status_field "$s1" lost) - $(status_field "$s0" lost) ))
  local wrong=$(( $(status_field "$s1" wrong) - $(status_field "$s0" wrong) ))
  local notop=$(( $(status_field "$s1" "not all in Op") - $(status_field "$s0" "not all in Op") ))
  local outs
  outs=$(echo "$mlines" | grep -c ": out (603Fh")
  local result=ok reaction="" check
  IFS=+ read -ra all <<<"$checks"
  for check in "${all[@]}"; do
    case "$check" in
      lost) [ "$lost" -gt 0 ] || result=FAIL; reaction+="$lost lost frames; " ;;
      wrong) [ "$wrong" -gt 0 ] || result=FAIL; reaction+="$wrong wrong WKC; " ;;
      al:*)
        local code=${check#al:}
        # The master's "left Op" lines carry each slave's AL status code; vdrive logs it too, but
        # samples every 100 ms and misses an error the master acknowledged within a few cycles.
        if { echo "$mlines" | grep -q "error 0x$code"; } || { echo "$vlines" | grep -q "AL error 0x$code"; } &&
           echo "$mlines" | grep -q "back in Op"; then
          reaction+="left Op with AL $code, back after $(echo "$mlines" | sed -n 's/.*back in Op after \([0-9]*\) ms.*/\1/p' | tail -n 1) ms; "
        else
          result=FAIL; reaction+="no AL $code and return to Op; "
        fi ;;
      drive:*)
        local station=${check#drive:} code
        code=${station#*:} station=${station%%:*}
        local alarm
        alarm=$(echo "$vlines" | grep -o "alarm .*(603Fh ${code}h)" | head -n 1)
        # The code of the outage (the first 603Fh seen in it) is on the line that ends it.
        if echo "$mlines" | grep -q "@0x$station [^:]*: enabled again after [0-9]* ms (603Fh ${code}h)" && [ -n "$alarm" ]; then
          reaction+="drive 0x$station: ${alarm}, reset and enabled again after $(echo "$mlines" | sed -n "s/.*@0x$station [^:]*: enabled again after \([0-9]*\) ms.*/\1/p" | tail -n 1) ms; "
        else
          result=FAIL; reaction+="drive 0x$station: no 603Fh ${code}h alarm, reset and re-enable (vdrive: '${alarm}'); "
        fi ;;
      steady) { [ "$outs" -eq 0 ] && [ "$notop" -eq 0 ]; } || result=FAIL; reaction+="$outs drive outages, $notop cycles not all in Op; " ;;
    esac
  done
  [ "$back" = ok ] || { result=FAIL; reaction+="not back in Op with every drive enabled within $BOUND_S s; "; }
  # How long after the fault's end the line and every drive were back: the last return in the log.
  local back_ms="" last_back
  last_back=$(echo "$mlines" | grep -E "enabled again|back in Op" | tail -n 1 | sed -n 's/^@\([0-9.]*\) .*/\1/p')
  [ -n "$last_back" ] && back_ms=$(awk -v a="$last_back" -v b="$t1" 'BEGIN { d = (a - b) * 1000; printf "%d", d < 0 ? 0 : d }')
  record "$name" "$result" "${reaction%; }" "$back_ms"
}

# One pass over the faults that act while the line is in Op: slave 1 = a6b (station 0x1001),
# 2 = ds5c1 (0x1002), 3 = ds1000a (0x1003). Healing time between them: op_fault waits for the line
# and every drive to be back first.
op_pass() {
  op_fault drop_50ms lost 0.05 drop --duration 50ms
  op_fault corrupt lost 0.5 corrupt --direction to_slaves --probability 0.3 --duration 500ms
  op_fault wire_cut_400ms lost+al:001B 0.4 drop --duration 400ms
  op_fault link_down_slave3 wrong+al:001B 1 link_down --slave 3 --duration 1s
  op_fault wkc_error_slave2 wrong 0.05 wkc_error --slave 2 --duration 50ms
  op_fault sync_lost_ds5c1 al:002C 0.3 sync_lost --slave 2 --duration 300ms
  op_fault alarm_a6b_12.0 drive:1001:FF0C 0 alarm --slave 1 --code 12.0
  op_fault alarm_ds5c1_E-030 drive:1002:FF03 0 alarm --slave 2 --code E-030
  op_fault alarm_ds1000a_FF05h drive:1003:FF05 0 alarm --slave 3 --code FF05h
  op_fault jam_a6b drive:1001:FF18 0.5 jam --slave 1 --duration 500ms
  op_fault load_change_ds1000a steady 1.5 load_change --slave 3 --load-scale 3 --duration 1500ms
}
PASS_S=40  # what one pass takes at most, measured on the 2-core VM (docs/reliability.md)

# --- Faults between the master's runs (acyclic requests) ---------------------------------------

sdo_read() { "$MASTER" sdo-read --iface "$M_IF" --slave "$1" --index 0x6065 --type u32 >"$WORK/sdo.out" 2>"$WORK/sdo.err"; }

acyclic_faults() {
  alive
  local out id rc
  # SII: the EEPROM does not acknowledge; the master's scan fails; cleared, it reads again.
  out=$(fault inject sii_error --slave 2 2>&1) && id=$(echo "$out" | sed -n 's/^fault \([0-9]*\) injected$/\1/p')
  "$MASTER" scan --iface "$M_IF" >"$WORK/scan.out" 2>"$WORK/scan.err"; rc=$?
  local err
  err=$(head -c 200 "$WORK/scan.err")
  fault clear "$id" >/dev/null 2>&1
  if [ "$rc" -ne 0 ] && "$MASTER" scan --iface "$M_IF" >/dev/null 2>&1; then
    record sii_error_ds5c1 ok "scan failed (exit $rc: $err); cleared, the scan reads the SII again" ""
  else
    record sii_error_ds5c1 FAIL "scan exit $rc with the SII failing ($err), or no scan after clearing it" ""
  fi
  # Mailbox: one lost reply is brought back by the repeat request; two time the request out.
  fault inject lost_reply --slave 1 --count 1 >/dev/null
  if sdo_read 1; then record lost_reply_once ok "SDO upload 6065h answered after the repeat request ($(cat "$WORK/sdo.out"))" ""
  else record lost_reply_once FAIL "SDO upload failed: $(cat "$WORK/sdo.err")" ""; fi
  fault inject lost_reply --slave 1 --count 2 >/dev/null
  if ! sdo_read 1; then
    record lost_reply_twice ok "SDO upload failed as documented: $(head -c 160 "$WORK/sdo.err")" ""
  else
    record lost_reply_twice FAIL "SDO upload answered although two replies were lost" ""
  fi
  sdo_read 1 || record mailbox_after_loss FAIL "the next SDO upload failed: $(cat "$WORK/sdo.err")" ""
  fault inject duplicate_reply --slave 3 --count 1 >/dev/null
  if sdo_read 3; then record duplicate_reply ok "SDO upload answered, the copy dropped ($(cat "$WORK/sdo.out"))" ""
  else record duplicate_reply FAIL "SDO upload failed: $(cat "$WORK/sdo.err")" ""; fi
  fault inject sdo_abort --slave 2 --abort-code 0x06090011 >/dev/null
  if ! sdo_read 2 && grep -qi "06090011" "$WORK/sdo.err"; then
    record sdo_abort ok "SDO upload aborted with 06090011h" ""
  else
    record sdo_abort FAIL "no abort 06090011h: $(cat "$WORK/sdo.out" "$WORK/sdo.err")" ""
  fi
  out=$(fault list 2>&1)
  [ "$out" = "no active faults" ] || record faults_left FAIL "faults still active: $out" ""
}

# --- Rounds -------------------------------------------------------------------------------------

op_at=""
while :; do
  ROUND=$((ROUND + 1))
  left=$(( SECONDS_TO_RUN - ($(date +%s) - T0) ))
  # The master's motion: the round, but no longer than what is left (start-up and the acyclic
  # faults take about 15 s).
  motion=$(( left - 15 < ROUND_S ? left - 15 : ROUND_S ))
  MOUT="$OUT/master-$ROUND.txt"
  stdbuf -oL "$MASTER" op --rt-priority 70 --iface "$M_IF" --dc --cycle-us 1000 --sine --revolutions 0.25 \
    --frequency 0.5 --seconds "$motion" --recover --recover-bound-ms $((BOUND_S * 1000)) --status-every-ms 100 \
    --reply-timeout-us 20000 >"$MOUT" 2>"$OUT/master-$ROUND.err" &
  MASTER_PID=$!
  for _ in $(seq 1 100); do grep -qx "Op" "$MOUT" && break; sleep 0.1; done
  grep -qx "Op" "$MOUT" || { cat "$MOUT" "$OUT/master-$ROUND.err"; fail "round $ROUND: vdrive-master op did not reach Op"; }
  [ -n "$op_at" ] || op_at=$(( $(date +%s) - T0 ))
  round_end=$(( $(date +%s) + motion ))
  # Passes while one more fits in the motion (the drives must be enabled for the last checks).
  passes=0
  while [ $passes -eq 0 ] || [ $(( round_end - $(date +%s) )) -gt $((PASS_S + 3)) ]; do
    op_pass
    passes=$((passes + 1))
  done
  wait "$MASTER_PID"
  master_rc=$?
  MASTER_PID=""
  [ "$master_rc" -eq 0 ] || { record "master_round_$ROUND" FAIL "vdrive-master op exited $master_rc: $(cat "$OUT/master-$ROUND.err")" ""; }
  acyclic_faults
  left=$(( SECONDS_TO_RUN - ($(date +%s) - T0) ))
  [ "$left" -ge 60 ] || break
done

alive
end_rss=$(rss_kib "$VDRIVE_PID")
stop_helpers
kill -INT "$VDRIVE_PID"; wait "$VDRIVE_PID" 2>/dev/null; vdrive_rc=$?; VDRIVE_PID=""
cp "$VLOG" "$OUT/vdrive.log"

read -r baseline max_after growth samples <<<"$(rss_growth "$OUT/rss.csv" "$(( op_at + BASELINE_S ))")"
soak_footer "$OUT/result.txt"
{
  echo "rounds: $ROUND (master runs of at most $ROUND_S s, then the acyclic faults)"
  echo "faults: $(($(wc -l <"$OUT/faults.tsv") - 1)) checked, $FAILS failed"
  awk -F'\t' 'NR > 1 { n[$2]++; if ($3 == "ok") ok[$2]++; if ($5 != "" && $5 + 0 > worst[$2]) worst[$2] = $5 + 0 }
    END { for (f in n) printf "  %-22s %4d injected, %4d ok%s\n", f, n[f], ok[f], (f in worst) ? ", slowest return " worst[f] " ms" : "" }' \
    "$OUT/faults.tsv" | sort
  for m in "$OUT"/master-*.txt; do
    echo "$(basename "$m"): $(grep "^summary:" "$m")"
    grep -E "^recovery:|^slave [0-9]+ @0x" "$m" | sed 's/^/  /'
  done
  echo "vdrive: exit $vdrive_rc at SIGINT; $(grep -o "stopped: .*" "$OUT/vdrive.log" | tail -n 1)"
  echo "vdrive: $(grep -c "host stall" "$OUT/vdrive.log") host stall lines"
  echo "rss: baseline $baseline KiB ($BASELINE_S s after the first Op), largest after it $max_after KiB, at the end ${end_rss:-?} KiB, growth $growth KiB, slack $RSS_SLACK_KIB KiB, $samples samples"
} >>"$OUT/result.txt"
cat "$OUT/result.txt"

[ "$vdrive_rc" -eq 0 ] || fail "vdrive exited $vdrive_rc at SIGINT"
[ "$baseline" != none ] || fail "no RSS sample $BASELINE_S s after Op"
[ "$growth" -le "$RSS_SLACK_KIB" ] || fail "vdrive's resident memory grew by $growth KiB (slack $RSS_SLACK_KIB KiB)"
[ "$FAILS" -eq 0 ] || fail "$FAILS fault checks failed (faults.tsv in $OUT)"
echo "PASS: every fault had its reaction and the line came back within $BOUND_S s; RSS growth $growth KiB; results in $OUT"
