#!/usr/bin/env bash
# CLI test of `bamgquad`: a constant frame (final quads 0.1 along 30 degrees, 0.01 across) gives
# all-quad cells stretched 10:1 along 30 degrees with the frame's cell count; a PHiLiP frame
# works as it is; quadsmooth keeps it valid; bad frames -> exit 2, nothing written.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
FIX=${QUADAPT_FIXTURES_DIR:-$SRC/tests/fixtures/philip}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v bamgquad >/dev/null || { echo "FAIL: bamgquad not built (tools must be on PATH)" >&2; exit 1; }
command -v ffbamg >/dev/null || [ -n "${QUADAPT_FFBAMG:-}" ] || { echo "SKIPPED: ffbamg (freefem++) not installed"; exit 77; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# frame.py N THETA_DEG H1 H2 OUT [BADCELL BADVALUE]: N x N quads on the unit square (MSH 2.2),
# boundary lines in groups bottom/right/top/left, per-cell Vinv = diag(1/h1, 1/h2) R(-theta).
cat > "$T/frame.py" <<'PY'
import math, sys
n, th, h1, h2, out = int(sys.argv[1]), math.radians(float(sys.argv[2])), float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
bad = (int(sys.argv[6]), sys.argv[7]) if len(sys.argv) > 7 else None
c, s = math.cos(th), math.sin(th)
M = [c / h1, s / h1, -s / h2, c / h2]
node = lambda i, j: j * (n + 1) + i + 1
L = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", "5",
     '1 1 "bottom"', '1 2 "right"', '1 3 "top"', '1 4 "left"', '2 5 "domain"', "$EndPhysicalNames",
     "$Nodes", str((n + 1) ** 2)]
