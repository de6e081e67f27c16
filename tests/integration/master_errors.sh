#!/usr/bin/env bash
# Integration: vdrive-master's answers when there is no line, with vdrive's exit codes: a missing
# interface is exit 3, an interface with nobody on it exit 1, a bad command line exit 2 (scan
# --state op names op as the way there), each with a one-line error; --version and --help's
# examples. Usage: bash master_errors.sh
# <vdrive> <build-dir>.
set -u
MASTER="${2:?build directory}/master/vdrive-master"
fail() { echo "FAIL: $*"; exit 1; }
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root"; exit 77; }
command -v ip >/dev/null || { echo "SKIP: ip not installed"; exit 77; }
[ -x "$MASTER" ] || fail "vdrive-master not found at $MASTER"

A="vdtea$$"; B="vdteb$$"
trap 'ip link del "$A" 2>/dev/null' EXIT

check() {  # check <exit code> <expected text> <args...>
  local code=$1 want=$2; shift 2
  local err rc
  err=$("$MASTER" "$@" 2>&1 >/dev/null); rc=$?
  [ "$rc" -eq "$code" ] || fail "'$*' exited $rc, expected $code"
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "'$*': error is not one line: $err"
  echo "$err" | grep -q "$want" || fail "'$*': error does not mention '$want': $err"
  echo "ok: $* -> $err"
}

check 3 "no interface" scan --iface "nosuch$$"
check 2 "vdrive-master op" scan --iface lo --state op
check 2 "bogus" scan --iface lo --bogus
ip link add "$A" type veth peer name "$B" || fail "cannot create veth"
ip link set "$A" up; ip link set "$B" up
check 1 "no reply" scan --iface "$A" --state preop
"$MASTER" --version | grep -Eq "^vdrive-master [0-9]+\.[0-9]+" || fail "--version does not print the version"
"$MASTER" --help | grep -q "^Examples:" || fail "--help has no examples"
echo PASS
