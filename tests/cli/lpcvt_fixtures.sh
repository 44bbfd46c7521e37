#!/usr/bin/env bash
# lpcvt on real frames written by the thesis's solver (PHiLiP fixtures, read as they are): with
# the step-3 complexity of the fixtures' README (--complexity, --degree: PHiLiP normalises its
# frames and passes the target separately), lpcvt + recombine give an all-quad mesh whose DOF
# count (cells (p+1)^2) is within 5% of the target. Two fixtures (S-shock p = 1, boundary
# layer p = 2) to keep it fast; docs/bench-lpcvt.md has all eight.
set -euo pipefail
D=$QUADAPT_FIXTURES_DIR
[ -f "$D/input_ss15_fb_p1_3.msh" ] || { echo "FAIL: PHiLiP fixture $D/input_ss15_fb_p1_3.msh missing" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
for spec in ss15_fb_p1:1:3456 bl15_fb_p2:2:7776; do
  IFS=: read -r name p C <<< "$spec"
  lpcvt "$D/input_${name}_3.msh" --complexity "$C" --degree "$p" -o "$T/$name-tri.msh" -q --write-frame "$T/$name-frame.msh"
  recombine "$T/$name-tri.msh" -o "$T/$name-quad.msh" -q
  /usr/bin/python3 - "$T/$name-tri.json" "$T/$name-quad.json" "$p" "$C" <<'PY'
import json, sys
r, q = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
p, C = int(sys.argv[3]), float(sys.argv[4])
assert abs(r["target_cells"] - C / (p + 1) ** 2) < 1e-6 * C, r["target_cells"]
# the count is set to the request; a point found outside the domain or on a boundary segment at
# the end is dropped (remove_outside, triangulate_domain): at most one, measured
assert abs(r["points"] - r["requested_points"]) <= 1.5, (r["points"], r["requested_points"])
dofs = q["cells"] * (p + 1) ** 2
print(f"{sys.argv[1]}: {r['points']} points, {q['cells']} quads, {dofs} DOFs for {C:.0f} ({dofs / C:.3f})")
# Within 5 % (issue #14's target; measured 1.015 and 1.017). Most of PHiLiP's cells store a
# reflected M (det M < 0); before metric_incircle depended on M^T M only, the metric flips were
# anti-Delaunay there and a quarter of the triangles found no convex partner (1.117, 1.163).
assert abs(dofs / C - 1) <= 0.05, (dofs, C)
# split/merge stops once the count leaves [1/1.5, 1.5] x the request (bl15_fb_p2 grew to 4,543
# points over 30 cycles, 347 s, before): a handful of cycles, not the cap of 30
assert len(r["cycle_history"]) <= 8, len(r["cycle_history"])
# frames are smoothed (--smooth 4) then graded (--gradation 2) by default (docs/lpcvt.md): both
# filters ran, and together they lowered the largest neighbour size ratio of the raw frame, on
# the boundary layer's jumps at least by half (measured 5.6 -> 2.4 and 7.1 -> 2.7; the
# anisotropic gradation alone may raise the mean-size ratio a little: 2.19 -> 2.41 on ss15_fb_p1);
# without the defaults there is no "smoothing" or "gradation" key at all
s, g = r["smoothing"], r["gradation"]
# and the lattice of the nearly isotropic cells turned to the walls (--orientation boundary)
assert r["orientation"]["mode"] == "boundary" and r["orientation"]["free_cells"] > 0, r["orientation"]
# the wall points spaced in the energy's L_p norm (--boundary-norm 0 = p = 6; docs/lpcvt.md, Method 2)
assert r["boundary_norm"] == 6, r["boundary_norm"]
assert s["passes"] == 4 and s["cells_changed"] > 0, s
assert g["growth"] == 2.0 and g["cells_changed"] > 0, g
raw, final = s["max_neighbour_size_ratio_before"], g["max_neighbour_size_ratio_after"]
assert final <= raw + 1e-9, (raw, final)
if "bl15" in sys.argv[1]:
    assert final < 0.5 * raw, (raw, final)
PY
  # The metric is M^T M (M = PHiLiP's Vinv as read, rows = the frame's inverse axes), not M M^T:
  # where the solution is steep the frame's short axis (the direction of the largest eigenvalue of
  # M^T M) lies along grad u. S-shock u = 0.75 tanh(4 sin(10y - 5) - 24x + 12): cells with
  # sech^2 of the argument > 0.3; boundary layer (layers on x = 1 and y = 1, eps = 0.005): cells
  # within 0.05 of one wall, grad u along its normal. Measured on the frame lpcvt meshed
  # (--write-frame, after its filters), anisotropic cells (stretch >= 2): medians 1.6 deg (S-shock)
  # and 0.6 deg (boundary layer) for M^T M against 32.7 and 90 deg for M M^T (on the raw files:
  # 3.9 and 1.0 against 34 and 90). Fails if the frame is ever read transposed.
  /usr/bin/python3 - "$T/$name-frame.msh" "$name" "$(dirname "$0")" <<'PY'
import math, sys
import numpy as np
sys.path.insert(0, sys.argv[3])
from golden_compare import read_msh
m = read_msh(sys.argv[1]); V = m["views"]["Vinv"]["values"]; nodes = m["nodes"]
mt, tm = [], []
for (t, i), v in V.items():
    M = np.array([[v[0], v[1]], [v[3], v[4]]])
    x, y = np.array([nodes[n][:2] for n in m["elements"][t][i]]).mean(0)
    if sys.argv[2].startswith("ss"):
        if 1 / math.cosh(4 * math.sin(10 * y - 5) - 24 * x + 12) ** 2 <= 0.3:
            continue
        g = np.array([-24.0, 40 * math.cos(10 * y - 5)])
    else:
        if min(1 - x, 1 - y) > 0.05:
            continue
        g = np.array([1.0, 0.0]) if 1 - x < 1 - y else np.array([0.0, 1.0])
    U, S, Vt = np.linalg.svd(M)
    if S[0] / S[1] < 2:
        continue
    g /= np.linalg.norm(g)
    mt.append(math.degrees(math.acos(min(1.0, abs(Vt[0] @ g)))))
    tm.append(math.degrees(math.acos(min(1.0, abs(U[:, 0] @ g)))))
a, b = float(np.median(mt)), float(np.median(tm))
print(f"{sys.argv[2]}: {len(mt)} steep anisotropic cells: short axis off grad u by {a:.1f} deg (M^T M), {b:.1f} deg (M M^T)")
assert len(mt) >= 50 and a < 10 and b > 25, (len(mt), a, b)
PY
done
# No flag at all: a PHiLiP file states no size convention, so it is read with PHiLiP's full-edge
# sizes and meshes to the 1296 cells it encodes (before quadapt wrote $FrameConvention, a quarter).
name=ss15_fb_p2
lpcvt "$D/input_${name}_3.msh" -o "$T/$name-tri.msh" -q
recombine "$T/$name-tri.msh" -o "$T/$name-quad.msh" -q
/usr/bin/python3 - "$T/$name-tri.json" "$T/$name-quad.json" <<'PY'
import json, sys
r, q = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert r["options"]["convention"] == "philip", r["options"]
assert abs(r["target_cells"] - 1296) < 0.1, r["target_cells"]
print(f"{sys.argv[1]}: no flag: {q['cells']} quads for the frame's 1296 ({q['cells'] / 1296:.3f})")
# The count lpcvt + recombine reach is the point generator's business (1274 before the metric
# cells of 853b8e4, 1540 after); bamgquad.sh checks 1296 +- 10 % with no flag end to end.
assert q["cells"] > 2 * 324, q["cells"]  # not the quarter a quadapt-convention reading asks for
PY
echo "lpcvt_fixtures: ok"
