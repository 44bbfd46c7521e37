#!/usr/bin/python3
"""A quad mesh drawn in the metric space of a constant frame, each cell coloured by its mean
|corner angle - 90°| in the metric (docs/quad-quality.md, "Sliding walls"). Not a test.

  metric_picture.py MESH.msh OUT.png --angle DEG --stretch S [--title T] [--vmax 20]

The frame is orientation.py's (frame_metric): half-axes h sqrt(S) x h / sqrt(S), h = sqrt(0.05 *
0.005), long axis at DEG; M = diag(1/h1, 1/h2) R(-DEG) maps the unit square to a parallelogram on which the frame's
target cells are squares of side 2 (meshquality's convention: a target edge has |M e| / 2 = 1).
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from orientation import frame_metric, read_msh  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh"); ap.add_argument("out")
    ap.add_argument("--angle", type=float, required=True)
    ap.add_argument("--stretch", type=float, required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("--vmax", type=float, default=20)
    a = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    M = frame_metric(a.angle, a.stretch)[3]
    m = read_msh(a.mesh)
    x = [(M[0][0] * p[0] + M[0][1] * p[1], M[1][0] * p[0] + M[1][1] * p[1]) for p in m["nodes"]]
    polys, dev = [], []
    for cell in m["elements"].get(3, []):
        P = [x[v] for v in cell]
        d = 0
        for k in range(4):
            o, n, p = P[k], P[(k + 1) % 4], P[(k - 1) % 4]
            e1, e2 = (n[0] - o[0], n[1] - o[1]), (p[0] - o[0], p[1] - o[1])
            c = (e1[0] * e2[0] + e1[1] * e2[1]) / math.hypot(*e1) / math.hypot(*e2)
            d += abs(math.degrees(math.acos(max(-1.0, min(1.0, c)))) - 90) / 4
        polys.append(P)
        dev.append(d)
    fig, ax = plt.subplots(figsize=(4.2, 9))
    pc = PolyCollection(polys, array=dev, cmap="viridis", edgecolors="k", linewidths=0.2)
    pc.set_clim(0, a.vmax)
    ax.add_collection(pc)
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_axis_off()
    mean = f"mean {sum(dev) / len(dev):.2f}°"
    ax.set_title(f"{a.title}: {mean}" if a.title else mean, fontsize=9)
    fig.colorbar(pc, ax=ax, shrink=0.5, label="mean |corner − 90°| in the metric")
    fig.savefig(a.out, dpi=80, bbox_inches="tight")


if __name__ == "__main__":
    main()
