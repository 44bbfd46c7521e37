#!/usr/bin/env bash
# meshconvert: our MSH 4.1 is a fixed point; Gmsh-written MSH 2.2 ASCII, 4.1 binary and 2.2 binary
# of the unit square convert to exactly the committed examples/meshes/square16.msh.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
compare="python3 $S/tests/cli/golden_compare.py"

meshconvert -q "$S/tests/golden/io/square2_fields.msh" -o "$T/a.msh"
cmp "$T/a.msh" "$S/tests/golden/io/square2_fields.msh"
test -s "$T/a.json"  # the report beside the output
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert r['fields']==['h','Vinv','u'] and r['cells']==4, r" "$T/a.json"

for fmt in "msh22" "msh41 -bin" "msh22 -bin"; do
  gmsh -2 -v 0 "$S/examples/geometry/unit_square.geo" -format $fmt -o "$T/g.msh"
  meshconvert -q "$T/g.msh" -o "$T/c.msh" --require quads
  $compare "$T/c.msh" "$S/examples/meshes/square16.msh" --rtol 0 --atol 0
  rm -f "$T/c.msh" "$T/c.json"
done

# PHiLiP's frame file (no $Entities, no boundary lines): the boundary appears, named.
meshconvert -q "$QUADAPT_FIXTURES_DIR/input_ss15_fb_p1_3.msh" -o "$T/p.msh" --require quads
grep -q '^1 1 "bottom"$' "$T/p.msh"
grep -q '^1 4 "left"$' "$T/p.msh"
grep -q '"Vinv"' "$T/p.msh"
echo "io_meshconvert: ok"
