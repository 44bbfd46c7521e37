#!/usr/bin/env bash
# meshquality on meshes whose answers are known by hand: the 16x16 square grid (all angles 90,
# scaled Jacobian 1; also against a stored golden report), two 60/120-degree rhombi, and the
# square grid measured in a constant frame M = diag(8, 2).
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

meshquality "$S/examples/meshes/square16.msh" > "$T/sq.json"
python3 - "$T/sq.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
p = r["physical"]
assert r["cells"] == 256 and r["quads"] == 256 and r["triangles"] == 0, r
assert abs(r["area"] - 1) < 1e-14
assert p["angle_min_deg"] == p["angle_max_deg"] == 90.0 or abs(p["angle_min_deg"] - 90) < 1e-12
assert abs(p["angle_max_deg"] - 90) < 1e-12 and p["quad_angle_share_80_100"] == 1.0
assert abs(p["scaled_jacobian_min"] - 1) < 1e-15 and abs(p["scaled_jacobian_mean"] - 1) < 1e-15
assert [(b["name"], b["edges"]) for b in r["boundary"]] == [("bottom", 16), ("right", 16), ("top", 16), ("left", 16)]
assert r["tool"] == "meshquality" and "timings" in r and "metric" not in r
PY
python3 "$S/tests/cli/golden_compare.py" "$T/sq.json" "$S/tests/golden/io/meshquality_square16.json" --ignore mesh

s=0.86602540378443864676
cat > "$T/rhombi.msh" <<MSH
\$MeshFormat
2.2 0 8
\$EndMeshFormat
\$Nodes
6
1 0 0 0
2 1 0 0
3 2 0 0
4 0.5 $s 0
5 1.5 $s 0
6 2.5 $s 0
\$EndNodes
\$Elements
2
1 3 2 1 1 1 2 5 4
2 3 2 1 1 2 3 6 5
\$EndElements
MSH
meshquality "$T/rhombi.msh" --require quads > "$T/rh.json"
python3 - "$T/rh.json" <<'PY'
import json, math, sys
r = json.load(open(sys.argv[1]))
p = r["physical"]
near = lambda a, b: abs(a - b) < 1e-9
assert near(p["angle_min_deg"], 60) and near(p["angle_max_deg"], 120) and near(p["angle_mean_deg"], 90), p
assert p["quad_angle_share_80_100"] == 0
assert near(p["scaled_jacobian_min"], math.sqrt(3) / 2) and near(p["scaled_jacobian_mean"], math.sqrt(3) / 2)
assert near(r["area"], math.sqrt(3))
assert [b["name"] for b in r["boundary"]] == ["boundary_1", "boundary_2", "boundary_3", "boundary_4"], r["boundary"]
PY

cat > "$T/frame.msh" <<'MSH'
$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
1
1 3 2 1 1 1 2 3 4
$EndElements
$ElementData
1
"Vinv"
0
3
0
9
1
1 8 0 0 0 2 0 0 0 0
$EndElementData
$FrameConvention
quadapt
$EndFrameConvention
MSH
meshquality "$S/examples/meshes/square16.msh" --frame "$T/frame.msh" > "$T/fr.json"
python3 - "$T/fr.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
m, f, e = r["metric"], r["frame"], r["metric"]["edge_length"]
near = lambda a, b: abs(a - b) < 1e-12
# h1 = 1/8 along x, h2 = 1/2 along y: target element 1/4 x 1, N = 1 * det(M) / 4 = 4.
assert near(f["continuous_complexity"], 4) and f["actual_cells"] == 256 and near(f["cells_over_continuous"], 64)
assert near(f["stretch_median"], 4) and near(f["orientation_median_deg"], 90), f
# metric edge lengths |M e|/2: x-edges 1/16 * 8 / 2 = 1/4, y-edges 1/16 * 2 / 2 = 1/16
assert e["edges"] == 1024 and near(e["min"], 1 / 16) and near(e["max"], 1 / 4) and e["share_in_range"] == 0
assert near(m["angle_min_deg"], 90) and near(m["angle_max_deg"], 90) and near(m["edge_ratio_median"], 4)
assert f["cells_outside"] == 0
PY
echo "meshquality_known: ok"
