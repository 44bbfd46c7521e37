#!/usr/bin/python3
"""Reads a .vtu with VTK's own reader (python3-vtk9) and checks it against the .msh it came from.

usage: vtu_check.py FILE.vtu FILE.msh [--exact EXPR --tol T]
 - every $ElementData view of the .msh is a CellData array of the .vtu with the same name,
   component count and values (bit-exact: both files print 17 significant digits);
 - the cells are the .msh's quads, in order, with the same area (VTK's own cell measure);
 - with --exact: the DG point data `u`, interpolated by VTK's Lagrange quadrilateral at 25
   parametric points per cell (EvaluateLocation gives the physical point and the weights),
   equals EXPR(x, y) within T (absolute). A wrong VTK node order fails this at once.
Prints the largest differences found."""
import argparse, math, os, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from golden_compare import read_msh  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402



def worst_of(worst, e):
    """Running maximum that keeps NaN: max(worst, nan) is worst in Python, so a file full of NaN
    would pass the tolerance checks."""
    return math.nan if math.isnan(worst) or math.isnan(e) else max(worst, e)

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("vtu")
    ap.add_argument("msh")
    ap.add_argument("--exact")
    ap.add_argument("--tol", type=float, default=1e-9)
    a = ap.parse_args()
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(a.vtu)
    r.Update()
    g = r.GetOutput()
    m = read_msh(a.msh)
    quads = m["elements"].get(3, [])
    assert g.GetNumberOfCells() == len(quads) and len(quads) > 0, (g.GetNumberOfCells(), len(quads))
    cd = g.GetCellData()
    for name, view in m["views"].items():
        if view["kind"] != "ElementData":
            continue
        arr = cd.GetArray(name)
        assert arr is not None, f"CellData '{name}' missing"
        assert arr.GetNumberOfComponents() == view["ncomp"], (name, arr.GetNumberOfComponents())
        got = vtk_to_numpy(arr).reshape(len(quads), view["ncomp"])
        for c in range(len(quads)):
            assert list(got[c]) == view["values"][(3, c)], (name, c, list(got[c]), view["values"][(3, c)])
        print(f"vtu_check: CellData {name} ({view['ncomp']} components) equal to the .msh, {len(quads)} cells")
    if any(v["ncomp"] == 9 for v in m["views"].values()):
        assert cd.GetTensors() is not None and cd.GetTensors().GetNumberOfComponents() == 9, "no active tensor"
        print(f"vtu_check: active tensor {cd.GetTensors().GetName()}")
    # geometry: areas of VTK's cells = the quads' shoelace areas
    nodes = m["nodes"]
    worst_area = 0.0
    for c, q in enumerate(quads):
        p = [nodes[k] for k in q]
        area = 0.5 * sum(p[i][0] * p[(i + 1) % 4][1] - p[(i + 1) % 4][0] * p[i][1] for i in range(4))
        cell = g.GetCell(c)
        bounds_ok = all(abs(cell.GetPoints().GetPoint(i)[0] - p[i][0]) < 1e-14 and
                        abs(cell.GetPoints().GetPoint(i)[1] - p[i][1]) < 1e-14 for i in range(4))
        assert bounds_ok, f"cell {c}: VTK corners are not the quad's vertices v0..v3"
        if cell.GetCellType() == 70:
            # area by VTK's own interpolation: Gauss rule on the parametric square [0,1]^2
            s = 0.0
            gp = [0.5 - 0.5 / math.sqrt(3), 0.5 + 0.5 / math.sqrt(3)]
            for u in gp:
                for v in gp:
                    der = [0.0] * (2 * cell.GetNumberOfPoints())
                    cell.InterpolateDerivs([u, v, 0], der)
                    n = cell.GetNumberOfPoints()
                    # VTK 9's Lagrange quad interleaves them: derivs[2 i + d] = d phi_i / d r_d
                    assert abs(sum(der[0::2])) < 1e-12 and abs(sum(der[1::2])) < 1e-12
                    J = [[0, 0], [0, 0]]
                    for i in range(n):
                        x = cell.GetPoints().GetPoint(i)
                        for d in range(2):
                            J[0][d] += der[2 * i + d] * x[0]
                            J[1][d] += der[2 * i + d] * x[1]
                    s += 0.25 * (J[0][0] * J[1][1] - J[0][1] * J[1][0])
            worst_area = worst_of(worst_area, abs(s - area))
    print(f"vtu_check: corners = quad vertices; area by VTK's interpolation - shoelace: max {worst_area:.3e}")
    assert worst_area < 1e-12
    if a.exact:
        pd = g.GetPointData().GetArray("u")
        assert pd is not None, "PointData u missing"
        f = eval("lambda x, y: " + a.exact, {"math": math})
        worst = 0.0
        for c in range(g.GetNumberOfCells()):
            cell = g.GetCell(c)
            assert cell.GetCellType() == 70, cell.GetCellType()
            ids = [cell.GetPointId(i) for i in range(cell.GetNumberOfPoints())]
            for s in (0.05, 0.3, 0.5, 0.7, 0.95):
                for t in (0.1, 0.25, 0.5, 0.8, 0.9):
                    x = [0.0, 0.0, 0.0]
                    w = [0.0] * len(ids)
                    cell.EvaluateLocation(vtk.mutable(0), [s, t, 0.0], x, w)
                    u = sum(wi * pd.GetValue(i) for wi, i in zip(w, ids))
                    worst = worst_of(worst, abs(u - f(x[0], x[1])))
        print(f"vtu_check: u by VTK's Lagrange interpolation - exact: max {worst:.3e} (tolerance {a.tol:.1e})")
        assert worst <= a.tol, worst


if __name__ == "__main__":
    main()
