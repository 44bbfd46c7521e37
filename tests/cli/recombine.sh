#!/usr/bin/env bash
# CLI test of `recombine`: Gmsh triangles (unit square; square with a hole) -> all-quad mesh;
# report figures, boundary names, bad input (exit 2, nothing written).
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v recombine >/dev/null || { echo "FAIL: recombine not built (tools must be on PATH)" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "SKIPPED: gmsh not installed"; exit 77; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cat > "$T/sq.geo" <<'GEO'
SetFactory("OpenCASCADE");
If (!Exists(hole)) hole = 0; EndIf
Rectangle(1) = {0, 0, 0, 1, 1};
s = 1;
If (hole > 0)
  Disk(2) = {0.5, 0.5, 0, 0.2};
  BooleanDifference(3) = {Surface{1}; Delete;}{Surface{2}; Delete;};
  s = 3;
EndIf
MeshSize{PointsOf{Surface{s};}} = 0.06;
Mesh.Algorithm = 6;
eps = 1e-6;
Physical Curve("bottom", 1) = Curve In BoundingBox{-eps, -eps, -eps, 1 + eps, eps, eps};
Physical Curve("right", 2) = Curve In BoundingBox{1 - eps, -eps, -eps, 1 + eps, 1 + eps, eps};
Physical Curve("top", 3) = Curve In BoundingBox{-eps, 1 - eps, -eps, 1 + eps, 1 + eps, eps};
Physical Curve("left", 4) = Curve In BoundingBox{-eps, -eps, -eps, eps, 1 + eps, eps};
If (hole > 0)
  Physical Curve("hole", 5) = Curve In BoundingBox{0.3 - eps, 0.3 - eps, -eps, 0.7 + eps, 0.7 + eps, eps};
EndIf
Physical Surface("domain", 6) = {s};
GEO
gmsh -2 "$T/sq.geo" -format msh41 -o "$T/tri.msh" >/dev/null
gmsh -2 -setnumber hole 1 "$T/sq.geo" -format msh41 -o "$T/hole.msh" >/dev/null

check() {  # report, expected area, groups...
  python3 - "$@" <<'PY'
import json, math, sys
r = json.load(open(sys.argv[1])); area = float(sys.argv[2]); groups = sys.argv[3:]
b = r["after_blossom"]; q = r["quality"]
def req(c, m):
    if not c: sys.exit("FAIL: " + m)
req(b["triangles_in"] % 2 == 0, "Blossom got an odd triangle count")
req(b["triangles_in"] in (r["triangles_in"], r["triangles_in"] + 1), "triangles_in")
req(r["parity_split"] == (r["triangles_in"] % 2 == 1), "parity split flag")
req(b["triangles"] <= 0.02 * b["triangles_in"], "too many triangles left: greedy fallback?")
req(0.85 * b["triangles_in"] <= 2 * b["quads"] + b["triangles"] <= b["triangles_in"], "quad count")
req(r["cells"] == 4 * b["quads"] + 3 * b["triangles"], "split count")
req(q["quads"] == r["cells"] and q["triangles"] == 0, "not all-quad")
req(q["inverted"] == 0 and q["min_scaled_jacobian"] > 0, "inverted cells")
req(abs(q["area"] - area) < 1e-9, "area %g != %g" % (q["area"], area))
req(q["min_angle_deg"] > 20, "min angle %g" % q["min_angle_deg"])
print("ok: %d triangles -> %d quads + %d triangles -> %d quads, min angle %.1f, min SJ %.3f" %
      (r["triangles_in"], b["quads"], b["triangles"], r["cells"], q["min_angle_deg"], q["min_scaled_jacobian"]))
PY
}

recombine -q "$T/tri.msh" -o "$T/quad.msh"
check "$T/quad.json" 1.0
for g in bottom right top left; do grep -q "\"$g\"" "$T/quad.msh" || fail "group $g lost"; done

recombine -q "$T/hole.msh" -o "$T/hquad.msh"
# the quads cover exactly gmsh's triangles (straight edges, split at midpoints): their area is the
# input's, summed here from hole.msh by an independent reader (was: the report's own value, so
# a quad mesh that moved the hole's nodes passed)
python3 - "$T/hole.msh" > "$T/area" <<'PY'
import os, sys
sys.path.insert(0, os.environ["QUADAPT_SOURCE_DIR"] + "/tests/cli")
from golden_compare import read_msh
m = read_msh(sys.argv[1])
X = m["nodes"]
area = 0.0
for t in m["elements"][2]:
    (ax, ay), (bx, by), (cx, cy) = (X[k][:2] for k in t)
    area += 0.5 * abs((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))
print(repr(area))
PY
check "$T/hquad.json" "$(cat "$T/area")"
python3 - "$T/hquad.json" <<'PY'
import json, math, sys
a = json.load(open(sys.argv[1]))["quality"]["area"]
if not (1 - math.pi * 0.04 < a < 1 - math.pi * 0.04 + 0.01): sys.exit("FAIL: holed area %g" % a)
PY
for g in bottom right top left hole; do grep -q "\"$g\"" "$T/hquad.msh" || fail "group $g lost (hole)"; done

# deterministic
recombine -q "$T/tri.msh" -o "$T/quad2.msh"
cmp -s "$T/quad.msh" "$T/quad2.msh" || fail "output differs between two runs"

# --- bad input: a quad mesh, a non-mesh, an output equal to the input -> exit 2, nothing written
set +e
recombine -q "$SRC/examples/meshes/square16.msh" -o "$T/bad1.msh" 2>"$T/err1"; rc1=$?
echo "not a mesh" > "$T/junk.msh"
recombine -q "$T/junk.msh" -o "$T/bad2.msh" 2>"$T/err2"; rc2=$?
recombine -q "$T/tri.msh" -o "$T/tri.msh" 2>"$T/err3"; rc3=$?
set -e
[ $rc1 = 2 ] || fail "quad input: exit $rc1"
grep -qi "triang" "$T/err1" || fail "quad input: message: $(cat "$T/err1")"
[ $rc2 = 2 ] || fail "junk input: exit $rc2"
[ $rc3 = 2 ] || fail "output = input: exit $rc3"
[ ! -e "$T/bad1.msh" ] && [ ! -e "$T/bad2.msh" ] && [ ! -e "$T/bad1.json" ] || fail "something written on bad input"
echo "recombine: all checks passed"
