#!/usr/bin/python3
"""How many points change region between two lpcvt outputs of the same frame (docs/bench-lpcvt-history.md,
"Is the tail a density correction?").

Points of each mesh binned on a B x B grid over the bounding box of REF; the share of points that
change bins = half the L1 difference of the two histograms over REF's point count (0: every region
holds the same number of points; a start that needs points carried across regions shows a large
share).

  density_bins.py REF.msh OTHER.msh... [--bins 4 8 16]
"""
import argparse, os, sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "cli"))
from golden_compare import read_msh  # noqa: E402


def points(path):
    n = read_msh(path)["nodes"]
    return (np.array(list(n.values())) if isinstance(n, dict) else np.asarray(n))[:, :2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("ref")
    ap.add_argument("others", nargs="+")
    ap.add_argument("--bins", type=int, nargs="+", default=[4, 8, 16])
    a = ap.parse_args()
    ref = points(a.ref)
    lo, hi = ref.min(axis=0), ref.max(axis=0)
    rng = [[lo[0], hi[0]], [lo[1], hi[1]]]
    print("| mesh | points | " + " | ".join(f"changed bins, {b}x{b}" for b in a.bins) + " |")
    print("|---" * (len(a.bins) + 2) + "|")
    for o in a.others:
        x = points(o)
        cells = []
        for b in a.bins:
            hr = np.histogram2d(ref[:, 0], ref[:, 1], bins=b, range=rng)[0]
            ho = np.histogram2d(x[:, 0], x[:, 1], bins=b, range=rng)[0]
            cells.append(f"{100 * 0.5 * np.abs(ho - hr).sum() / len(ref):.2f} %")
        print(f"| {os.path.basename(o)} | {len(x)} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
