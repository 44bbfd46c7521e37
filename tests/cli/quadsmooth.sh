#!/usr/bin/env bash
# CLI test of `quadsmooth`: on recombine's all-quad output the minimum angle never drops and the
# mean cell minimum angle rises; boundary names and nodes survive; bad input -> exit 2.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v quadsmooth >/dev/null && command -v recombine >/dev/null || { echo "FAIL: quad tools not built (tools must be on PATH)" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "SKIPPED: gmsh not installed"; exit 77; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# triangles of the L-shape (non-convex, 6 boundary groups), then recombine
sed '/Recombin/d' "$SRC/examples/geometry/l_shape.geo" > "$T/l.geo"
gmsh -2 "$T/l.geo" -format msh41 -o "$T/l.msh" >/dev/null
recombine -q "$T/l.msh" -o "$T/lq.msh"
IN="$T/lq.msh"

for sweeps in 1 3; do
  quadsmooth -q "$IN" --sweeps $sweeps -o "$T/s$sweeps.msh"
  python3 - "$T/s$sweeps.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); b = r["quality_before"]; a = r["quality"]
def req(c, m):
    if not c: sys.exit("FAIL: " + m)
req(a["min_angle_deg"] >= b["min_angle_deg"], "min angle dropped %g -> %g" % (b["min_angle_deg"], a["min_angle_deg"]))
req(a["inverted"] == 0 and a["min_scaled_jacobian"] > 0, "inverted cells")
req(abs(a["area"] - b["area"]) < 1e-12 * b["area"] + 1e-15, "area changed (boundary moved)")
req(a["mean_cell_min_angle_deg"] >= b["mean_cell_min_angle_deg"], "mean cell min angle dropped")
req(r["sweeps"] >= 1 and r["moves_full"] + r["moves_reduced"] > 0, "nothing moved")
print("ok: sweeps %d, min angle %.2f -> %.2f, mean cell min angle %.2f -> %.2f" % (r["sweeps"],
      b["min_angle_deg"], a["min_angle_deg"], b["mean_cell_min_angle_deg"], a["mean_cell_min_angle_deg"]))
PY
done
python3 - "$IN" "$T/s3.msh" <<'PY'
import sys
def groups(f):
    t = open(f).read(); i = t.index("$PhysicalNames"); n = int(t[i:].split("\n")[1])
    return sorted(l.split()[-1] for l in t[i:].split("\n")[2:2 + n] if l.split()[0] == "1")
if groups(sys.argv[1]) != groups(sys.argv[2]): sys.exit("FAIL: boundary groups %s -> %s" % (groups(sys.argv[1]), groups(sys.argv[2])))
if len(groups(sys.argv[2])) != 6: sys.exit("FAIL: expected the L-shape's 6 groups")
print("ok: groups", groups(sys.argv[2]))
PY

# --- bad input: a file that is not a mesh; an inverted cell -> exit 2, nothing written
echo "garbage" > "$T/junk.msh"
cat > "$T/inv.msh" <<'MSH'
$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
6
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
5 1 1 0
6 2 1 0
$EndNodes
$Elements
2
1 3 2 1 1 1 2 5 4
2 3 2 1 1 2 5 6 3
$EndElements
MSH
set +e
quadsmooth -q "$T/junk.msh" -o "$T/bad.msh" 2>"$T/err"; rc=$?
quadsmooth -q "$T/inv.msh" -o "$T/bad2.msh" 2>"$T/err2"; rc2=$?
set -e
[ $rc = 2 ] || fail "junk: exit $rc"
[ $rc2 = 2 ] || fail "inverted cell: exit $rc2"
grep -qi "invert" "$T/err2" || fail "inverted cell: message: $(cat "$T/err2")"
[ ! -e "$T/bad.msh" ] && [ ! -e "$T/bad2.msh" ] || fail "output written on bad input"
# --- with --frame the default is the shape fit in the frame's metric (docs/quadsmooth.md): the
# report names it, the mean metric angle deviation falls, no cell inverts; --method angle is the
# Zhou-Shimada smoothing; --method shape without a frame is bad input (exit 2, nothing written)
python3 "$SRC/tests/cli/lpcvt_frame.py" "$T/frame.msh" --n 8 --h1 0.02 --h2 0.02 --theta 0.5
quadsmooth -q "$IN" --frame "$T/frame.msh" -o "$T/fs.msh"
quadsmooth -q "$IN" --frame "$T/frame.msh" --method angle -o "$T/fa.msh"
for f in "$IN" fs fa; do
  g="$f"; [ "$f" = "$IN" ] || g="$T/$f.msh"
  meshquality "$g" --frame "$T/frame.msh" > "$T/$(basename "$g" .msh).q.json"
done
python3 - "$T/fs.json" "$T/lq.q.json" "$T/fs.q.json" "$T/fa.q.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); q0, qs, qa = (json.load(open(f))["metric"] for f in sys.argv[2:])
def req(c, m):
    if not c: sys.exit("FAIL: " + m)
