# Sourced by the soaks (bench/soak/run.sh, bench/soak/fault_soak.sh) after
# tests/integration/lib/veth_line.sh: what they share.
#   soak_header FILE TITLE        the soak, the machine, the start time and load, into FILE
#   soak_footer FILE              the end time and load, appended to FILE
#   rss_kib PID                   the process's resident memory (VmRSS) in KiB
#   rss_sample PID CSV T0         one "seconds since T0,KiB" row; false if the process is gone
#   rss_growth CSV FROM           "baseline largest growth samples" of the rows at FROM s and after:
#                                 baseline the first of them, largest the largest after it
# The RSS check (a leak, a growing queue or log buffer) is the same in both: growth after the
# baseline at most RSS_SLACK_KIB; start-up (profiles, dictionaries, plants, first touches of stacks
# and buffers) happens before the baseline.

soak_header() {
  {
    echo "$2"
    echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(uname -r)"
    echo "start: $(date -u '+%Y-%m-%d %H:%M:%S UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
  } >"$1"
}

soak_footer() {
  echo "end: $(date -u '+%Y-%m-%d %H:%M:%S UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)" >>"$1"
}

rss_kib() { awk '/^VmRSS:/ {print $2}' "/proc/$1/status" 2>/dev/null; }

rss_sample() {
  local rss
  rss=$(rss_kib "$1")
  [ -n "$rss" ] || return 1
  echo "$(( $(date +%s) - $3 )),$rss" >>"$2"
}

rss_growth() {
  awk -F, -v from="$2" 'NR > 1 && $1 >= from {
      if (base == "") base = $2; else if ($2 > max) max = $2; n++ }
    END { if (base == "") print "none 0 0 0"; else { if (max < base) max = base; print base, max, max - base, n } }' "$1"
}
