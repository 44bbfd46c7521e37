#!/usr/bin/env bash
# CLI test: where the domain lies does not matter. The 10:1 frame at 30 degrees on the unit
# square, and the same frame moved to [1e7, 1e7 + 1]^2 (an exact translation: the grid's
# coordinates are 1e7 + i/16). The L_p-CVT chain and bamgquad must give the same meshes, moved.
# Before session 35 the shoelace area on absolute coordinates (|x|^2 eps = 1e-2 at 1e7) called
# every cell "degenerate: zero area" (lpcvt, bamgquad, meshconvert exit 2 on reading), and
# ffbamg, given the coordinates as they are, aborted ("Fatal error in the mesh generator") from
# an offset of 1e6 on.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
export QUADAPT_SOURCE_DIR=$SRC
source "$SRC/tests/cli/lib/assert.sh"
PY=/usr/bin/python3; [ -x $PY ] || PY=python3
in_temp_dir
export OMP_NUM_THREADS=1

for X in 0 10000000; do
  $PY "$SRC/tests/cli/lpcvt_frame.py" f$X.msh --n 16 --h1 0.05 --h2 0.005 --theta 0.5236 \
    --box $X $((X + 1)) $X $((X + 1))
  lpcvt -q f$X.msh -o t$X.msh
  recombine -q t$X.msh -o q$X.msh
  quadsmooth -q q$X.msh --frame f$X.msh -o m$X.msh
  meshquality m$X.msh --frame f$X.msh > mq$X.json
  bamgquad -q f$X.msh -o b$X.msh
  meshquality b$X.msh --frame f$X.msh > bq$X.json
done

$PY - "$SRC" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[1] + "/tests/cli")
from golden_compare import read_msh
def fail(m):
    print("FAIL: " + m, file=sys.stderr); sys.exit(1)
def read_nodes(path):
    return [tuple(x[:2]) for x in read_msh(path)["nodes"]]
for name in ("mq", "bq"):
    a, b = json.load(open(f"{name}0.json")), json.load(open(f"{name}10000000.json"))
    for key in ("cells", "nodes", "irregular_interior_vertices"):
        if a[key] != b[key]:
            fail(f"{name}: {key} {a[key]} at the origin, {b[key]} at 1e7")
    # coordinates at 1e7 are rounded to 1e-9, 2e-7 of the short edge 0.005; lpcvt's minimisation
    # carries that to ~1e-6 (3.5e-7 before its metric flips went most violated first, 9.9e-7
    # since), and recombine and quadsmooth to ~2e-4 deg in the mean angle deviation (measured
    # 1.7e-4; 1e-5 before)
    for key, tol in (("scaled_jacobian_min", 1e-5), ("quad_angle_deviation_mean_deg", 1e-3)):
        x, y = a["metric"][key], b["metric"][key]
        if abs(x - y) > tol:
            fail(f"{name}: metric {key} {x} at the origin, {y} at 1e7")
    x, y = a["metric"]["edge_length"]["share_in_range"], b["metric"]["edge_length"]["share_in_range"]
    if x != y:
        fail(f"{name}: edges in range {x} at the origin, {y} at 1e7")
# bamgquad's input to BAMG is the same bytes (shifted by a multiple of a power of two), so BAMG's
# triangles are the same, moved; the smoothing after it carries the rounding of 1e7 (2e-9) to
# 1.4e-6 (measured), 3e-4 of the short edge
p, q = read_nodes("b0.msh"), read_nodes("b10000000.msh")
if len(p) != len(q):
    fail(f"bamgquad: {len(p)} nodes at the origin, {len(q)} at 1e7")
d = max(max(abs(u[0] + 1e7 - v[0]), abs(u[1] + 1e7 - v[1])) for u, v in zip(p, q))
if d > 1e-5:
    fail(f"bamgquad: nodes moved by up to {d} besides the translation")
print(f"placement: chain {json.load(open('mq0.json'))['cells']} cells, bamgquad {len(p)} nodes; "
      f"bamgquad nodes within {d:.1e} of the moved ones")
PY

# a box of extent 1e6 at the origin: ffbamg's coordinates as they are (it writes ~12 digits: a
# scaled copy, tried in session 35, put wall nodes at x = 999999.9999997), so every wall node
# lies exactly on its wall
$PY "$SRC/tests/cli/lpcvt_frame.py" big.msh --n 16 --h1 50000 --h2 5000 --theta 0.5236 --box 0 1000000 0 1000000
bamgquad -q big.msh -o bigq.msh
$PY - "$SRC" <<'PY'
import sys
sys.path.insert(0, sys.argv[1] + "/tests/cli")
from golden_compare import read_msh
xy = [tuple(x[:2]) for x in read_msh("bigq.msh")["nodes"]]
near = [v for p in xy for v in p if 0 < abs(v - 1e6) < 1 or 0 < abs(v) < 1e-6]
if near:
    print(f"FAIL: {len(near)} coordinates off the walls of [0, 1e6]^2, e.g. {near[0]!r}", file=sys.stderr); sys.exit(1)
on = sum(1 for p in xy for v in p if v in (0.0, 1e6))
if on < 40:
    print(f"FAIL: only {on} wall coordinates", file=sys.stderr); sys.exit(1)
PY
echo "placement: OK"
