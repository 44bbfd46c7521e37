#!/usr/bin/env bash
# CLI test: lpcvt's frame filters do not depend on the coordinate axes on a graded frame.
# PHiLiP's ss15_fb_p1 step-3 frame (rough: its neighbouring cells differ by up to 68x), turned by
# 90 degrees ((x, y) -> (-y, x)) and mirrored ((x, y) -> (-x, y)) — both exact in floating point,
# the frame M turned with them (M' = M Q^T: entries swapped and negated, no rounding). The frame
# lpcvt actually meshes (`--write-frame`: after the smoothing, the gradation and the rescale) must
# be the turned / mirrored one, M'^T M' = Q M^T M Q^T to 1e-9 (relative) in every cell.
# The turned and mirrored frames have another canonical order (mesh/canonical.hpp sorts nodes by
# x, then y): before the gradation took the finest cell first (metric_filter.hpp), its worklist
# followed that order and the graded frames differed by up to 21 % (57 % in test_fast's rougher frame).
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v lpcvt >/dev/null || { echo "FAIL: lpcvt not built (tools must be on PATH)" >&2; exit 1; }
PY=/usr/bin/python3; [ -x $PY ] || PY=python3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
export OMP_NUM_THREADS=1
F="$SRC/tests/fixtures/philip/input_ss15_fb_p1_3.msh"

# the frame re-written (MSH 2.2, cells and Vinv) as base, rot (r1) and mir (m0): tests/cli/frame_transform.py
for sym in "id base" "r1 rot" "m0 mir"; do
  set -- $sym
  $PY "$SRC/tests/cli/frame_transform.py" "$F" "$T/$2.msh" "$1"
done
for n in base rot mir; do
  lpcvt -q "$T/$n.msh" --convention philip -o "$T/$n-tri.msh" --write-frame "$T/$n-frame.msh" \
    --max-iterations 1 --max-cycles 1 --report "$T/$n.json"
done

$PY - "$T" "$SRC" <<'PY'
import json, os, sys
import numpy as np
T, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tests", "cli"))
from golden_compare import read_msh  # noqa: E402
def fail(msg):
    print("FAIL: " + msg, file=sys.stderr); sys.exit(1)
def frame(name):
    """cell centroids (n x 2) and M^T M (n x 2 x 2) of the frame lpcvt meshed"""
    m = read_msh(f"{T}/{name}-frame.msh")
    nodes = np.array(m["nodes"])[:, :2]
    (etype, cells), = [(t, c) for t, c in m["elements"].items() if t in (2, 3)]
    vals = m["views"]["Vinv"]["values"]
    g = np.array([nodes[c].mean(axis=0) for c in cells])
    M = np.array([[[vals[(etype, e)][0], vals[(etype, e)][1]], [vals[(etype, e)][3], vals[(etype, e)][4]]]
                  for e in range(len(cells))])
    return g, np.einsum("nki,nkj->nij", M, M)
g0, A0 = frame("base")
grad = json.load(open(f"{T}/base.json"))["gradation"]
if grad["cells_changed"] < 100:
    fail(f"the gradation changed only {grad['cells_changed']} cells: this frame no longer tests it")
Q = {"rot": np.array([[0.0, -1.0], [1.0, 0.0]]), "mir": np.array([[-1.0, 0.0], [0.0, 1.0]])}
for name, q in Q.items():
    g, A = frame(name)
    if len(g) != len(g0):
        fail(f"{name}: {len(g)} frame cells, the original {len(g0)}")
    back = g @ q  # q^T x: the centroids mapped back (q orthogonal)
    d = np.sqrt(((g0[:, None, :] - back[None, :, :]) ** 2).sum(-1))
    match = d.argmin(axis=1)
    if d.min(axis=1).max() > 1e-12 or len(set(match.tolist())) != len(g0):
        fail(f"{name}: the frame's cells are not the mapped ones")
    want = np.einsum("ij,njk,lk->nil", q, A0, q)  # Q A Q^T
    rel = np.abs(A[match] - want).reshape(len(g0), 4).max(axis=1) / np.abs(want).reshape(len(g0), 4).max(axis=1)
    print(f"{name}: {grad['cells_changed']} cells graded; largest relative difference of M^T M {rel.max():.2e}")
    if rel.max() > 1e-9:
        fail(f"{name}: the frame lpcvt meshed is not the {name} of the original's "
             f"({int((rel > 1e-9).sum())} cells differ, by up to {100 * rel.max():.1f} %)")
print("ok: the graded frame turns and mirrors with the problem")
PY
