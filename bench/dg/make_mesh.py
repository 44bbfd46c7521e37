#!/usr/bin/env python3
"""Unit-square all-quad meshes for the dgsolve benchmark (MSH 4.1 ASCII, boundary groups
bottom/right/top/left). Python 3 standard library only.

usage: make_mesh.py NX NY OUT.msh [--stretch S]

Without --stretch: the uniform NX x NY grid. With --stretch S: the NY rows stay uniform
(height 1/NY) while the NX columns are graded geometrically, symmetric about x = 1/2, from width
1/(S NY) at x = 1/2 outwards, so the cells at x = 1/2 are S times taller than wide (an adapted
anisotropic mesh of the kind that makes iterative solvers struggle).
"""
import sys


def graded_columns(nx, ny, stretch):
    """Column boundaries in [0, 1]: widths w0 r^k from x = 1/2 outwards, w0 = 1/(stretch ny)."""
    half = nx // 2
    w0 = 1.0 / (stretch * ny)
    if w0 * half >= 0.5:
        raise SystemExit("--stretch too small for this grid")
    lo, hi = 1.0, 2.0
    total = lambda r: sum(w0 * r ** k for k in range(half))
    while total(hi) < 0.5:
        hi *= 2
    for _ in range(200):  # bisection on the ratio r so that half the columns fill [1/2, 1]
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if total(mid) < 0.5 else (lo, mid)
    r = 0.5 * (lo + hi)
    right = [0.5]
    for k in range(half):
        right.append(right[-1] + w0 * r ** k)
    right[-1] = 1.0
    left = [1.0 - x for x in reversed(right[1:])]
    xs = left + right
    if nx % 2:
        raise SystemExit("--stretch needs an even NX")
    return xs


def main():
    args = sys.argv[1:]
    stretch = None
    if "--stretch" in args:
        k = args.index("--stretch")
        stretch = float(args[k + 1])
        del args[k:k + 2]
    nx, ny, out = int(args[0]), int(args[1]), args[2]
    xs = graded_columns(nx, ny, stretch) if stretch else [i / nx for i in range(nx + 1)]
    ys = [j / ny for j in range(ny + 1)]
    nid = lambda i, j: j * (nx + 1) + i + 1
    nodes = [(nid(i, j), xs[i], ys[j]) for j in range(ny + 1) for i in range(nx + 1)]
    cells = [(nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)) for j in range(ny) for i in range(nx)]
    sides = [[(nid(i, 0), nid(i + 1, 0)) for i in range(nx)],
             [(nid(nx, j), nid(nx, j + 1)) for j in range(ny)],
             [(nid(i, ny), nid(i - 1, ny)) for i in range(nx, 0, -1)],
             [(nid(0, j), nid(0, j - 1)) for j in range(ny, 0, -1)]]
    names = ["bottom", "right", "top", "left"]
    L = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", "5"]
    L += ['1 %d "%s"' % (k + 1, names[k]) for k in range(4)] + ['2 5 "domain"', "$EndPhysicalNames"]
    L += ["$Entities", "0 4 1 0"]
    L += ["%d 0 0 0 1 1 0 1 %d 0" % (k + 1, k + 1) for k in range(4)]
    L += ["1 0 0 0 1 1 0 1 5 4 1 2 3 4", "$EndEntities"]
    L += ["$Nodes", "1 %d 1 %d" % (len(nodes), len(nodes)), "2 1 0 %d" % len(nodes)]
    L += [str(t) for t, _, _ in nodes] + ["%.17g %.17g 0" % (x, y) for _, x, y in nodes] + ["$EndNodes"]
    nb = sum(len(s) for s in sides)
    L += ["$Elements", "5 %d 1 %d" % (nb + len(cells), nb + len(cells))]
    tag = 1
    for k in range(4):
        L.append("1 %d 1 %d" % (k + 1, len(sides[k])))
        for a, b in sides[k]:
            L.append("%d %d %d" % (tag, a, b))
            tag += 1
    L.append("2 1 3 %d" % len(cells))
    for c in cells:
        L.append(" ".join(map(str, (tag,) + c)))
        tag += 1
    L.append("$EndElements")
    with open(out, "w") as f:
        f.write("\n".join(L) + "\n")


if __name__ == "__main__":
    main()