req(r["options"]["method"] == "shape", "default method with --frame: %s" % r["options"]["method"])
d0, ds, da = (q["quad_angle_deviation_mean_deg"] for q in (q0, qs, qa))
req(ds < d0, "shape fit: metric angle deviation %g -> %g" % (d0, ds))
req(r["quality"]["inverted"] == 0, "shape fit: inverted cells")
print("ok: metric angle deviation %.2f -> %.2f (shape), %.2f (angle)" % (d0, ds, da))
PY
# --- the shape fit slides wall nodes along straight walls (docs/quadsmooth.md, "Walls"): on the
# L-shape (axis-parallel walls, 6 groups) every boundary edge keeps its wall's coordinate bit for
# bit, the corners and the groups' ends stay, some wall nodes move; --walls fixed moves none
quadsmooth -q "$IN" --frame "$T/frame.msh" --walls fixed -o "$T/ff.msh"
python3 - "$SRC/tests/cli" "$IN" "$T/fs.msh" "$T/fs.json" "$T/ff.msh" "$T/ff.json" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[1])
from golden_compare import read_msh
m0, ms, mf = (read_msh(f) for f in (sys.argv[2], sys.argv[3], sys.argv[5]))
rs, rf = json.load(open(sys.argv[4])), json.load(open(sys.argv[6]))
def req(c, m):
    if not c: sys.exit("FAIL: " + m)
req(rs["options"]["walls"] == "slide" and rf["options"]["walls"] == "fixed", "options.walls: %s, %s" % (rs["options"]["walls"], rf["options"]["walls"]))
req(rs["sliding_wall_nodes"] > 0 and rf["sliding_wall_nodes"] == 0, "sliding_wall_nodes %d, %d" % (rs["sliding_wall_nodes"], rf["sliding_wall_nodes"]))
x0, xs, xf = (m["nodes"] for m in (m0, ms, mf))
edges = m0["elements"][1]
nbrs = {}  # boundary node -> its wall neighbours
for a, b in edges:
    nbrs.setdefault(a, []).append(b)
    nbrs.setdefault(b, []).append(a)
moved = 0
for a, b in edges:
    axis = 0 if x0[a][0] == x0[b][0] else 1  # the coordinate constant along the wall
    req(x0[a][axis] == x0[b][axis], "the L-shape's wall edge %d-%d is not axis-parallel" % (a, b))
    for v in (a, b):
        req(xs[v][axis] == x0[v][axis], "slide: node %d left its wall: %r -> %r" % (v, x0[v], xs[v]))
        req(xf[v] == x0[v], "--walls fixed: boundary node %d moved" % v)
for v, w in nbrs.items():  # the L-shape's 6 corners (where its 6 groups meet) stay
    corner = len(w) != 2 or (x0[w[0]][0] != x0[w[1]][0] and x0[w[0]][1] != x0[w[1]][1])
    if corner: req(xs[v] == x0[v], "slide: corner %d moved" % v)
    moved += xs[v] != x0[v]
req(moved > 0, "slide: no wall node moved")
print("ok: %d of %d wall nodes slid, every one on its wall; --walls fixed: none moved" % (moved, len(nbrs)))
PY
# --- the report says which rule ended the sweeps: the cap ("sweeps": --sweeps 2 with the default
# tolerance) or the tolerance ("tolerance": 10 edge lengths, met by the first sweep)
quadsmooth -q "$IN" --frame "$T/frame.msh" --sweeps 2 -o "$T/cap.msh"
quadsmooth -q "$IN" --frame "$T/frame.msh" --sweeps 5 --tolerance 10 -o "$T/tol.msh"
python3 - "$T/cap.json" "$T/tol.json" <<'PY'
import json, sys
cap, tol = (json.load(open(f)) for f in sys.argv[1:])
def req(c, m):
    if not c: sys.exit("FAIL: " + m)
req(cap["sweeps"] == 2 and cap["stop"] == "sweeps", "--sweeps 2: %s sweeps, stop %s" % (cap["sweeps"], cap["stop"]))
req(tol["sweeps"] == 1 and tol["stop"] == "tolerance", "--tolerance 10: %s sweeps, stop %s" % (tol["sweeps"], tol["stop"]))
print("ok: stop 'sweeps' after the cap of 2, 'tolerance' after 1 sweep")
PY
# --- --fit-frame (docs/quadsmooth.md, "Which frame the fit aims at"): on a graded frame (a curved
# band) raw is the default (the same bytes), meshed and capped aim at other frames (other meshes),
# the report says which and what the filter changed; capped caps cells; no cell inverts
python3 "$SRC/tests/cli/lpcvt_frame.py" "$T/band.msh" --n 12 --kind band --h1 0.05 --stretch 6 --band-radius 0.4 --band-width 0.08
quadsmooth -q "$IN" --frame "$T/band.msh" -o "$T/b0.msh"
for ff in raw meshed capped; do quadsmooth -q "$IN" --frame "$T/band.msh" --fit-frame $ff -o "$T/b$ff.msh"; done
cmp -s "$T/b0.msh" "$T/braw.msh" || fail "--fit-frame raw: not the default's bytes"
! cmp -s "$T/braw.msh" "$T/bmeshed.msh" || fail "--fit-frame meshed: the same mesh as raw"
! cmp -s "$T/bmeshed.msh" "$T/bcapped.msh" || fail "--fit-frame capped: the same mesh as meshed"
python3 - "$T/b0.json" "$T/bmeshed.json" "$T/bcapped.json" <<'PY'
import json, sys
r0, rm, rc = (json.load(open(f)) for f in sys.argv[1:])
def req(c, m):
    if not c: sys.exit("FAIL: " + m)
