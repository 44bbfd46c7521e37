#!/usr/bin/env bash
# CLI test: on a graded frame, lpcvt's frame filters and quadsmooth do not depend on the axes.
# PHiLiP's ss15_fb_p1 step-3 frame (rough: its neighbouring cells differ by up to 68x), turned by
# 90 degrees ((x, y) -> (-y, x)) and mirrored ((x, y) -> (-x, y)) — both exact in floating point,
# the frame M turned with them (M' = M Q^T: entries swapped and negated, no rounding;
# tests/cli/frame_transform.py). docs/quad-quality.md, "Turned and mirrored graded frames".
#  1. The frame lpcvt actually meshes (`--write-frame`: after the smoothing, the gradation and the
#     rescale) must be the turned / mirrored one, M'^T M' = Q M^T M Q^T to 1e-9 (relative) in
#     every cell. The turned and mirrored frames have another canonical order (mesh/canonical.hpp
#     sorts nodes by x, then y): before the gradation took the finest cell first
#     (metric_filter.hpp), its worklist followed that order and the graded frames differed by up
#     to 21 % (57 % in test_fast's rougher frame).
#  2. quadsmooth given the turned / mirrored quad mesh and frame must give the turned / mirrored
#     mesh, to 1e-10 of the domain. Before the frame sampler took the finest of the cells that
#     share an edge or vertex (frame.hpp FrameSampler), a wall node on a background vertex took
#     the lowest-numbered cell's metric, and the nodes differed by 3e-2 (turn) and 6e-2 (mirror).
#     The same with the turned / mirrored quads renumbered: before the fit's colouring went by
#     the nodes' metric distance from their centroid (quad/smooth.cpp), it followed the node
#     numbering, and the turned mesh renumbered differed by 7.0e-2 of the domain.
#  3. lpcvt's points (the default run) on the turned / mirrored frame must be the turned / mirrored
#     points, after one iteration to 1e-12 of the domain and after the whole run to 1e-3 (the
#     minimisation carries the rounding of the turned coordinates to 1e-5..1e-3 on PHiLiP's eight
#     frames; here 6e-5 and 7e-5). Before the lattice start's proposals went by ring and distance from the
#     seed (lattice.hpp; the mirror reverses the order +a, +b, -a, -b) and the metric graph's flips
#     most violated first (metric_graph.hpp "Flip order"; split/merge and the exact count measure
#     its edges), up to 0.11 of the domain (mirror) and 0.06 (turn).
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
QUADAPT_SOURCE_DIR=$SRC
. "$SRC/tests/cli/lib/assert.sh"
[ -n "${QUADAPT_BIN_DIR:-}" ] && PATH="$(cd "$QUADAPT_BIN_DIR" && pwd):$PATH"
in_temp_dir
PY=/usr/bin/python3; [ -x $PY ] || PY=python3
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
# 3.: lpcvt's points, after one iteration and after the default run
for n in base rot mir; do
  lpcvt -q "$T/$n.msh" --convention philip -o "$T/$n-one.msh" --max-iterations 1 --max-cycles 1
  lpcvt -q "$T/$n.msh" --convention philip -o "$T/$n-full.msh"
done
# 2.: the base run's quads, turned and mirrored exactly, smoothed in each frame; and the turned
#     ones renumbered (nodes in reversed order), as the chain numbers a turned problem's quads
recombine -q "$T/base-tri.msh" -o "$T/base-quad.msh"
for sym in "id base keep" "r1 rot keep" "m0 mir keep" "r1 rotrev reverse" "m0 mirrev reverse"; do
  set -- $sym
  $PY "$SRC/tests/cli/frame_transform.py" "$T/base-quad.msh" "$T/$2-q.msh" "$1" "$3"
  quadsmooth -q "$T/$2-q.msh" --frame "$T/${2%rev}.msh" -o "$T/$2-smooth.msh"
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
x0 = np.array(read_msh(f"{T}/base-smooth.msh")["nodes"])[:, :2]
span = np.ptp(x0, axis=0).max()
for name, q in list(Q.items()) + [("rotrev", Q["rot"]), ("mirrev", Q["mir"])]:
    x = np.array(read_msh(f"{T}/{name}-smooth.msh")["nodes"])[:, :2] @ q  # mapped back
    if len(x) != len(x0):
        fail(f"quadsmooth {name}: {len(x)} nodes, the original {len(x0)}")
    d = np.sqrt(((x0[:, None, :] - x[None, :, :]) ** 2).sum(-1)).min(axis=1)
    print(f"quadsmooth {name}: largest node distance {d.max() / span:.2e} of the domain")
    if d.max() > 1e-10 * span:
        fail(f"quadsmooth {name}: the smoothed mesh is not the {name} of the original's "
             f"({int((d > 1e-10 * span).sum())} nodes off, by up to {d.max() / span:.2e} of the domain)")
print("ok: quadsmooth's mesh turns and mirrors with the problem")
for run, tol in (("one", 1e-12), ("full", 1e-3)):
    x0 = np.array(read_msh(f"{T}/base-{run}.msh")["nodes"])[:, :2]
    span = np.ptp(x0, axis=0).max()
    for name, q in Q.items():
        x = np.array(read_msh(f"{T}/{name}-{run}.msh")["nodes"])[:, :2] @ q  # mapped back
        if len(x) != len(x0):
            fail(f"lpcvt {name} ({run}): {len(x)} points, the original {len(x0)}")
        d = np.sqrt(((x0[:, None, :] - x[None, :, :]) ** 2).sum(-1)).min(axis=1)
        print(f"lpcvt {name} ({run}): largest point distance {d.max() / span:.2e} of the domain")
        if d.max() > tol * span:
            fail(f"lpcvt {name} ({run}): the points are not the {name} of the original's "
                 f"({int((d > tol * span).sum())} off, by up to {d.max() / span:.2e} of the domain)")
print("ok: lpcvt's points turn and mirror with the problem")
PY
