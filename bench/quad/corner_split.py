#!/usr/bin/python3
"""Where a quad mesh's right corners (in a frame's metric) are lost: split by the vertex's
valence and by how smooth the frame is around the quad (docs/quad-quality.md, "Where the right
corners are lost"). Not a test.

    corner_split.py FRAME MESH [FRAME MESH ...]

FRAME: a frame file (Vinv per cell; PHiLiP's or quadapt's: corner angles do not depend on the
size convention). MESH: an all-quad mesh of the same domain. Each quad is measured in M of the
frame cell holding its centroid, as meshquality does; a corner is right when its angle in that
metric is within 90 +- 10 degrees.

- by valence: the quad's corner at a boundary vertex, at an interior vertex of valence 4
  (regular) or of another valence (irregular);
- by the frame around the quad: the cells holding the midpoints between the quad's centroid and
  its four vertices, measured against the centroid's cell as frame_roughness.py measures faces
  (P = M_b M_a^-1: corner distortion 90 - angle(P e1, P e2), length factor exp max |log sigma(P)|):
  "one cell" (all four in the centroid's cell), "< 10 deg, < sqrt2" (the item's tolerances),
  "rougher" (the rest).
"""
import math
import os
import sys
from collections import defaultdict

import numpy as np
from matplotlib.path import Path

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "cli"))
from golden_compare import read_msh  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from frame_roughness import distortion  # noqa: E402  (the roughness table's face measure)


def xy(nodes, k):
    return np.array(nodes[k][:2], float)


class Frame:
    def __init__(self, path):
        m = read_msh(path)
        values = m["views"]["Vinv"]["values"]
        self.M, polys = [], []
        for t in (3, 2):  # quads, then triangles (the view's keys are (type, index))
            for i, c in enumerate(m["elements"].get(t, [])):
                v = values[(t, i)]
                self.M.append(np.array([[v[0], v[1]], [v[3], v[4]]]))
                polys.append(np.array([xy(m["nodes"], k) for k in c]))
        self.paths = [Path(p) for p in polys]
        self.lo = np.array([p.min(0) for p in polys])
        self.hi = np.array([p.max(0) for p in polys])

    def locate(self, z, tol=1e-9):
        near = np.nonzero(((self.lo - tol) <= z).all(1) & (z <= (self.hi + tol)).all(1))[0]
        for j in near:
            if self.paths[j].contains_point(z, radius=tol) or self.paths[j].contains_point(z, radius=-tol):
                return int(j)
        return int(near[0]) if len(near) else None


def split(frame_path, mesh_path):
    f = Frame(frame_path)
    m = read_msh(mesh_path)
    quads = m["elements"].get(3, [])
    valence, edges = defaultdict(int), defaultdict(int)
    for c in quads:
        for i in range(4):
            valence[c[i]] += 1
            a, b = c[i], c[(i + 1) % 4]
            edges[(min(a, b), max(a, b))] += 1
    boundary = {v for e, k in edges.items() if k == 1 for v in e}
    by_vertex = defaultdict(lambda: [0, 0])
    by_frame = defaultdict(lambda: [0, 0])
    for c in quads:
        P = np.array([xy(m["nodes"], k) for k in c])
        z = P.mean(0)
        q = f.locate(z)
        M = f.M[q]
        dmax, lmax, other = 0.0, 1.0, False
        for i in range(4):
            j = f.locate(0.5 * (P[i] + z))
            if j is None or j == q:
                continue
            other = True
            d, l = distortion(M, f.M[j])
            dmax, lmax = max(dmax, d), max(lmax, l)
        kind = "one cell" if not other else ("< 10 deg, < sqrt2" if dmax < 10 and lmax < math.sqrt(2) else "rougher")
        for i in range(4):
            u, w = M @ (P[(i + 1) % 4] - P[i]), M @ (P[(i - 1) % 4] - P[i])
            ang = math.degrees(math.acos(np.clip(u @ w / (np.linalg.norm(u) * np.linalg.norm(w)), -1, 1)))
            right = abs(ang - 90) <= 10
            v = c[i]
            vk = "boundary" if v in boundary else ("regular" if valence[v] == 4 else "irregular")
            for key, acc in (("all", by_vertex), (vk, by_vertex), (kind, by_frame)):
                acc[key][0] += right
                acc[key][1] += 1
    interior = [v for v in valence if v not in boundary]
    irregular = sum(1 for v in interior if valence[v] != 4)
    return by_vertex, by_frame, irregular, len(interior), len(quads)


def share(acc, key):
    a, b = acc.get(key, (0, 0))
    return f"{a / b:.2f}" if b else "-"


def main(argv):
    if len(argv) < 2 or len(argv) % 2:
        print(__doc__, file=sys.stderr)
        return 2
    print("| mesh | right corners | interior irregular vertices | at regular / irregular / boundary vertices "
          "| quads in one frame cell: share, right | < 10 deg, < sqrt2: share, right | rougher: share, right |")
    print("|---|---|---|---|---|---|---|")
    for fr, me in zip(argv[0::2], argv[1::2]):
        bv, bf, irr, nint, nq = split(fr, me)

        def part(k):
            n = bf.get(k, (0, 0))[1] / 4
            return f"{n / nq:.2f}, {share(bf, k)}"

        print(f"| {os.path.basename(me)} | {share(bv, 'all')} | {irr} of {nint} ({irr / nint:.1%}) | "
              f"{share(bv, 'regular')} / {share(bv, 'irregular')} / {share(bv, 'boundary')} | "
              f"{part('one cell')} | {part('< 10 deg, < sqrt2')} | {part('rougher')} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