req(r0["options"]["fit_frame"] == "raw" and "fit_frame" not in r0, "default: options.fit_frame %s" % r0["options"].get("fit_frame"))
req(rm["fit_frame"]["mode"] == "meshed" and rm["fit_frame"]["smoothed_cells"] > 0 and rm["fit_frame"]["capped_cells"] == 0,
    "meshed: report %r" % rm["fit_frame"])
req(rc["fit_frame"]["mode"] == "capped" and rc["fit_frame"]["capped_cells"] > 0 and rc["fit_frame"]["cap_rescale"] < 1,
    "capped: report %r" % rc["fit_frame"])
req(rm["options"]["frame_smooth"] == 4 and rm["options"]["frame_gradation"] == 2, "meshed: filter options %r" % rm["options"])
for r in (r0, rm, rc):
    req(r["quality"]["inverted"] == 0, "inverted cells with --fit-frame %s" % r["options"]["fit_frame"])
print("ok: --fit-frame raw (default) / meshed / capped: %d cells smoothed, %d capped (rescale %.3f)" % (
    rm["fit_frame"]["smoothed_cells"], rc["fit_frame"]["capped_cells"], rc["fit_frame"]["cap_rescale"]))
PY
set +e
quadsmooth -q "$IN" --frame "$T/band.msh" --method angle --fit-frame capped -o "$T/bad4.msh" 2>"$T/err4"; rc4=$?
quadsmooth -q "$IN" --frame "$T/band.msh" --fit-frame meshed --frame-gradation 0.5 -o "$T/bad5.msh" 2>"$T/err5"; rc5=$?
set -e
[ $rc4 = 2 ] && grep -q "shape fit only" "$T/err4" || fail "--fit-frame with --method angle: exit $rc4, $(cat "$T/err4")"
[ $rc5 = 2 ] && grep -q -- "--frame-gradation: 0.5 is not 0 (off) or in (1, inf)" "$T/err5" || fail "--frame-gradation 0.5: exit $rc5, $(cat "$T/err5")"
[ ! -e "$T/bad4.msh" ] && [ ! -e "$T/bad5.msh" ] || fail "output written on bad options"
set +e
quadsmooth -q "$IN" --method shape -o "$T/bad3.msh" 2>"$T/err3"; rc3=$?
set -e
[ $rc3 = 2 ] || fail "--method shape without --frame: exit $rc3"
[ ! -e "$T/bad3.msh" ] || fail "--method shape without --frame: output written"
# a frame that does not cover the mesh (another domain's): a warning naming both files and the
# count, in the report too (was silent: a reviewer's L-shape frame on a wider mesh, min angle 90 -> 42)
python3 "$SRC/tests/cli/lpcvt_frame.py" "$T/small.msh" --n 8 --h1 0.02 --h2 0.02 --box 0 0.5 0 0.5
quadsmooth "$IN" --frame "$T/small.msh" -o "$T/fsm.msh" 2>"$T/err4" || fail "frame not covering the mesh: exit $?"
grep -q "warning: .* cells of $IN have their centroid outside $T/small.msh's background" "$T/err4" || fail "no coverage warning: $(cat "$T/err4")"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert r['cells_outside_frame'] > 0, r['cells_outside_frame']" "$T/fsm.json" || fail "cells_outside_frame"
quadsmooth "$IN" --frame "$T/frame.msh" -o "$T/fs2.msh" 2>"$T/err5"
! grep -q "outside" "$T/err5" || fail "coverage warning with a covering frame: $(cat "$T/err5")"
# recombine --frame says it too (it used the nearest frame cell silently: a CLI audit)
lpcvt -q "$T/frame.msh" -o "$T/ct.msh"
recombine "$T/ct.msh" --frame "$T/small.msh" -o "$T/cq.msh" 2>"$T/err6" || fail "recombine, frame not covering: exit $?"
grep -q "warning: .* cells of $T/ct.msh have their centroid outside $T/small.msh's background" "$T/err6" ||
  fail "recombine: no coverage warning: $(cat "$T/err6")"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert r['cells_outside_frame'] > 0, r['cells_outside_frame']" "$T/cq.json" ||
  fail "recombine: cells_outside_frame"
recombine "$T/ct.msh" --frame "$T/frame.msh" -o "$T/cq2.msh" 2>"$T/err7"
! grep -q "outside" "$T/err7" || fail "recombine: coverage warning with a covering frame: $(cat "$T/err7")"
echo "quadsmooth: all checks passed"
