#!/usr/bin/env bash
# Bounded libFuzzer runs of the .msh reader and the case-expression parser (tests/fuzz) from the
# committed seed corpus: SECONDS each (default 60). Exit non-zero on a crash, a leak, UB or a
# non-quadapt exception; the reproducer is left in build-fuzz/crash-*. Usage: scripts/fuzz.sh [SECONDS]
# Long run and recorded results: docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DQUADAPT_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)"
for target in msh_read case_expression; do
  case $target in msh_read) seeds=msh; len=8192 ;; case_expression) seeds=expression; len=512 ;; esac
  work=build-fuzz/corpus-$target
  mkdir -p "$work"
  echo "fuzz: $target for ${SECONDS_EACH}s"
  if ! (cd build-fuzz && "bin/fuzz_$target" -max_total_time="$SECONDS_EACH" -max_len=$len -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$target-" "corpus-$target" "../tests/fuzz/corpus/$seeds" \
        > "fuzz-$target.log" 2>&1); then
    tail -n 40 "build-fuzz/fuzz-$target.log" >&2
    echo "fuzz: $target FAILED (reproducer: build-fuzz/$target-crash-* or -leak-/-timeout-)" >&2
    exit 1
  fi
  grep -E "stat::number_of_executed_units|Done [0-9]+ runs" "build-fuzz/fuzz-$target.log" || true
done
echo "fuzz: no crash"
