#!/usr/bin/python3
"""Synthetic frame files for the lpcvt benchmark (MSH 4.1 ASCII like PHiLiP's: a quad grid on
the unit square, per-cell $ElementData "Vinv" = V^-1, V = R(theta) diag(h1, h2); quadapt
convention: the final all-quad mesh has edges 2h1 x 2h2, and lpcvt puts about
integral 1/(16 h1 h2) points).

  frames.py OUT.msh --kind const --points N [--stretch 10] [--theta 30] [--n 16]
      constant frame, h1 = stretch * h2, rotated by theta degrees, sized for about N points
  frames.py OUT.msh --kind bl --points N [--stretch 10] [--jump 4] [--levels 3] [--n 16]
      boundary-layer-like: long along x, stretch everywhere; the background rows' sizes grow by
      `jump` from the top row (y = 1) downwards for `levels` rows, then stay: size jumps of 4x
      between neighbouring cells at stretch 10:1
"""
import argparse
import math


def write(path, n, frames):
    nodes = [(i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
    cells = []
    for j in range(n):
        for i in range(n):
            k = j * (n + 1) + i
            cells.append((k, k + 1, k + n + 2, k + n + 1))
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        f.write(f"$Nodes\n1 {len(nodes)} 1 {len(nodes)}\n2 1 0 {len(nodes)}\n")
        f.write("".join(f"{k + 1}\n" for k in range(len(nodes))))
        f.write("".join(f"{p[0]!r} {p[1]!r} 0\n" for p in nodes))
        f.write("$EndNodes\n")
        f.write(f"$Elements\n1 {len(cells)} 1 {len(cells)}\n2 1 3 {len(cells)}\n")
        f.write("".join(f"{k + 1} {q[0] + 1} {q[1] + 1} {q[2] + 1} {q[3] + 1}\n" for k, q in enumerate(cells)))
        f.write("$EndElements\n")
        f.write(f'$ElementData\n1\n"Vinv"\n1\n0\n3\n0\n9\n{len(cells)}\n')
        for k, (h1, h2, th) in enumerate(frames):
            c, s = math.cos(th), math.sin(th)
            m = [c / h1, s / h1, -s / h2, c / h2]  # V^-1 = diag(1/h1, 1/h2) R(-theta)
            f.write(f"{k + 1} {m[0]!r} {m[1]!r} 0 {m[2]!r} {m[3]!r} 0 0 0 1\n")
        f.write("$EndElementData\n$FrameConvention\nquadapt\n$EndFrameConvention\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--kind", choices=["const", "bl"], required=True)
    ap.add_argument("--points", type=float, required=True)
    ap.add_argument("--stretch", type=float, default=10)
    ap.add_argument("--theta", type=float, default=30, help="degrees (const)")
    ap.add_argument("--jump", type=float, default=4)
    ap.add_argument("--levels", type=int, default=3)
    ap.add_argument("--n", type=int, default=16)
    a = ap.parse_args()
    n, r = a.n, a.stretch
    if a.kind == "const":
        # points ~ 1 / (16 h1 h2) = 1 / (16 r h2^2)
        h2 = 1 / math.sqrt(16 * r * a.points)
        frames = [(r * h2, h2, math.radians(a.theta))] * (n * n)
    else:
        # row k from the top: size factor jump^min(k, levels-1); points ~ sum over rows of
        # (1/n) / (16 r (s f_k)^2)
        fac = [a.jump ** min(k, a.levels - 1) for k in range(n)]
        s = math.sqrt(sum(1 / (n * 16 * r * f * f) for f in fac) / a.points)
        frames = []
        for j in range(n):
            f = fac[n - 1 - j]
            frames += [(r * s * f, s * f, 0.0)] * n
    write(a.out, n, frames)


if __name__ == "__main__":
    main()
