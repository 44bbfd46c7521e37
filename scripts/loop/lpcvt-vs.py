#!/usr/bin/env python3
"""The L_p-CVT loop against our BAMG loop and the best of the thesis's three methods (issue #14).

usage: lpcvt-vs.py [RUNS]      (default RUNS = runs; needs RUNS/STUDY/pP-{lpcvt,bamg}/convergence.csv)

For each (study, p) row: both loops' errors at the thesis's L_p-CVT DOF count (log-log
interpolation along each curve, as the study reports do, no extrapolation), their ratio, and the
ratio to the smallest error of the thesis's fixed-fraction, BAMG and L_p-CVT rows. Where the
seed runs of `make -f Makefile.cases seeds` exist (RUNS/STUDY/pP-lpcvt-seedS), the L_p-CVT
figure is the median over pP-lpcvt and those runs (the goal-oriented rows). Prints a markdown
table and the two counts.
"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare import interp_loglog  # noqa: E402  (the study reports' interpolation)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RUNS = sys.argv[1] if len(sys.argv) > 1 else "runs"
THESIS = json.load(open(os.path.join(ROOT, "docs", "data", "thesis-tables.json")))["cases"]
STUDIES = [("sshock-feature", "sshock-feature", "l2_error"),
           ("bl-feature", "boundary-layer-feature", "l2_error"),
           ("sshock-goal", "sshock-goal", "functional_error"),
           ("bl-goal", "boundary-layer-goal", "functional_error")]


def curve(path, col):
    rows = list(csv.DictReader(open(path)))
    return [(float(r["dofs"]), abs(float(r[col]))) for r in rows if r.get(col) not in ("", None)]


def at(c, dofs):
    """compare.py's log-log interpolation, without its extrapolation: nan off the curve."""
    y, flag = interp_loglog(c, dofs)
    return y if y is not None and flag == "" else float("nan")


print("| study | p | thesis L_p-CVT DOFs | our L_p-CVT | our BAMG | L_p-CVT / BAMG | thesis best (method) | L_p-CVT / thesis best |")
print("|---|---|---|---|---|---|---|---|")
n = below_bamg = below_thesis = 0
for study, key, col in STUDIES:
    for p in (1, 2, 3):
        rows = [r for r in THESIS[key]["rows"] if r["p"] == p]
        best = min(rows, key=lambda r: r["error"])
        dofs = next(r["dofs"] for r in rows if r["method"] == "lpcvt")
        try:
            el = at(curve(os.path.join(RUNS, study, f"p{p}-lpcvt", "convergence.csv"), col), dofs)
            runs = [el] + [at(curve(os.path.join(RUNS, study, d, "convergence.csv"), col), dofs)
                           for d in sorted(os.listdir(os.path.join(RUNS, study)))
                           if d.startswith(f"p{p}-lpcvt-seed")
                           and os.path.exists(os.path.join(RUNS, study, d, "loop.done"))]
            el = sorted(runs)[len(runs) // 2] if len(runs) % 2 else math.exp(
                sum(math.log(v) for v in sorted(runs)[len(runs) // 2 - 1:len(runs) // 2 + 1]) / 2)
            label = f"{el:.3g}" + (f" (median of {len(runs)}: " + ", ".join(f"{v:.2g}" for v in runs) + ")"
                                   if len(runs) > 1 else "")
            eb = at(curve(os.path.join(RUNS, study, f"p{p}-bamg", "convergence.csv"), col), dofs)
        except OSError as e:
            print(f"| {study} | {p} | missing run: {e.filename} | | | | | |")
            continue
        n += 1
        below_bamg += el <= eb
        below_thesis += el < best["error"]
        print(f"| {study} | {p} | {dofs:.3g} | {label} | {eb:.3g} | {el / eb:.2f} | {best['error']:.3g} ({best['method']}) | {el / best['error']:.2f} |")
print()
print(f"L_p-CVT at or below our BAMG loop: {below_bamg} of {n}; below the thesis's best: {below_thesis} of {n}")
