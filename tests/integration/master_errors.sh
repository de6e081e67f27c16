#!/usr/bin/env bash
# Integration: vdrive-master's answers when there is no line: a missing interface and an
# interface with nobody on it give a one-line error and exit 1. Usage: bash master_errors.sh
# <vdrive> <build-dir>.
set -u
MASTER="${2:?build directory}/master/vdrive-master"
fail() { echo "FAIL: $*"; exit 1; }
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root"; exit 77; }
command -v ip >/dev/null || { echo "SKIP: ip not installed"; exit 77; }
[ -x "$MASTER" ] || fail "vdrive-master not found at $MASTER"

A="vdtea$$"; B="vdteb$$"
trap 'ip link del "$A" 2>/dev/null' EXIT

check() {  # check <expected text> <args...>
  local want=$1; shift
  local err rc
  err=$("$MASTER" "$@" 2>&1 >/dev/null); rc=$?
  [ "$rc" -eq 1 ] || fail "'$*' exited $rc, expected 1"
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "'$*': error is not one line: $err"
  echo "$err" | grep -q "$want" || fail "'$*': error does not mention '$want': $err"
  echo "ok: $* -> $err"
}

check "no interface" scan --iface "nosuch$$"
ip link add "$A" type veth peer name "$B" || fail "cannot create veth"
ip link set "$A" up; ip link set "$B" up
check "no reply" scan --iface "$A" --state preop
echo PASS
