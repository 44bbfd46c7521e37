#!/usr/bin/env bash
# lpcvt -> recombine -> quadsmooth on the thesis's analytic saddle metric (eq. 6.1, §6.1), exact
# and sampled on a 16x16 background: all-quad, nothing inverted, area and boundary names kept,
# smoothing never lowers the minimum angle.
set -euo pipefail
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
for t in lpcvt recombine quadsmooth; do command -v $t >/dev/null || { echo "FAIL: $t not built (tools must be on PATH)" >&2; exit 1; }; done
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

for mode in exact sampled; do
  extra=""; [ $mode = sampled ] && extra="--sampled"
  lpcvt -q --analytic saddle $extra -o "$T/$mode.msh"
  recombine -q "$T/$mode.msh" -o "$T/${mode}_q.msh"
  quadsmooth -q "$T/${mode}_q.msh" -o "$T/${mode}_qs.msh"
  python3 - "$T/${mode}_q.json" "$T/${mode}_qs.json" "$T/${mode}_q.msh" "$T/${mode}.msh" $mode <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); s = json.load(open(sys.argv[2])); mode = sys.argv[5]
def req(c, m):
    if not c: sys.exit("FAIL (%s): %s" % (mode, m))
q = r["quality"]
req(q["triangles"] == 0 and q["quads"] == r["cells"], "not all-quad")
req(q["inverted"] == 0 and q["min_scaled_jacobian"] > 0, "inverted cells after recombine")
req(abs(q["area"] - 2.6 * 2.6) < 1e-9, "area %g" % q["area"])
a = s["quality"]; b = s["quality_before"]
req(a["inverted"] == 0 and a["min_scaled_jacobian"] > 0, "inverted cells after quadsmooth")
req(a["min_angle_deg"] >= b["min_angle_deg"], "quadsmooth lowered the min angle")
def groups(f):
    t = open(f).read(); i = t.index("$PhysicalNames"); n = int(t[i:].split("\n")[1])
    return sorted(l.split()[-1] for l in t[i:].split("\n")[2:2 + n] if l.split()[0] == "1")
req(groups(sys.argv[3]) == groups(sys.argv[4]) and groups(sys.argv[3]), "boundary groups %s -> %s" % (groups(sys.argv[4]), groups(sys.argv[3])))
print("ok (%s): %d triangles -> %d quads + %d triangles -> %d cells; min SJ %.3f -> %.3f after smoothing, min angle %.1f -> %.1f" % (
    mode, r["triangles_in"], r["after_blossom"]["quads"], r["after_blossom"]["triangles"], r["cells"],
    q["min_scaled_jacobian"], a["min_scaled_jacobian"], b["min_angle_deg"], a["min_angle_deg"]))
PY
done
echo "recombine_lpcvt: all checks passed"
