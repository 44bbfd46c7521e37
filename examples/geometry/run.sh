#!/usr/bin/env bash
# Meshes every example geometry with gmsh, converts and validates it with meshconvert (all
# quads), checks its quality and boundary names with meshquality, and checks that the unit
# square reproduces the committed examples/meshes/square16.msh exactly.
set -euo pipefail
S=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
G=$S/examples/geometry
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

gmsh -2 -v 0 "$G/unit_square.geo" -o "$T/gmsh16.msh"
meshconvert -q "$T/gmsh16.msh" -o "$T/square16.msh" --require quads
cmp "$T/square16.msh" "$S/examples/meshes/square16.msh"
gmsh -2 -v 0 -setnumber N 5 "$G/unit_square.geo" -o "$T/gmsh5.msh"
meshquality "$T/gmsh5.msh" --require quads | python3 -c "
import json, sys; r = json.load(sys.stdin); assert r['cells'] == 25 and r['physical']['scaled_jacobian_min'] == 1.0, r"

check() {  # check GEO AREA NAMES...
  local geo=$1 area=$2
  shift 2
  gmsh -2 -v 0 "$G/$geo.geo" -o "$T/$geo.gmsh.msh"
  meshconvert -q "$T/$geo.gmsh.msh" -o "$T/$geo.msh" --require quads
  meshquality "$T/$geo.msh" > "$T/$geo.json"
  python3 - "$T/$geo.json" "$area" "$@" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
area, names = float(sys.argv[2]), sys.argv[3:]
assert r["triangles"] == 0 and r["quads"] > 100, r
assert abs(r["area"] - area) < 5e-3, r["area"]
assert r["physical"]["scaled_jacobian_min"] > 0.5 and r["physical"]["angle_min_deg"] > 30, r["physical"]
assert [b["name"] for b in r["boundary"]] == names, r["boundary"]
print(f"{sys.argv[1]}: {r['quads']} quads, min angle {r['physical']['angle_min_deg']:.1f}, "
      f"min scaled Jacobian {r['physical']['scaled_jacobian_min']:.3f}")
PY
}
check unstructured_square 1 bottom right top left
check l_shape 0.75 bottom right inner_horizontal inner_vertical top left
check square_with_hole 0.8743 bottom right top left hole
echo "examples/geometry: ok"
