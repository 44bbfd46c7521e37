#!/usr/bin/python3
"""Which points still move at the end of an lpcvt minimisation (docs/bench-lpcvt-history.md,
"What the last iterations move"). Not a test.

  lpcvt FRAME -o A.msh --max-iterations 70 --move-tol 0 --edge-tol 0
  lpcvt FRAME -o B.msh --max-iterations 80 --move-tol 0 --edge-tol 0
  tail_moves.py A.msh B.msh

Matches B's nodes to A's nearest (the same point set a few iterations apart), measures each move
in units of A's nearest-neighbour distance there, and prints how concentrated the squared moves
are (the share carried by the largest 1, 5, 10, 25, 50 %), where the largest 5 % are (share of
the nodes of each of 8 x 8 bins of the unit square) and the mean cosine between the moves of
Delaunay neighbours (1: a coherent drift; 0: independent local moves). Needs numpy and scipy
(/usr/bin/python3 on Debian).
"""
import os
import sys

import numpy as np
from scipy.spatial import Delaunay, cKDTree

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "cli"))
from golden_compare import read_msh  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    A = np.array(read_msh(sys.argv[1])["nodes"])[:, :2]
    B = np.array(read_msh(sys.argv[2])["nodes"])[:, :2]
    tree = cKDTree(A)
    dist, idx = tree.query(B)
    spacing = tree.query(A, k=2)[0][:, 1]
    r = dist / spacing[idx]
    print(f"{len(B)} nodes, matched one to one: {len(set(idx.tolist())) == len(B)}; "
          f"RMS move {np.sqrt(np.mean(r ** 2)):.4f} spacings, median {np.median(r):.4f}")
    s = np.sort(r ** 2)[::-1]
    c = np.cumsum(s) / s.sum()
    print("largest moves' share of the squared move: " +
          ", ".join(f"{100 * f:g} %: {100 * c[max(0, int(f * len(c)) - 1)]:.0f} %" for f in (0.01, 0.05, 0.1, 0.25, 0.5)))
    big = B[r > np.quantile(r, 0.95)]
    H = np.histogram2d(big[:, 0], big[:, 1], bins=8, range=[[0, 1], [0, 1]])[0]
    N = np.histogram2d(B[:, 0], B[:, 1], bins=8, range=[[0, 1], [0, 1]])[0]
    print("share (%) of each bin's nodes among the largest 5 % (rows: x from 0, columns: y from 0):")
    print(np.round(100 * H / np.maximum(N, 1)).astype(int))
    D = B - A[idx]
    cos = []
    for t in Delaunay(B).simplices:
        for k in range(3):
            i, j = t[k], t[(k + 1) % 3]
            if dist[i] > 0 and dist[j] > 0:
                cos.append(D[i] @ D[j] / dist[i] / dist[j])
    print(f"mean cosine between neighbours' moves: {np.mean(cos):.3f}")


if __name__ == "__main__":
    main()
