#!/usr/bin/env bash
# meshconvert X.msh -o X.vtu (docs/file-formats.md §5), read back by VTK's own reader
# (python3-vtk9, tests/cli/vtu_check.py):
#  - the DG solution u of a degree-3 polynomial case (dgsolve reproduces it to rounding) on an
#    unstructured quad mesh, interpolated by VTK's Lagrange quadrilaterals at 25 points per cell,
#    equals the polynomial within 1e-9 (measured 5.7e-13; a wrong VTK node order gives O(1));
#  - every cell field (dwr from adjoint; Vinv, h, theta, rho of a frame) bit-exact as CellData,
#    Vinv as the active 9-component tensor; VTK's cell geometry = the quads (area to 1e-12).
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
PY=/usr/bin/python3
$PY -c "import vtk" 2>/dev/null || { echo "FAIL: python3-vtk9 missing (scripts/install-deps.sh installs it)" >&2; exit 1; }
cat > "$T/poly.json" <<'JSON'
{"diffusion": [[0.1, 0.02], [0.02, 0.05]], "advection": [1, 0.5], "exact": "x^3 - 2*x*y^2 + y + 0.5",
 "functional": {"boundary": "right"}}
JSON
dgsolve -q "$S/examples/meshes/unstructured_square.msh" -c "$T/poly.json" -p 3 -o "$T/sol.msh"
adjoint -q "$T/sol.msh" -c "$T/poly.json" -o "$T/dwr.msh"
meshconvert -q "$T/dwr.msh" -o "$T/dwr.vtu"
$PY "$S/tests/cli/vtu_check.py" "$T/dwr.vtu" "$T/dwr.msh" --exact "x**3 - 2*x*y**2 + y + 0.5" --tol 1e-9
F="$S/tests/golden/frame/sshock16_p2_frame.msh"
meshconvert -q "$F" -o "$T/frame.vtu"
$PY "$S/tests/cli/vtu_check.py" "$T/frame.vtu" "$F"
# p = 1 (VTK_QUAD with its own points) and p = 2 also round-trip
for p in 1 2; do
  cat > "$T/lin.json" <<JSON
{"diffusion": [[0.1, 0], [0, 0.1]], "advection": [1, 0.5], "exact": "$([ $p = 1 ] && echo '2*x - y + 0.25' || echo 'x*y - y^2 + 0.25')"}
JSON
  dgsolve -q "$S/examples/meshes/unstructured_square.msh" -c "$T/lin.json" -p $p -o "$T/s$p.msh"
  meshconvert -q "$T/s$p.msh" -o "$T/s$p.vtu"
done
$PY "$S/tests/cli/vtu_check.py" "$T/s2.vtu" "$T/s2.msh" --exact "x*y - y**2 + 0.25" --tol 1e-9
$PY - "$T/s1.vtu" <<'PY'
import sys, vtk
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update(); g = r.GetOutput()
assert g.GetCell(0).GetCellType() == 9 and g.GetNumberOfPoints() == 4 * g.GetNumberOfCells()
u = g.GetPointData().GetArray("u")
worst = max(abs(u.GetValue(i) - (2 * g.GetPoint(i)[0] - g.GetPoint(i)[1] + 0.25)) for i in range(g.GetNumberOfPoints()))
assert worst < 1e-9, worst
print("p=1: VTK_QUAD, u at the vertices - exact: max %.3e" % worst)
PY
# the output is deterministic and written atomically; a .msh output is still MSH
meshconvert -q "$T/dwr.msh" -o "$T/dwr2.vtu"
cmp "$T/dwr.vtu" "$T/dwr2.vtu"
meshconvert -q "$T/dwr.msh" -o "$T/back.msh"
head -1 "$T/back.msh" | grep -q MeshFormat
echo "meshconvert_vtu: ok"
