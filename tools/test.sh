#!/usr/bin/env bash
# Sets up (Debian packages), builds, and runs the whole test suite (unit + integration; the
# integration tests need root and skip themselves otherwise).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/tools/setup-debian.sh"
"$here/tools/build.sh"
cd "${VDRIVE_BUILD_DIR:-$here/build}"
ctest --output-on-failure -j"$(nproc)" "$@"
