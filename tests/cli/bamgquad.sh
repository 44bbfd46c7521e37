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

# --- a node no cell uses: dropped before BAMG (ffbamg aborted, "Err mesh vertices 122 is not in a
# triangle", and bamgquad printed its 478-character crash dump; the other tools accept the file)
python3 - "$T/frame.msh" "$T/unused.msh" <<'PY'
import sys
L = open(sys.argv[1]).read().split("\n")
i = L.index("$Nodes")
L[i + 1] = str(int(L[i + 1]) + 1)
L.insert(L.index("$EndNodes"), "99999 0.37 0.61 0")
open(sys.argv[2], "w").write("\n".join(L))
PY
bamgquad -q "$T/unused.msh" -o "$T/unused_q.msh" 2> "$T/err_unused" || fail "unused node: $(cat "$T/err_unused")"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert abs(r['complexity_ratio']-1) <= 0.15, r['cells']" "$T/unused_q.json" ||
  fail "unused node: cell count"

# --- a pinched domain (a bottom quad's upper-left half missing: its corner on the bottom is on four
# free edges): one line naming the input and the pinch, from bamgquad and lpcvt (they said "mesh:
# boundary node ... starts two boundary edges" and "lpcvt: lpcvt: invalid output triangulation")
python3 - "$T/frame.msh" "$T/pinched.msh" <<'PY'
import sys
L = open(sys.argv[1]).read().split("\n")
for k, l in enumerate(L):
    f = l.split()
    if len(f) == 9 and f[1] == "3" and f[5] == "6" and f[6] == "7":  # the quad 6 7 18 17 (bottom row)
        L[k] = " ".join([f[0], "2"] + f[2:8])
        break
else:
    sys.exit("no such quad")
open(sys.argv[2], "w").write("\n".join(L))
PY
for tool in bamgquad lpcvt; do
  set +e
  $tool "$T/pinched.msh" -o "$T/pinched_$tool.msh" 2> "$T/err_pinched"; rc=$?
  set -e
  [ $rc = 2 ] || fail "pinched, $tool: exit $rc ($(cat "$T/err_pinched"))"
  [ "$(wc -l < "$T/err_pinched")" = 1 ] || fail "pinched, $tool: not one line: $(cat "$T/err_pinched")"
  grep -q "^$tool: $T/pinched.msh: the domain is pinched: the boundary node at (0.5, 0) " "$T/err_pinched" ||
    fail "pinched, $tool: $(cat "$T/err_pinched")"
  [ ! -e "$T/pinched_$tool.msh" ] || fail "pinched, $tool: output written"
done

# --- an ffbamg that fails: one line naming the input and ffbamg's own error line (was its whole log)
cat > "$T/fakebamg" <<'SH'
#!/bin/sh
echo "  -- mesh:  Mesh Generator bamg version 1.02 : banner"
echo "  Err mesh vertices 7 is not in a  triangle"
echo "terminate called after throwing an instance of 'bamg::ErrorMesh'"
exit 1
SH
chmod +x "$T/fakebamg"
set +e
QUADAPT_FFBAMG="$T/fakebamg" bamgquad -q "$T/frame.msh" -o "$T/fake.msh" 2> "$T/err_fake"; rc=$?
set -e
[ $rc = 2 ] && [ "$(wc -l < "$T/err_fake")" = 1 ] || fail "failing ffbamg: exit $rc: $(cat "$T/err_fake")"
grep -q "^bamgquad: $T/frame.msh: ffbamg failed (exit status 1): Err mesh vertices 7 is not in a triangle$" "$T/err_fake" ||
  fail "failing ffbamg: $(cat "$T/err_fake")"

# --- an ffbamg that cannot be started: the machine's problem, not the frame's — one line naming
# ffbamg and its package, not the frame (it said "frame.msh: cannot run ...": a CLI audit)
set +e
QUADAPT_FFBAMG="$T/no-such-ffbamg" bamgquad -q "$T/frame.msh" -o "$T/nob.msh" 2> "$T/err_nob"; rc=$?
set -e
[ $rc = 2 ] && [ "$(wc -l < "$T/err_nob")" = 1 ] && [ ! -e "$T/nob.msh" ] || fail "missing ffbamg: exit $rc: $(cat "$T/err_nob")"
grep -q "^bamgquad: cannot run '$T/no-such-ffbamg' (FreeFEM's BAMG; Debian package freefem++): No such file or directory$" "$T/err_nob" ||
  fail "missing ffbamg: $(cat "$T/err_nob")"

# --- a count far off the target says so (was exit 0 and silent: 4 cells for 1000 at --edge-factor 1e6)
bamgquad "$T/frame.msh" -o "$T/ef.msh" --edge-factor 1e6 2> "$T/err_ef" || fail "--edge-factor 1e6: $(cat "$T/err_ef")"
grep -q "^bamgquad: warning: [0-9]* cells for the frame's target of 1000 (ratio .*) after [0-9] BAMG run(s): --edge-factor far from its default?$" "$T/err_ef" ||
  fail "--edge-factor 1e6: no warning: $(cat "$T/err_ef")"
bamgquad "$T/frame.msh" -o "$T/q2.msh" 2> "$T/err_q2"
if grep -q "warning" "$T/err_q2"; then fail "a warning on a calibrated run: $(cat "$T/err_q2")"; fi
echo "bamgquad: all checks passed"
