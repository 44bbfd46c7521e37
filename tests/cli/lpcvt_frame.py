#!/usr/bin/python3
"""Writes a test frame file like PHiLiP's (MSH 4.1 ASCII, no $Entities, no boundary lines) but in
quadapt's size convention ($FrameConvention quadapt; --philip: without it, as PHiLiP's files):
an n x n quad grid on [x0,x1]x[y0,y1] (optionally with the top-right quarter removed: an
L-shape) and per cell $ElementData "Vinv" = V^-1, V = R(theta) diag(h1, h2), 9 components.

  lpcvt_frame.py OUT.msh --n 8 --h1 0.05 --h2 0.05 --theta 0 [--box x0 x1 y0 y1] [--lshape]
  --kind symmetric: M = R diag(1/h1, 1/h2) R^T (symmetric, same M^T M).
  --kind saddle: M = eq. 6.1 sampled at cell centres (times --factor).
  --kind band: a curved boundary layer: half-axes h1 along the circles |x| = r and h1 / s(d)
    across, s(d) = 1 + (--stretch - 1) exp(-(d / --band-width)^2), d = |x| - --band-radius
    (circles about the origin: on the unit square a quarter-circle band meeting two walls at right
    angles; isotropic h1 far from it).
  --finer-cell K: the metric of the cell with element tag K finer by 1e-6 (relative), so that
  lpcvt's lattice start grows from that cell (the finest first; ties: the smallest coordinates along
  the frame's axes) —
  the lattice's phase against the walls (docs/quad-quality.md, "The lattice's phase").
  --shuffle SEED: the same frame with its nodes and cells listed in a random order (seeded) and
  each quad's vertex list starting at a random corner (counter-clockwise kept): tools that read
  frames must give the same outputs (mesh/canonical.hpp). --finer-cell and --corrupt-cell name
  cells by their unshuffled tags.
  --corrupt nan|singular|stretched|huge|none: damage one cell's frame (bad-input tests): the cell with element
  tag --corrupt-cell K (default 1; tags are 1..cells in file order, rows from the bottom).
"""
import argparse
import math


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--n", type=int, default=8)
    ap.add_argument("--h1", type=float, default=0.05)
    ap.add_argument("--h2", type=float, default=0.05)
    ap.add_argument("--theta", type=float, default=0.0)
    ap.add_argument("--box", type=float, nargs=4, default=[0, 1, 0, 1])
    ap.add_argument("--lshape", action="store_true")
    ap.add_argument("--kind", choices=["constant", "symmetric", "saddle", "band"], default="constant")
    ap.add_argument("--factor", type=float, default=1.0)
    ap.add_argument("--stretch", type=float, default=10.0)
    ap.add_argument("--band-radius", type=float, default=0.6)
    ap.add_argument("--band-width", type=float, default=0.06)
    ap.add_argument("--philip", action="store_true", help="no $FrameConvention section (read as PHiLiP's sizes)")
    ap.add_argument("--corrupt", choices=["none", "nan", "singular", "stretched", "huge", "nofield"], default="none")
    ap.add_argument("--corrupt-cell", type=int, default=1)
    ap.add_argument("--shuffle", type=int, default=0, help="list nodes and cells in a random order (this seed)")
    ap.add_argument("--finer-cell", type=int, default=0, help="make this cell's metric finer by 1e-6 (the lattice seed)")
    a = ap.parse_args()
    n = a.n
    x0, x1, y0, y1 = a.box
    nodes = [(x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n) for j in range(n + 1) for i in range(n + 1)]
    cells = []
    for j in range(n):
        for i in range(n):
            if a.lshape and i >= n // 2 and j >= n // 2:
                continue
            k = j * (n + 1) + i
            cells.append((k, k + 1, k + n + 2, k + n + 1))
    c, s = math.cos(a.theta), math.sin(a.theta)
    frames = []
    for q in cells:
        if a.kind == "constant":
            # V^-1 = diag(1/h1, 1/h2) R(-theta)
            m = [c / a.h1, s / a.h1, -s / a.h2, c / a.h2]
        elif a.kind == "symmetric":
            # R diag(1/h1, 1/h2) R^T: same Riemannian metric, symmetric (like eq. 6.1)
            p1, p2 = 1 / a.h1, 1 / a.h2
            m = [c * c * p1 + s * s * p2, c * s * (p1 - p2), c * s * (p1 - p2), s * s * p1 + c * c * p2]
        elif a.kind == "band":
            x = sum(nodes[v][0] for v in q) / 4
            y = sum(nodes[v][1] for v in q) / 4
            d = math.hypot(x, y) - a.band_radius
            h2 = a.h1 / (1 + (a.stretch - 1) * math.exp(-(d / a.band_width) ** 2))
            t = math.atan2(y, x) + math.pi / 2
            ct, st = math.cos(t), math.sin(t)
            m = [ct / a.h1, st / a.h1, -st / h2, ct / h2]
        else:
            x = sum(nodes[v][0] for v in q) / 4
            y = sum(nodes[v][1] for v in q) / 4
            m = [1 + 4 * x * x, -4 * x * y, -4 * x * y, 1 + 4 * y * y]
            m = [a.factor * t for t in m]
        frames.append(m)
    if a.finer_cell:
        if not 1 <= a.finer_cell <= len(frames):
            raise SystemExit(f"lpcvt_frame.py: --finer-cell {a.finer_cell}: the frame has cells 1..{len(frames)}")
        frames[a.finer_cell - 1] = [t * (1 + 1e-6) for t in frames[a.finer_cell - 1]]
    if a.corrupt == "nan":
        frames[a.corrupt_cell - 1] = [float("nan")] * 4
    elif a.corrupt == "singular":
        frames[a.corrupt_cell - 1] = [1.0, 2.0, 2.0, 4.0]
    elif a.corrupt == "stretched":  # det M = 1, stretch 1e16
        frames[a.corrupt_cell - 1] = [1e8, 0.0, 0.0, 1e-8]
    elif a.corrupt == "huge":  # |M|^2 overflows
        frames[a.corrupt_cell - 1] = [1e300, 0.0, 0.0, 1e300]
    if a.shuffle:
        import random
        rng = random.Random(a.shuffle)
        node_order = list(range(len(nodes)))
        rng.shuffle(node_order)  # new position -> old node
        new_of = {old: new for new, old in enumerate(node_order)}
        nodes = [nodes[old] for old in node_order]
        cell_order = list(range(len(cells)))
        rng.shuffle(cell_order)
        rotated = []
        for old in cell_order:
            q = [new_of[v] for v in cells[old]]
            r = rng.randrange(4)
            rotated.append(tuple(q[r:] + q[:r]))
        cells = rotated
        frames = [frames[old] for old in cell_order]
    with open(a.out, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        f.write(f"$Nodes\n1 {len(nodes)} 1 {len(nodes)}\n2 1 0 {len(nodes)}\n")
        for k in range(len(nodes)):
            f.write(f"{k + 1}\n")
        for p in nodes:
            f.write(f"{p[0]!r} {p[1]!r} 0\n")
        f.write("$EndNodes\n")
        f.write(f"$Elements\n1 {len(cells)} 1 {len(cells)}\n2 1 3 {len(cells)}\n")
        for k, q in enumerate(cells):
            f.write(f"{k + 1} {q[0] + 1} {q[1] + 1} {q[2] + 1} {q[3] + 1}\n")
        f.write("$EndElements\n")
        if a.corrupt != "nofield":
            f.write(f'$ElementData\n1\n"Vinv"\n1\n0\n3\n0\n9\n{len(cells)}\n')
            for k, m in enumerate(frames):
                f.write(f"{k + 1} {m[0]!r} {m[1]!r} 0 {m[2]!r} {m[3]!r} 0 0 0 1\n")
            f.write("$EndElementData\n")
        if not a.philip:
            f.write("$FrameConvention\nquadapt\n$EndFrameConvention\n")


if __name__ == "__main__":
    main()
