#!/usr/bin/env bash
# Build quadapt and run the whole test suite (unit, CLI and example tests) with ctest.
# Installs the Debian dependencies first (idempotent). Usage: scripts/test.sh [extra ctest args]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
export OMP_NUM_THREADS=2
ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
