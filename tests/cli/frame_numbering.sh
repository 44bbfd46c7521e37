#!/usr/bin/env bash
# CLI test: the tools that read a frame do not depend on how its file numbers the background.
# The same frame written with its nodes and cells in a shuffled order and every quad's vertex
# list starting at another corner (lpcvt_frame.py --shuffle) must give the same bytes from
# lpcvt, recombine, quadsmooth --frame and bamgquad, and the same meshquality --frame figures:
# read_frame puts every frame in a canonical order first (lib/mesh/canonical.hpp). Before it, a
# cell shuffle of a constant 30-degree frame gave 14-18 irregular vertices instead of 18 (the
# lattice start's ties went to the first cell in the file) and a node shuffle of a PHiLiP frame
# moved lpcvt's points by up to 1.7 spacings.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
. "$SRC/tests/cli/lib/assert.sh"
for t in lpcvt recombine quadsmooth bamgquad meshquality; do
  command -v $t >/dev/null || fail "$t not built (tools must be on PATH)"
done
PY=/usr/bin/python3; [ -x $PY ] || PY=python3
in_temp_dir
export OMP_NUM_THREADS=2

# chain NAME: the default chain and bamgquad on NAME.msh; outputs NAME-*.msh, NAME.mq.json
chain() {
  lpcvt -q "$1.msh" -o "$1-tri.msh"
  recombine -q "$1-tri.msh" -o "$1-quad.msh"
  quadsmooth -q "$1-quad.msh" --frame "$1.msh" -o "$1-mesh.msh"
  bamgquad -q "$1.msh" -o "$1-bamg.msh"
  meshquality "$1-mesh.msh" --frame "$1.msh" > "$1.mq.json"
}
same_figures() {  # A.json B.json: every number equal (strings: file names; timings aside)
  $PY - "$1" "$2" <<'PY'
import json, sys
def strip(d):
    if isinstance(d, dict):
        return {k: strip(v) for k, v in d.items()
                if k not in ("provenance", "timings", "time_s", "seconds", "peak_memory_mb") and not isinstance(v, str)}
    if isinstance(d, list):
        return [strip(v) for v in d if not isinstance(v, str)]
    return d
a, b = (strip(json.load(open(p))) for p in sys.argv[1:3])
if a != b:
    sys.exit(f"FAIL: meshquality figures differ between {sys.argv[1]} and {sys.argv[2]}")
PY
}

# a constant 10:1 frame at 30 degrees, and a curved band (stretch 8, graded)
$PY "$SRC/tests/cli/lpcvt_frame.py" c30.msh --n 12 --h1 0.05 --h2 0.005 --theta 0.5235987755982988
$PY "$SRC/tests/cli/lpcvt_frame.py" c30-s.msh --n 12 --h1 0.05 --h2 0.005 --theta 0.5235987755982988 --shuffle 31
$PY "$SRC/tests/cli/lpcvt_frame.py" band.msh --n 16 --kind band --h1 0.04 --stretch 8
$PY "$SRC/tests/cli/lpcvt_frame.py" band-s.msh --n 16 --kind band --h1 0.04 --stretch 8 --shuffle 7
cmp -s c30.msh c30-s.msh && fail "the shuffled frame file is the same file"
for f in c30 band; do
  chain $f
  chain $f-s
  for stage in tri quad mesh bamg; do same_bytes "$f-$stage.msh" "$f-s-$stage.msh"; done
  same_figures "$f.mq.json" "$f-s.mq.json"
done
echo "frame numbering: lpcvt, recombine, quadsmooth, bamgquad byte-identical on 2 shuffled frames"
