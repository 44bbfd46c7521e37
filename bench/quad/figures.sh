#!/usr/bin/env bash
# Figures of docs/quad-quality.md: on every PHiLiP frame input_<case>_3.msh (PHiLiP's size
# convention) and on the eq. 6.1 saddle sampled on a 16x16 background (quadapt convention),
#   A = bamgquad FRAME                         (BAMG + Blossom + split)
#   B = lpcvt FRAME | recombine | quadsmooth --frame FRAME   (the default chain, as the loop runs it)
# plus the thesis's own output_<case>_2.msh; meshquality (physical, and in the frame's metric).
# usage: figures.sh BIN FIXTURES OUT  (FIXTURES = tests/fixtures/philip)
set -euo pipefail
BIN=$1; FIX=$2; OUT=$3
SRC=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$OUT"
export PATH="$BIN:$PATH"
cases="ss15_fb_p1 ss15_fb_p2 ss15_adj_p1 ss15_adj_p2 bl15_fb_p2 bl15_fb_p3 bl15_adj_p2 bl15_adj_p3"
for c in $cases; do
  F=$FIX/input_${c}_3.msh
  echo "== $c" >&2
  bamgquad -q "$F" --convention philip -o "$OUT/${c}_bamg.msh"
  quadsmooth -q "$OUT/${c}_bamg.msh" -o "$OUT/${c}_bamg_s.msh"
  lpcvt -q "$F" --convention philip -o "$OUT/${c}_lpcvt_tri.msh"
  recombine -q "$OUT/${c}_lpcvt_tri.msh" -o "$OUT/${c}_lpcvt_q.msh"
  quadsmooth -q "$OUT/${c}_lpcvt_q.msh" --frame "$F" -o "$OUT/${c}_lpcvt.msh"
  # PHiLiP's sizes are full edges: meshquality reads a file without $FrameConvention in PHiLiP's
  # convention (docs/file-formats.md), so a target edge has metric length 1 against F itself
  # (this script used to double Vinv by hand, which measured against twice the sizes once the
  # reader learnt the convention)
  for m in bamg bamg_s lpcvt; do meshquality "$OUT/${c}_$m.msh" --frame "$F" > "$OUT/${c}_$m.mq.json"; done
  meshquality "$FIX/output_${c}_2.msh" > "$OUT/${c}_thesis.mq.json"
done
# both paths on OUT/NAME_frame.msh (quadapt convention), as above
own_frame() {
  local n=$1 F="$OUT/$1_frame.msh"
  bamgquad -q "$F" -o "$OUT/${n}_bamg.msh"
  quadsmooth -q "$OUT/${n}_bamg.msh" -o "$OUT/${n}_bamg_s.msh"
  lpcvt -q "$F" -o "$OUT/${n}_lpcvt_tri.msh"
  recombine -q "$OUT/${n}_lpcvt_tri.msh" -o "$OUT/${n}_lpcvt_q.msh"
  quadsmooth -q "$OUT/${n}_lpcvt_q.msh" --frame "$F" -o "$OUT/${n}_lpcvt.msh"
  for m in bamg bamg_s lpcvt; do meshquality "$OUT/${n}_$m.msh" --frame "$F" > "$OUT/${n}_$m.mq.json"; done
}
# eq. 6.1 saddle, sampled at the centres of a 16x16 background on [-1.3, 1.3]^2, times 8
python3 "$SRC/tests/cli/lpcvt_frame.py" "$OUT/saddle_frame.msh" --n 16 --kind saddle --box -1.3 1.3 -1.3 1.3 --factor 8
own_frame saddle
# a curved band (issue #14, item 2): quarter-circle boundary layer about the origin, stretch 10 at
# r = 0.6, width 0.06, isotropic h = 0.02 elsewhere, sampled on a 48x48 background (quadapt convention)
python3 "$SRC/tests/cli/lpcvt_frame.py" "$OUT/band_frame.msh" --n 48 --kind band --h1 0.02 --stretch 10 --band-radius 0.6 --band-width 0.06
own_frame band
# pictures: one boundary-layer case, the three meshes
if command -v rsvg-convert >/dev/null; then
  c=bl15_fb_p2
  meshplot -q "$FIX/output_${c}_2.msh" -o "$OUT/quad-${c}-thesis.png" --width 500 --title "thesis L_p-CVT (output_${c}_2)"
  meshplot -q "$OUT/${c}_bamg.msh" -o "$OUT/quad-${c}-bamgquad.png" --width 500 --title "bamgquad (input_${c}_3)"
  meshplot -q "$OUT/${c}_lpcvt.msh" -o "$OUT/quad-${c}-lpcvt.png" --width 500 --title "lpcvt+recombine+quadsmooth (input_${c}_3)"
  meshplot -q "$OUT/saddle_bamg.msh" -o "$OUT/quad-saddle-bamgquad.png" --width 500 --title "bamgquad, eq. 6.1 x 8"
  meshplot -q "$OUT/saddle_lpcvt.msh" -o "$OUT/quad-saddle-lpcvt.png" --width 500 --title "lpcvt+recombine+quadsmooth, eq. 6.1 x 8"
  meshplot -q "$OUT/band_bamg.msh" -o "$OUT/quad-band-bamgquad.png" --width 500 --title "bamgquad, curved band"
  meshplot -q "$OUT/band_lpcvt.msh" -o "$OUT/quad-band-lpcvt.png" --width 500 --title "lpcvt+recombine+quadsmooth, curved band"
fi
python3 "$(dirname "$0")/table.py" "$OUT" $cases > "$OUT/table.md"
cat "$OUT/table.md"
