#!/usr/bin/env bash
# The main job: install dependencies, build the tools, and run one adaptive loop
# (S-shock, feature-based, p = 2, L_p-CVT path) to about 4e4 DOFs with Makefile.cases.
# Results: runs/demo/ (convergence.csv, convergence.png, final-mesh*.png). Extra arguments go to make.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
make -f Makefile.cases demo "$@"
