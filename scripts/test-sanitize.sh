#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer: a separate build in
# build-asan (-DQUADAPT_SANITIZE=ON), then ctest there. Any ASan report or UB aborts the tool or
# test that hit it, so the test fails. Usage: scripts/test-sanitize.sh [extra ctest args]
# Cost and the subset CI runs: docs/sanitizers.md.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DQUADAPT_SANITIZE=ON >/dev/null
cmake --build build-asan -j"$(nproc)"
export OMP_NUM_THREADS=2
# Leaks are not checked: the Gmsh SDK keeps its global model alive to exit (docs/sanitizers.md).
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" "$@"
