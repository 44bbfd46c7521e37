#!/usr/bin/env bash
# lpcvt on real frames written by the thesis's solver (PHiLiP fixtures, read as they are): with
# the step-3 complexity of the fixtures' README (--complexity, --degree: PHiLiP normalises its
# frames and passes the target separately), lpcvt + recombine give an all-quad mesh whose DOF
# count (cells (p+1)^2) is within 10% of the target. Two fixtures (S-shock p = 1, boundary
# layer p = 2) to keep it fast; docs/bench-lpcvt.md has all eight.
set -euo pipefail
D=$QUADAPT_FIXTURES_DIR
[ -f "$D/input_ss15_fb_p1_3.msh" ] || { echo "FAIL: PHiLiP fixture $D/input_ss15_fb_p1_3.msh missing" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
for spec in ss15_fb_p1:1:3456 bl15_fb_p2:2:7776; do
  IFS=: read -r name p C <<< "$spec"
  lpcvt "$D/input_${name}_3.msh" --complexity "$C" --degree "$p" -o "$T/$name-tri.msh" -q
  recombine "$T/$name-tri.msh" -o "$T/$name-quad.msh" -q
  /usr/bin/python3 - "$T/$name-tri.json" "$T/$name-quad.json" "$p" "$C" <<'PY'
import json, sys
r, q = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
p, C = int(sys.argv[3]), float(sys.argv[4])
assert abs(r["target_cells"] - C / (p + 1) ** 2) < 1e-6 * C, r["target_cells"]
assert r["points"] == round(r["requested_points"]), (r["points"], r["requested_points"])
dofs = q["cells"] * (p + 1) ** 2
print(f"{sys.argv[1]}: {r['points']} points, {q['cells']} quads, {dofs} DOFs for {C:.0f} ({dofs / C:.3f})")
assert abs(dofs / C - 1) <= 0.10, (dofs, C)
PY
done
echo "lpcvt_fixtures: ok"
