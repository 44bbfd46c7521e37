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

# the frame re-written (MSH 2.2, quads and Vinv) as base, rot and mir
$PY - "$F" "$T" "$SRC" <<'PY'
import os, sys
F, T, SRC = sys.argv[1:4]
sys.path.insert(0, os.path.join(SRC, "tests", "cli"))
from golden_compare import read_msh  # noqa: E402
m = read_msh(F)
quads, V = m["elements"][3], m["views"]["Vinv"]["values"]
if len(V) != len(quads):
    sys.exit(f"FAIL: {F}: {len(V)} Vinv values for {len(quads)} quads")
def write(name, point, vinv, reverse):
    with open(f"{T}/{name}.msh", "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(m["nodes"]))
        for k, p in enumerate(m["nodes"]):
            x, y = point(p[0], p[1])
            f.write(f"{k + 1} {x!r} {y!r} 0\n")
        f.write("$EndNodes\n$Elements\n%d\n" % len(quads))
        for e, q in enumerate(quads):
            q = q[::-1] if reverse else q
            f.write(f"{e + 1} 3 2 0 1 " + " ".join(str(v + 1) for v in q) + "\n")
        f.write('$EndElements\n$ElementData\n1\n"Vinv"\n1\n0.0\n3\n0\n9\n%d\n' % len(quads))
        for e in range(len(quads)):
            a = V[(3, e)]
            M = [[a[0], a[1]], [a[3], a[4]]]
            W = vinv(M)
            f.write(f"{e + 1} {W[0][0]!r} {W[0][1]!r} 0 {W[1][0]!r} {W[1][1]!r} 0 0 0 1\n")
        f.write("$EndElementData\n")
# M' = M Q^T; rot: Q = [[0, -1], [1, 0]], so M' = [-M[:, 1], M[:, 0]]; mir: Q = diag(-1, 1)
write("base", lambda x, y: (x, y), lambda M: M, False)
write("rot", lambda x, y: (-y, x), lambda M: [[-M[0][1], M[0][0]], [-M[1][1], M[1][0]]], False)
write("mir", lambda x, y: (-x, y), lambda M: [[-M[0][0], M[0][1]], [-M[1][0], M[1][1]]], True)
PY
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
