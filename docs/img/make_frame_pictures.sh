#!/usr/bin/env bash
# Regenerates the frame-field pictures of docs/size-solve.md and docs/estimate-frame.md with the
# project's `meshplot` (no plotting code of our own):
#   bash docs/img/make_frame_pictures.sh BIN_DIR
# Inputs: the stored S-shock goldens (tests/golden/frame/, 16x16, p = 2, growth 1.5).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
SRC=$(cd "$HERE/../.." && pwd)
BIN=${1:?usage: make_frame_pictures.sh BIN_DIR}
G="$SRC/tests/golden/frame"
# thesis Fig. 6.5a analogue: crosses with arm lengths 1/h1, 1/h2 from the DG solution's frame
"$BIN/meshplot" -q "$G/sshock16_p2_dg_frame.msh" --field Vinv --glyph cross \
  --title "S-shock 16x16, p = 2: target frame (arms in ratio 1/h1 : 1/h2, sized by the cell), growth 1.5" -o "$HERE/frame-sshock16-p2-cross.svg"
# true-size parallelograms +-v, +-w (the target elements)
"$BIN/meshplot" -q "$G/sshock16_p2_dg_frame.msh" --field Vinv --glyph parallelogram \
  --title "S-shock 16x16, p = 2: target elements (parallelograms +-v, +-w)" -o "$HERE/frame-sshock16-p2-parallelogram.svg"
# error constant B from estimate-frame (log scale, 10 decades)
"$BIN/meshplot" -q "$G/sshock16_p2_dg_shape.msh" --field B --log10 --range=-6,4 \
  --title "S-shock 16x16, p = 2: log10 B (estimate-frame)" -o "$HERE/shape-sshock16-p2-B.svg"
rm -f "$HERE"/*.svg.json
ls -la "$HERE"/frame-sshock16-p2-*.svg "$HERE"/shape-sshock16-p2-B.svg
