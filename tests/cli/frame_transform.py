#!/usr/bin/env python3
"""Exact turns and mirrors of a frame file (the eight symmetries of the square).

    frame_transform.py IN OUT SYMMETRY [reverse]      SYMMETRY in id r1 r2 r3 m0 m1 m2 m3

rK = a turn by K x 90 degrees about the origin, mK = the mirror x -> -x followed by rK. Each maps
x -> Q x with Q's entries in {0, 1, -1}, so the coordinates are only swapped and negated: no
rounding. The frame turns with the problem, M' = M Q^T (the same swaps and signs), so the
Riemannian metric is M'^T M' = Q M^T M Q^T. A mirror reverses each cell's vertex list (the cells
stay counter-clockwise). The output is MSH 2.2 with the background's cells, the cell view
"Vinv" when it has one (values written with repr: exact) and its $FrameConvention section
(docs/file-formats.md; PHiLiP's files have none and stay PHiLiP's); the boundary is left to the
reader, which completes it from the free edges. Used by
tests/cli/graded_equivariance.sh, bench/quad/dihedral.py and bench/quad/lpcvt_equivariance.py.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from golden_compare import read_msh  # noqa: E402

SYMMETRIES = ("id", "r1", "r2", "r3", "m0", "m1", "m2", "m3")


def matrix(sym):
    """Q (2 x 2 nested lists of ints) of a symmetry name"""
    if sym not in SYMMETRIES:
        raise ValueError(f"unknown symmetry {sym!r} (one of {', '.join(SYMMETRIES)})")
    q = [[-1, 0], [0, 1]] if sym[0] == "m" else [[1, 0], [0, 1]]
    for _ in range(0 if sym == "id" else int(sym[1])):
        q = [[-q[1][0], -q[1][1]], [q[0][0], q[0][1]]]  # [[0, -1], [1, 0]] @ q
    return q


def apply(q, x, y):
    """Q (x, y): exact, Q's entries being 0 and +-1"""
    def dot(row):
        terms = [c * v for c, v in zip(row, (x, y)) if c != 0]
        return terms[0] + 0.0 if terms else 0.0  # + 0.0: no negative zeros
    return dot(q[0]), dot(q[1])


def transform(path, out, sym, order="keep"):
    """order "reverse": the nodes written in reversed order (renumbered: node k of IN is node
    n - 1 - k of OUT), the same mesh otherwise"""
    if order not in ("keep", "reverse"):
        raise ValueError(f"unknown node order {order!r} (keep or reverse)")
    q = matrix(sym)
    m = read_msh(path)
    cells = [(t, c) for t in (2, 3) for c in m["elements"].get(t, [])]
    view = m["views"].get("Vinv")  # a mesh without a frame (a quad mesh) is turned too
    if view is not None and len(view["values"]) != len(cells):
        raise ValueError(f"{path}: expected one Vinv value per triangle or quad")
    det = q[0][0] * q[1][1] - q[0][1] * q[1][0]
    with open(out, "w") as f:
        n = len(m["nodes"])
        new_id = (lambda k: n - k) if order == "reverse" else (lambda k: k + 1)
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % n)
        for k in (range(n - 1, -1, -1) if order == "reverse" else range(n)):
            x, y = apply(q, m["nodes"][k][0], m["nodes"][k][1])
            f.write(f"{new_id(k)} {x!r} {y!r} 0\n")
        f.write("$EndNodes\n$Elements\n%d\n" % len(cells))
        index = {2: 0, 3: 0}
        keys = []
        for e, (t, c) in enumerate(cells):
            keys.append((t, index[t]))
            index[t] += 1
            c = c[::-1] if det < 0 else c
            f.write(f"{e + 1} {t} 2 0 1 " + " ".join(str(new_id(v)) for v in c) + "\n")
        f.write("$EndElements\n")
        if view is None:
            return
        f.write('$ElementData\n1\n"Vinv"\n1\n0.0\n3\n0\n9\n%d\n' % len(cells))
        for e, key in enumerate(keys):
            a = view["values"][key]
            # M' = M Q^T: row r of M' is (Q M_r)^T, M_r the row r of M
            rows = [apply(q, a[0], a[1]), apply(q, a[3], a[4])]
            f.write(f"{e + 1} {rows[0][0]!r} {rows[0][1]!r} 0 {rows[1][0]!r} {rows[1][1]!r} 0 0 0 1\n")
        f.write("$EndElementData\n")
        text = open(path, encoding="utf-8", errors="replace").read()
        a, b = text.find("$FrameConvention\n"), text.find("$EndFrameConvention")
        if a >= 0 and b > a:
            f.write(text[a:b] + "$EndFrameConvention\n")


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    transform(*sys.argv[1:5])
