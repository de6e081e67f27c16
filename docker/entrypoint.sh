#!/bin/sh
# Entrypoint of the vdrive image: runs its arguments (`vdrive ...` or `vdrive-master ...`).
# With VDRIVE_WAIT_IFACE=NAME it first waits for interface NAME to appear (a veth end moved into
# the container after it started, docker/veth-between.sh) and brings it up, because `vdrive run`
# and `vdrive-master` need their interface to exist and be up when they start.
# With VDRIVE_WAIT_LINE=1 as well (the master's container) it then waits until a line answers a
# `vdrive-master scan` there, so the master does not start before the drives' end serves.
# VDRIVE_WAIT_TIMEOUT: seconds each wait may take (default 120); on timeout exit 3 naming what
# was missing, the code `vdrive run` gives for a missing interface (vdrive/cli/exit_codes.hpp).
set -eu
if [ -n "${VDRIVE_WAIT_IFACE:-}" ]; then
  timeout=${VDRIVE_WAIT_TIMEOUT:-120}
  case $timeout in ''|*[!0-9]*) echo "vdrive-entrypoint: VDRIVE_WAIT_TIMEOUT: not a number of seconds: '$timeout'" >&2; exit 2;; esac
  waited=0
  while ! ip link show "$VDRIVE_WAIT_IFACE" >/dev/null 2>&1; do
    if [ "$waited" -ge $((timeout * 10)) ]; then
      echo "vdrive-entrypoint: interface '$VDRIVE_WAIT_IFACE' did not appear within ${timeout} s" >&2
      exit 3
    fi
    sleep 0.1
    waited=$((waited + 1))
  done
  ip link set "$VDRIVE_WAIT_IFACE" up
  if [ "${VDRIVE_WAIT_LINE:-0}" = 1 ]; then
    waited=0
    until vdrive-master scan --iface "$VDRIVE_WAIT_IFACE" >/dev/null 2>&1; do
      if [ "$waited" -ge $((timeout * 4)) ]; then
        echo "vdrive-entrypoint: no EtherCAT slave answered on '$VDRIVE_WAIT_IFACE' within ${timeout} s" >&2
        exit 3
      fi
      sleep 0.25
      waited=$((waited + 1))
    done
  fi
fi
exec "$@"
