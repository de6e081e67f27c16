#!/usr/bin/env bash
# Telemetry sampler cost on the loop thread: builds and runs bench_telemetry, printing the machine,
# date and load average with the numbers (docs/performance.md "Telemetry sampler").
# Usage: bash bench/telemetry/run.sh [build-dir]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build}
cd "$here" && flock /tmp/vdrive-build.lock cmake --build "$build" --target bench_telemetry >/dev/null
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) CPU(s); $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$build/bench/bench_telemetry" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
