#!/usr/bin/env bash
# Regenerates the figures of docs/lpcvt.md (thesis Figs. 6.1-6.2 and the lattice checks).
# usage: bench/lpcvt/figures.sh [BUILD_DIR]   (default: build) -> docs/img/lpcvt-*.png
set -euo pipefail
S=$(cd "$(dirname "$0")/../.." && pwd)
B=${1:-$S/build}
L=$B/bin/lpcvt
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
PY=/usr/bin/python3
P="$PY $S/bench/lpcvt/plot_voronoi.py"
$L --analytic saddle -o "$T/saddle.msh" --voronoi "$T/saddle-v.json" -q
$P "$T/saddle-v.json" "$S/docs/img/lpcvt-saddle.png" --title "L_6-CVT, saddle metric (eq. 6.1), continuous"
$L --analytic saddle --sampled -o "$T/saddle16.msh" --voronoi "$T/saddle16-v.json" -q
$P "$T/saddle16-v.json" "$S/docs/img/lpcvt-saddle16.png" --title "L_6-CVT, saddle metric sampled on a 16x16 background"
$PY "$S/tests/cli/lpcvt_frame.py" "$T/iso.msh" --n 4 --h1 0.025 --h2 0.025
for p in 6 2; do
  $L "$T/iso.msh" -p $p -o "$T/iso$p.msh" --voronoi "$T/iso$p-v.json" -q
  $P "$T/iso$p-v.json" "$S/docs/img/lpcvt-iso-p$p.png" --title "constant isotropic frame, p = $p"
done
$PY "$S/tests/cli/lpcvt_frame.py" "$T/an.msh" --n 4 --h1 0.04 --h2 0.015 --theta 0.5235987756
$L "$T/an.msh" -o "$T/an-tri.msh" --voronoi "$T/an-v.json" -q
$P "$T/an-v.json" "$S/docs/img/lpcvt-frame30.png" --title "constant frame, 30 degrees, h1/h2 = 8/3"
$PY "$S/tests/cli/lpcvt_frame.py" "$T/L.msh" --n 8 --h1 0.03 --h2 0.015 --theta 0.5235987756 --lshape
$L "$T/L.msh" -o "$T/L-tri.msh" --voronoi "$T/L-v.json" -q
$P "$T/L-v.json" "$S/docs/img/lpcvt-lshape.png" --title "L-shape, frame at 30 degrees"
