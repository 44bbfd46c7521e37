#!/usr/bin/env bash
# The pictures of docs/adjoint.md: initial (16x16, p = 1) adjoint psi and log10(dwr) of the
# goal-oriented S-shock (thesis Fig. 6.21) and boundary layer (Fig. 6.29, both variants).
# usage: bench/adjoint/figures.sh [BIN_DIR]      -> docs/img/adjoint-*.png
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${1:-$SRC/build/bin}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
python3 "$SRC/tests/golden/refine/make_square.py" 16 "$W/sq16.msh" bare
for pair in sshock-advection:sshock boundary-layer-advection:bl boundary-layer-goal-thesis:bl-thesis; do
  case=${pair%%:*}; short=${pair##*:}
  "$BIN/dgsolve" -q "$W/sq16.msh" -c "$SRC/examples/cases/$case.json" -p 1 -o "$W/sol.msh"
  "$BIN/adjoint" -q "$W/sol.msh" -c "$SRC/examples/cases/$case.json" -o "$W/dwr.msh"
  "$BIN/meshplot" -q --report "$W/plot.json" "$W/dwr.msh" --field psi --title "$case, 16x16, p = 1: adjoint psi (degree 2)" \
    -o "$SRC/docs/img/adjoint-$short-psi.png"
  "$BIN/meshplot" -q --report "$W/plot.json" "$W/dwr.msh" --field dwr --log10 --title "$case, 16x16, p = 1: log10 dwr" \
    -o "$SRC/docs/img/adjoint-$short-dwr.png"
done