L += ["%d %.17g %.17g 0" % (node(i, j), i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
L += ["$EndNodes"]
E = []
for i in range(n): E.append((1, node(i, 0), node(i + 1, 0)))
for j in range(n): E.append((2, node(n, j), node(n, j + 1)))
for i in range(n): E.append((3, node(i + 1, n), node(i, n)))
for j in range(n): E.append((4, node(0, j + 1), node(0, j)))
Q = [(node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)) for j in range(n) for i in range(n)]
L += ["$Elements", str(len(E) + len(Q))]
k = 0
for g, a, b in E:
    k += 1; L.append("%d 1 2 %d %d %d %d" % (k, g, g, a, b))
q0 = k
for q in Q:
    k += 1; L.append("%d 3 2 5 5 %d %d %d %d" % ((k,) + q))
L += ["$EndElements", "$ElementData", "1", '"Vinv"', "1", "0", "3", "0", "9", str(len(Q))]
for e in range(len(Q)):
    m = list(M)
    if bad and e == bad[0]: m = [float(bad[1])] * 4
    L.append("%d %s" % (q0 + 1 + e, " ".join("%.17g" % x for x in [m[0], m[1], 0, m[2], m[3], 0, 0, 0, 0])))
L += ["$EndElementData", "$FrameConvention", "quadapt", "$EndFrameConvention"]
open(out, "w").write("\n".join(L) + "\n")
PY

# --- constant frame: final quads 2 h1 = 0.1 along 30 degrees, 2 h2 = 0.01 across; 1000 cells
python3 "$T/frame.py" 10 30 0.05 0.005 "$T/frame.msh"
bamgquad -q "$T/frame.msh" -o "$T/q.msh"
# more cells than BAMG's vertex limit can give (~4 per vertex): exit 2 before BAMG runs (was: exit
# 0 with the limit's mesh, ratio 1.7e-10 on a frame scaled by 1e6)
rc=0; bamgquad "$T/frame.msh" -o "$T/big.msh" --max-vertices 200 2> "$T/big.err" || rc=$?
[ $rc -eq 2 ] && grep -q "frame.msh: the frame asks for 1.000e+03 cells; BAMG would need about 2.500e+02 vertices, more than --max-vertices 200" "$T/big.err" ||
  { cat "$T/big.err"; echo "FAIL: --max-vertices: exit $rc"; exit 1; }
[ ! -e "$T/big.msh" ] || { echo "FAIL: --max-vertices wrote output"; exit 1; }
python3 - "$T/q.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); q = r["quality"]; s = r["stretch"]
def req(c, m):
    if not c: sys.exit("FAIL: " + m)
req(abs(r["target_complexity"] - 1000) < 1e-6, "target complexity %g" % r["target_complexity"])
req(abs(r["complexity_ratio"] - 1) <= 0.15, "cells %d vs target 1000" % r["cells"])
req(q["quads"] == r["cells"] and q["triangles"] == 0, "not all-quad")
req(q["inverted"] == 0 and q["min_scaled_jacobian"] > 0, "inverted cells")
req(abs(q["area"] - 1) < 1e-9, "area")
req(abs(s["median_stretch"] / 10 - 1) <= 0.15, "median stretch %g (want 10 +- 15%%)" % s["median_stretch"])
req(abs(s["median_angle_deg"] - 30) <= 5, "median long axis %g deg (want 30 +- 5)" % s["median_angle_deg"])
print("ok: %d cells (target 1000), stretch median %.2f at %.1f deg (mean %.2f at %.1f), min SJ %.3f" %
      (r["cells"], s["median_stretch"], s["median_angle_deg"], s["mean_stretch"], s["mean_angle_deg"], q["min_scaled_jacobian"]))
PY
for g in bottom right top left; do grep -q "\"$g\"" "$T/q.msh" || fail "group $g lost"; done
! grep -q '^\$ElementData' "$T/q.msh" || fail "output carries the frame's field"

# quadsmooth after bamgquad: valid, min angle not lower
if command -v quadsmooth >/dev/null; then
  quadsmooth -q "$T/q.msh" -o "$T/qs.msh"
  python3 - "$T/qs.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
if r["quality"]["min_angle_deg"] < r["quality_before"]["min_angle_deg"] or r["quality"]["inverted"]: sys.exit("FAIL: quadsmooth after bamgquad")
PY
fi

# --- a real PHiLiP frame (no boundary groups in the file: named from the unit square's sides)
F="$FIX/input_ss15_fb_p2_3.msh"
if [ -f "$F" ]; then
  bamgquad -q "$F" -o "$T/ph.msh"  # no flag: the file states no convention, read as PHiLiP's
  python3 - "$T/ph.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); q = r["quality"]
if q["triangles"] or q["inverted"] or q["min_scaled_jacobian"] <= 0: sys.exit("FAIL: PHiLiP frame: not a valid all-quad mesh")
if abs(r["complexity_ratio"] - 1) > 0.10: sys.exit("FAIL: PHiLiP frame: %d cells for a target of %g" % (r["cells"], r["target_complexity"]))
if abs(r["target_complexity"] - 1296) > 1: sys.exit("FAIL: PHiLiP frame: target %g, expected 1296 (full-edge sizes)" % r["target_complexity"])
# calibrated on BAMG's count (2 cells per triangle predicted): fewer Blossom runs than BAMG runs
c = r["calibration"]
if not 1 <= c["blossom_runs"] < c["runs"]: sys.exit("FAIL: PHiLiP frame: %d Blossom runs for %d BAMG runs" % (c["blossom_runs"], c["runs"]))
print("ok: PHiLiP frame: %d cells (target %.0f, first run %.3f of it, %d runs), min SJ %.3f" % (r["cells"],
      r["target_complexity"], r["calibration"]["first_ratio"], r["calibration"]["runs"], q["min_scaled_jacobian"]))
PY
  for g in bottom right top left; do grep -q "\"$g\"" "$T/ph.msh" || fail "PHiLiP frame: group $g missing"; done
fi

# --- bad frames: a singular Vinv (det M = 0), a non-finite Vinv, no Vinv at all -> exit 2, nothing written
python3 "$T/frame.py" 4 0 0.1 0.1 "$T/zero.msh" 5 0
python3 "$T/frame.py" 4 0 0.1 0.1 "$T/nan.msh" 5 nan
python3 "$T/frame.py" 4 0 0.1 0.1 "$T/novinv.msh"
sed -i '/^\$ElementData/,/^\$EndElementData/d' "$T/novinv.msh"
for b in zero nan novinv; do
  set +e
  bamgquad -q "$T/$b.msh" -o "$T/out_$b.msh" 2>"$T/err_$b"; rc=$?
  set -e
  [ $rc = 2 ] || fail "$b: exit $rc ($(cat "$T/err_$b"))"
  [ ! -e "$T/out_$b.msh" ] && [ ! -e "$T/out_$b.json" ] || fail "$b: output written"
  grep -q "$b.msh" "$T/err_$b" || fail "$b: message does not name the file: $(cat "$T/err_$b")"
done
grep -qi "vinv" "$T/err_novinv" || fail "no-Vinv message: $(cat "$T/err_novinv")"
echo "bamgquad: all checks passed"
