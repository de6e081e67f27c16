#!/usr/bin/env bash
# Sets up (Debian packages), builds, and runs the demo: a line of three drives on a veth pair that
# it creates, scanned and taken up the state machine by the built-in master, moving a csp sine, with
# the live web page on http://127.0.0.1:8080/ (docs/web.md) and DDS telemetry of the axes shown as
# `vdrive telemetry` shows it (docs/telemetry.md). From a terminal the drives keep moving until
# Ctrl-C; from a script it ends by itself. Run as root. Installs and builds only what the program
# needs (tools/test.sh adds the rest, reusing this build).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/tools/setup-debian.sh" --demo
VDRIVE_DEMO_ONLY=1 "$here/tools/build.sh"
exec "${VDRIVE_BUILD_DIR:-$here/build}/vdrive/vdrive" demo "$@"
