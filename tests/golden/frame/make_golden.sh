#!/usr/bin/env bash
# Regenerates the frame goldens (after an intended change of the estimator or the sizing):
#   bash tests/golden/frame/make_golden.sh BIN_DIR
# S-shock (thesis eq. 6.4) on the 16x16 unit square, p = 2, from the GLL interpolant of the exact
# solution (no solver dependence): SHAPE (estimate-frame) and FRAME (size-solve --growth 1.5).
# When dgsolve and examples/cases/sshock.json exist, also from the DG solution (sshock16_p2_dg_*).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
SRC=$(cd "$HERE/../../.." && pwd)
BIN=${1:?usage: make_golden.sh BIN_DIR}
PATH="$BIN:$PATH"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
EXACT="0.75*tanh(4*sin(10*y-5)-24*x+12)"
python3 "$SRC/tests/golden/refine/make_square.py" 16 "$T/square16.msh" bare
estimate-frame -q "$T/square16.msh" --exact "$EXACT" -p 2 -o "$HERE/sshock16_p2_shape.msh" --threads 2
size-solve -q "$HERE/sshock16_p2_shape.msh" --growth 1.5 -o "$HERE/sshock16_p2_frame.msh" --threads 2
if command -v dgsolve >/dev/null && [ -f "$SRC/examples/cases/sshock.json" ]; then
  dgsolve -q "$T/square16.msh" -c "$SRC/examples/cases/sshock.json" -p 2 -o "$T/sol.msh" --threads 2
  estimate-frame -q "$T/sol.msh" -o "$HERE/sshock16_p2_dg_shape.msh" --threads 2
  size-solve -q "$HERE/sshock16_p2_dg_shape.msh" --growth 1.5 -o "$HERE/sshock16_p2_dg_frame.msh" --threads 2
fi
ls -la "$HERE"
