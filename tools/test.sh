#!/usr/bin/env bash
# Sets up (Debian packages), builds, and runs the whole test suite (unit + integration; the
# integration tests need root and skip themselves otherwise), then a short run of every fuzz
# target (tools/fuzz-ci.sh; VDRIVE_FUZZ_SECONDS per target, default 30, 0 skips it).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/tools/setup-debian.sh"
"$here/tools/build.sh"
cd "${VDRIVE_BUILD_DIR:-$here/build}"
ctest --output-on-failure -j"$(nproc)" "$@"
if [ "${VDRIVE_FUZZ_SECONDS:-30}" != 0 ]; then "$here/tools/fuzz-ci.sh"; fi
