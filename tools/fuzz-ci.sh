#!/usr/bin/env bash
# Short fuzzing runs of every libFuzzer target (tests/fuzz, docs/fuzzing.md), as CI runs them
# after the test suite: a clang build with AddressSanitizer and UndefinedBehaviorSanitizer in
# build-fuzz/ (or $VDRIVE_FUZZ_BUILD_DIR), then each target for VDRIVE_FUZZ_SECONDS (default 30)
# starting from its committed corpus, tests/fuzz/corpus/<target>/: small seeds and the reproducer
# of every finding, which so run first, as regression tests. New inputs go to a scratch corpus, never
# into the tree. Any crash, sanitizer report, leak or input slower than 10 s fails the run (exit 1);
# the reproducer is left in build-fuzz/findings/<target>/ and named in the output: add it to the
# target's corpus with the fix.
#
# Usage: tools/fuzz-ci.sh [TARGET...]   (default: every target with a corpus directory)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${VDRIVE_FUZZ_BUILD_DIR:-$here/build-fuzz}
seconds=${VDRIVE_FUZZ_SECONDS:-30}
corpus_root="$here/tests/fuzz/corpus"
if (($#)); then targets=("$@"); else mapfile -t targets < <(cd "$corpus_root" && ls -d fuzz_* | sort); fi

started=$SECONDS
CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DVDRIVE_BUILD_FUZZERS=ON -DVDRIVE_BUILD_TESTS=OFF -DVDRIVE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"
echo "fuzz: built ${#targets[@]} targets in $((SECONDS - started)) s"

# The test suite's own files seed the file readers as well.
declare -A more_seeds=([fuzz_esi]="$here/tests/products/esi" [fuzz_eni]="$here/tests/products/networks")

failed=()
for t in "${targets[@]}"; do
  scratch=$(mktemp -d)
  findings="$build/findings/$t"
  mkdir -p "$findings"
  log="$build/findings/$t.log"
  # -timeout: an input slower than 10 s is a hang; -rss_limit_mb: libFuzzer's default, said aloud.
  if "$build/tests/fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$findings/" "$scratch" "$corpus_root/$t" ${more_seeds[$t]:-} >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
    echo "fuzz: $t: ${runs:-?} inputs in $seconds s, $cov, no finding"
  else
    echo "fuzz: $t: FINDING (log $log):"
    # The cause (a sanitizer's report or an escaped exception) and the first frames in our code.
    grep -E "ERROR|SUMMARY|runtime error|terminate called|what\(\)|Test unit written to" "$log" | head -8 | sed 's/^/  /'
    grep -E "^ +#[0-9]+ .* in (vdrive|esc_model|plant|master|LLVMFuzzerTestOneInput)" "$log" | head -6 | sed 's/^/  /' || true
    failed+=("$t")
  fi
  rm -rf "$scratch"
done
if ((${#failed[@]})); then
  echo "fuzz: findings in ${failed[*]}"
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, no finding ($((SECONDS - started)) s in all)"
