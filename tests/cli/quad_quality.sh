#!/usr/bin/env bash
# Issue #14's quality targets on two frames the default chain (lpcvt -> recombine -> quadsmooth
# --frame, as the loop runs it) must keep meeting (docs/quad-quality.md):
#  - an isotropic frame at 30° on the unit square: irregular interior vertices <= 3 %, because
#    lpcvt turns the lattice of isotropic cells to the walls (--orientation boundary; with
#    --orientation frame the lattice stays at 30° and 2.9 % of the vertices are irregular, 4.3 %
#    before the L_6 wall spacing and the interior bonus; the check is only that it is worse);
#  - a 5:1 frame at 30°: irregular interior vertices <= 3 %, because lpcvt spaces the wall points
#    by the L_p metric length (--boundary-norm, default the exponent 6: one wall point per lattice
#    row; with the thesis's Euclidean length, --boundary-norm 2, more: 3.2 % before the interior bonus);
#  - a 5:1 frame at 45°: irregular interior vertices <= 3 %, because recombine's matching leaves
#    the lattice's lone triangles at the walls (--interior-bonus, default 0.1; with 0: 3.9 %);
#  - the same 5:1 frame at 30°: mean metric angle deviation <= 8 °, because quadsmooth slides the
#    wall nodes along the walls (--walls slide, the default: 4.1°; with --walls fixed the lattice
#    stays sheared by the walls' angle, 6.7°; the check is that fixed walls are worse by 1°);
#  - the curved band (stretch 10 on a quarter circle): metric corners within 90 +- 10° >= 0.6,
#    edges in range >= 0.8, count within 5 %, valid.
set -euo pipefail
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
for t in lpcvt recombine quadsmooth meshquality; do command -v $t >/dev/null || { echo "FAIL: $t not built (tools must be on PATH)" >&2; exit 1; }; done
HERE=$(cd "$(dirname "$0")" && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
export OMP_NUM_THREADS=1

chain() {  # chain FRAME NAME [lpcvt options]; RECOMBINE="recombine options"
  local f=$1 n=$2; shift 2
  lpcvt -q "$f" -o "$T/$n-tri.msh" --seed 3 "$@"
  recombine -q "$T/$n-tri.msh" -o "$T/$n-quad.msh" ${RECOMBINE:-}
  quadsmooth -q "$T/$n-quad.msh" --frame "$f" -o "$T/$n-mesh.msh"
  meshquality "$T/$n-mesh.msh" --frame "$f" > "$T/$n.mq.json"
}

python3 "$HERE/lpcvt_frame.py" "$T/iso30.msh" --n 16 --h1 0.0158113883 --h2 0.0158113883 --theta 0.5235987756
chain "$T/iso30.msh" iso30
chain "$T/iso30.msh" iso30-frame --orientation frame
python3 "$HERE/lpcvt_frame.py" "$T/a30s5.msh" --n 16 --h1 0.0353553391 --h2 0.0070710678 --theta 0.5235987756
chain "$T/a30s5.msh" a30s5
chain "$T/a30s5.msh" a30s5-l2 --boundary-norm 2
quadsmooth -q "$T/a30s5-quad.msh" --frame "$T/a30s5.msh" --walls fixed -o "$T/a30s5-fixed-mesh.msh"
meshquality "$T/a30s5-fixed-mesh.msh" --frame "$T/a30s5.msh" > "$T/a30s5-fixed.mq.json"
python3 "$HERE/lpcvt_frame.py" "$T/a45s5.msh" --n 16 --h1 0.0353553391 --h2 0.0070710678 --theta 0.7853981633974483
chain "$T/a45s5.msh" a45s5
RECOMBINE="--interior-bonus 0" chain "$T/a45s5.msh" a45s5-nobonus
python3 "$HERE/lpcvt_frame.py" "$T/band.msh" --n 48 --kind band --h1 0.02
chain "$T/band.msh" band

python3 - "$T" <<'PY'
import json, sys
T = sys.argv[1]
def J(n): return json.load(open("%s/%s.mq.json" % (T, n)))
def req(c, m):
    if not c: sys.exit("FAIL: " + m)
a, b, c = J("iso30"), J("iso30-frame"), J("band")
req(a["irregular_interior_share"] <= 0.03, "isotropic 30°: %.1f %% irregular (> 3 %%)" % (100 * a["irregular_interior_share"]))
req(b["irregular_interior_share"] > a["irregular_interior_share"],
    "isotropic 30°: --orientation frame no worse than boundary (%.3f vs %.3f): the test lost its point"
    % (b["irregular_interior_share"], a["irregular_interior_share"]))
d, e = J("a30s5"), J("a30s5-l2")
req(d["irregular_interior_share"] <= 0.03, "30°, 5:1: %.1f %% irregular (> 3 %%)" % (100 * d["irregular_interior_share"]))
req(e["irregular_interior_share"] > d["irregular_interior_share"],
    "30°, 5:1: --boundary-norm 2 no worse than the default (%.3f vs %.3f): the test lost its point"
    % (e["irregular_interior_share"], d["irregular_interior_share"]))
dd, df = d["metric"]["quad_angle_deviation_mean_deg"], J("a30s5-fixed")["metric"]["quad_angle_deviation_mean_deg"]
req(dd <= 8, "30°, 5:1: mean metric angle deviation %.2f° (> 8°)" % dd)
req(df > dd + 1, "30°, 5:1: --walls fixed not worse by 1° than sliding walls (%.2f° vs %.2f°): the test lost its point" % (df, dd))
print("ok: 30°/5:1 mean metric angle deviation %.2f° (fixed walls: %.2f°)" % (dd, df))
f, g = J("a45s5"), J("a45s5-nobonus")
req(f["irregular_interior_share"] <= 0.03, "45°, 5:1: %.1f %% irregular (> 3 %%)" % (100 * f["irregular_interior_share"]))
req(g["irregular_interior_share"] > f["irregular_interior_share"],
    "45°, 5:1: --interior-bonus 0 no worse than the default (%.3f vs %.3f): the test lost its point"
    % (g["irregular_interior_share"], f["irregular_interior_share"]))
m = c["metric"]
req(m["quad_angle_share_80_100"] >= 0.6, "band: metric corners in 90+-10: %.2f < 0.6" % m["quad_angle_share_80_100"])
req(m["edge_length"]["share_in_range"] >= 0.8, "band: edges in range %.2f < 0.8" % m["edge_length"]["share_in_range"])
N = c["frame"]["continuous_complexity"]
req(abs(c["cells"] / N - 1) <= 0.05, "band: %d cells for %.0f" % (c["cells"], N))
req(c["physical"]["scaled_jacobian_min"] > 0, "band: invalid quad")
print("ok: 45°/5:1 irregular %.1f %% (no interior bonus: %.1f %%)" % (100 * f["irregular_interior_share"], 100 * g["irregular_interior_share"]))
print("ok: 30°/5:1 irregular %.1f %% (Euclidean wall spacing: %.1f %%)" % (100 * d["irregular_interior_share"], 100 * e["irregular_interior_share"]))
print("ok: isotropic 30° irregular %.1f %% (frame's angle: %.1f %%); band corners %.2f, edges %.2f, %d cells for %.0f"
      % (100 * a["irregular_interior_share"], 100 * b["irregular_interior_share"], m["quad_angle_share_80_100"],
         m["edge_length"]["share_in_range"], c["cells"], N))
PY
