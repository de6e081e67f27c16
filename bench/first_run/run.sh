#!/usr/bin/env bash
# The README's first command on a fresh Debian 12 machine, timed: a minimal Debian 12 root made
# by debootstrap (no compiler, no cmake, nothing of the project's) gets a copy of this checkout's
# HEAD, and `bash tools/demo.sh` runs in it under chroot, as root, every line of its output
# stamped with the seconds since it started. Then it runs a second time in the same root (the
# build reused). The root shares this host's kernel, network and /dev (the demo makes and removes
# its own veth pair, as on a real machine).
#
# Reported (result.txt, and on stdout):
#   packages   when tools/setup-debian.sh finished (the build's first line)
#   built      when tools/build.sh said "build: done"
#   moving     when the demo printed its first live telemetry line of a drive in Op and csp (mode 8)
#   total      when the demo ended by itself (no terminal: one sine, then it stops)
# for the first run and for the second.
#
# Usage: bash bench/first_run/run.sh [OUT_DIR]
#   OUT_DIR (kept): first.log, second.log (stamped output), result.txt. Default: a new
#   /var/tmp/vdrive-first-run-<date> directory; the root is made in OUT_DIR/root and removed at
#   the end unless KEEP_ROOT=1. Needs root and the network to deb.debian.org (or MIRROR).
# Environment: MIRROR (default http://deb.debian.org/debian), KEEP_ROOT, DEMO_ARGS (extra
#   arguments for tools/demo.sh, default none).
# Measure on an otherwise idle machine: the build uses every core.
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
SRC=$(cd "$HERE/../.." && pwd)
OUT=${1:-/var/tmp/vdrive-first-run-$(date -u +%Y%m%dT%H%M%SZ)}
MIRROR=${MIRROR:-http://deb.debian.org/debian}
ROOT="$OUT/root"

[ "$(id -u)" = 0 ] || { echo "first_run: needs root (debootstrap, chroot, veth)" >&2; exit 77; }
mkdir -p "$OUT"
[ ! -e "$ROOT" ] || { echo "first_run: $ROOT exists; give a new OUT_DIR" >&2; exit 2; }
command -v debootstrap >/dev/null || { apt-get update -qq && apt-get install -y -qq debootstrap >/dev/null; }

mounted=()
cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -l "${mounted[i]}" 2>/dev/null || true; done
  if [ "${KEEP_ROOT:-0}" != 1 ] && [ -d "$ROOT" ]; then rm -rf --one-file-system "$ROOT"; fi
}
trap cleanup EXIT

started=$SECONDS
echo "first_run: making a minimal Debian 12 root in $ROOT"
debootstrap --variant=minbase bookworm "$ROOT" "$MIRROR" >"$OUT/debootstrap.log" 2>&1 ||
  { echo "first_run: debootstrap failed; see $OUT/debootstrap.log" >&2; exit 1; }
echo "first_run: root made in $((SECONDS - started)) s (not counted)"
cp /etc/resolv.conf "$ROOT/etc/resolv.conf"
mkdir -p "$ROOT/src"
git -C "$SRC" archive HEAD | tar -x -C "$ROOT/src"
commit=$(git -C "$SRC" rev-parse --short HEAD)
for m in proc sys dev dev/pts dev/shm; do
  mkdir -p "$ROOT/$m"
  mount --bind "/$m" "$ROOT/$m"
  mounted+=("$ROOT/$m")
done

# One run of the demo command in the root; its output stamped "SECONDS.TENTHS line".
run_demo() {
  local log=$1
  chroot "$ROOT" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root \
    bash -c "cd /src && exec bash tools/demo.sh ${DEMO_ARGS:-}" </dev/null 2>&1 |
    { t0=$(date +%s%N); while IFS= read -r line; do
        printf '%6.1f %s\n' "$(( ($(date +%s%N) - t0) / 1000000 ))e-3" "$line"
      done; } >"$log"
  return "${PIPESTATUS[0]}"
}

# The stamp of the first line matching $2 in log $1, or "-".
stamp() { awk -v re="$2" '$0 ~ re { print $1; found = 1; exit } END { if (!found) print "-" }' "$1"; }

report() {
  local log=$1 name=$2 rc=$3
  printf '%-6s packages %6s s  built %6s s  moving %6s s  total %6s s  exit %s\n' "$name" \
    "$(stamp "$log" ' build: ')" "$(stamp "$log" ' build: done')" "$(stamp "$log" ' telemetry: .* Op .*mode=8 ')" \
    "$(tail -n 1 "$log" | awk '{ print $1 }')" "$rc"
}

{
  echo "first_run: $(date -u +%Y-%m-%dT%H:%MZ), commit $commit, $(nproc) cores, $(uname -r)"
  rc=0; run_demo "$OUT/first.log" || rc=$?
  report "$OUT/first.log" first "$rc"
  rc=0; run_demo "$OUT/second.log" || rc=$?
  report "$OUT/second.log" second "$rc"
} | tee "$OUT/result.txt"
echo "first_run: logs in $OUT"
