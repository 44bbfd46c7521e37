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

# --jitter J --seed S: another start mesh; the same bytes for the same seed (and any output name),
# others for another seed; the boundary nodes stay; a bad fraction writes nothing.
meshconvert -q "$S/examples/meshes/square16.msh" --jitter 0.2 --seed 2 -o "$T/j1.msh"
meshconvert -q "$S/examples/meshes/square16.msh" --jitter 0.2 --seed 2 -o "$T/other-name.msh"
cmp "$T/j1.msh" "$T/other-name.msh"
meshconvert -q "$S/examples/meshes/square16.msh" --jitter 0.2 --seed 3 -o "$T/j3.msh"
! cmp -s "$T/j1.msh" "$T/j3.msh" || { echo "seed 3 gave seed 2's mesh"; exit 1; }
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert r['jittered_nodes']==225 and r['options']['seed']==2, r" "$T/j1.json"
python3 - "$S/examples/meshes/square16.msh" "$T/j1.msh" <<'PY'
import sys
def nodes(f):
    L = open(f).read().split("\n"); i = L.index("$Nodes"); n = int(L[i + 1].split()[1])
    return [tuple(map(float, l.split()[:2])) for l in L[i + 2:] if len(l.split()) == 3][:n]
a, b = nodes(sys.argv[1]), nodes(sys.argv[2])
assert len(a) == len(b) == 289, (len(a), len(b))
moved = [i for i in range(289) if a[i] != b[i]]
assert len(moved) == 225, len(moved)
assert all(0 < x < 1 and 0 < y < 1 for x, y in (a[i] for i in moved)), "a boundary node moved"
assert max(max(abs(a[i][0] - b[i][0]), abs(a[i][1] - b[i][1])) for i in moved) <= 0.2 / 16 + 1e-15
PY
rc=0; meshconvert -q "$S/examples/meshes/square16.msh" --jitter 0.5 -o "$T/bad.msh" 2> "$T/err" || rc=$?
[ $rc -eq 2 ] && [ ! -e "$T/bad.msh" ] && grep -q "jitter" "$T/err" || { echo "bad --jitter: rc $rc, $(cat "$T/err")"; exit 1; }
echo "io_meshconvert: ok"
