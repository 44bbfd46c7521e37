#!/usr/bin/python3
"""Thesis Fig. 6.1-style summary of an lpcvt run: initial and final clipped Voronoi diagrams,
energy and gradient-norm convergence.

Usage: lpcvt_voronoi.py VORONOI.json OUT.(png|svg) [--title TEXT]
VORONOI.json is written by `lpcvt ... --voronoi VORONOI.json`.
"""
import argparse
import json

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import LineCollection


def draw(ax, d, title):
    ax.add_collection(LineCollection([[(e[0], e[1]), (e[2], e[3])] for e in d["edges"]],
                                     colors="tab:blue", linewidths=0.6))
    ax.add_collection(LineCollection([[(e[0], e[1]), (e[2], e[3])] for e in d["boundary"]],
                                     colors="k", linewidths=1.0))
    s = d["sites"]
    nf = d["nfixed"]
    ax.plot([p[0] for p in s[:nf]], [p[1] for p in s[:nf]], "s", ms=2.5, color="tab:red",
            label="boundary (fixed)")
    ax.plot([p[0] for p in s[nf:]], [p[1] for p in s[nf:]], "o", ms=2.5, color="k", label="free")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_title(f"{title} ({len(s)} points)")
    ax.set_xticks([])
    ax.set_yticks([])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("voronoi")
    ap.add_argument("out")
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    d = json.load(open(a.voronoi))
    fig, axs = plt.subplots(2, 2, figsize=(10, 9.5))
    draw(axs[0][0], d["initial"], "(a) initial Voronoi diagram")
    draw(axs[0][1], d["final"], "(b) final Voronoi diagram")
    h = d["history"]
    n = list(range(len(h["energy"])))
    # cycle boundaries (new cycle = L-BFGS restart after split/merge)
    starts = [k for k in n if h["iteration"][k] == 0 and k > 0]
    ax = axs[1][0]
    ax.semilogy(n, h["energy"], "-", lw=1)
    for k in starts:
        ax.axvline(k, color="0.8", lw=0.6)
    ax.set_xlabel("L-BFGS iteration (all cycles)")
    ax.set_ylabel("$E_{L_p}$")
    ax.set_title("(c) energy")
    ax = axs[1][1]
    ax.semilogy(n, h["grad_norm"], "-", lw=1, label=r"$\|\nabla E\|$")
    ax.semilogy([k for k in n if h["step"][k] > 0], [s for s in h["step"] if s > 0], "-", lw=0.8,
                label=r"$\|\delta x\|$")
    for k in starts:
        ax.axvline(k, color="0.8", lw=0.6)
    ax.set_xlabel("L-BFGS iteration (all cycles)")
    ax.set_title("(d) gradient norm and step size")
    ax.legend()
    if a.title:
        fig.suptitle(a.title)
    fig.tight_layout()
    fig.savefig(a.out, dpi=85)


if __name__ == "__main__":
    main()
