#!/usr/bin/env bash
# Configures and builds vdrive into build/ (or $VDRIVE_BUILD_DIR). Extra arguments go to cmake.
#   VDRIVE_DEMO_ONLY=1  only the program (tools/demo.sh): no tests, no benchmarks; a later full
#                       build in the same directory reuses everything built here
#   VDRIVE_BUILD_TYPE   CMake build type, default Release (-O3, no debug information: the
#                       optimisation of RelWithDebInfo, built in about half the time); RelWithDebInfo
#                       for a debugger (give it on every call: without it a directory is
#                       reconfigured as Release and rebuilt)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${VDRIVE_BUILD_DIR:-$here/build}
if [ "${VDRIVE_DEMO_ONLY:-0}" = 1 ]; then
  what=(-DVDRIVE_BUILD_TESTS=OFF -DVDRIVE_BUILD_BENCH=OFF)
  targets=(--target vdrive)
  first="about 3 minutes on 2 cores the first time"
else
  what=(-DVDRIVE_BUILD_TESTS=ON -DVDRIVE_BUILD_BENCH=ON)
  targets=()
  first="about 10 minutes on 2 cores the first time (tests and benchmarks included)"
fi
started=$SECONDS
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=${VDRIVE_BUILD_TYPE:-Release} "${what[@]}" "$@" >/dev/null
if [ ! -f "$build/.ninja_log" ] || [ ! -s "$build/.ninja_log" ]; then
  echo "build: compiling into $build, $first; later runs reuse it"
fi
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
echo "build: done in $((SECONDS - started)) s"
