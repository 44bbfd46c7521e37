#!/usr/bin/env python3
"""The L_p-CVT loop against our BAMG loop and the best of the thesis's three methods (issue #14).

usage: lpcvt-vs.py [RUNS]      (default RUNS = runs; needs RUNS/STUDY/pP-{lpcvt,bamg}/convergence.csv)

For each (study, p) row: both loops' errors at the thesis's L_p-CVT DOF count (log-log
interpolation along each curve, as the study reports do, no extrapolation), their ratio, and the
ratio to the smallest error of the thesis's fixed-fraction, BAMG and L_p-CVT rows. Where the
seed runs of `make -f Makefile.cases seeds` exist (RUNS/STUDY/pP-lpcvt-seedS), the L_p-CVT
figure is the median over pP-lpcvt and those runs (the goal-oriented rows); likewise the BAMG
figure over pP-bamg and the runs of `make -f Makefile.cases bamg-seeds` (RUNS/STUDY/pP-bamg-seedS,
other start meshes), when they exist — then the count against BAMG's first run alone is printed
too. Prints a markdown table and the counts; then, for the rows with at least three runs of both
loops, how far apart the two samples are: the ratio of their geometric means and the two-sided
Mann-Whitney (Wilcoxon rank-sum) p-value of "the L_p-CVT errors and the BAMG errors come from the
same distribution" (exact up to 9 + 9 runs, then the normal approximation; small p: the
difference is not the runs' noise).
"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare import geomean, interp_loglog, mann_whitney_p  # noqa: E402  (the study reports' interpolation)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
if sys.argv[1:] in (["-h"], ["--help"]):
    print(__doc__.strip())
    sys.exit(0)
if len(sys.argv) > 2 or (len(sys.argv) == 2 and sys.argv[1].startswith("-")):
    print("lpcvt-vs.py: unknown option or extra argument: " + " ".join(sys.argv[1:]) + " (usage: lpcvt-vs.py [RUNS])",
          file=sys.stderr)
    sys.exit(2)
RUNS = sys.argv[1] if len(sys.argv) > 1 else "runs"
if not os.path.isdir(RUNS):
    print("lpcvt-vs.py: %s: no such directory (the RUNS of make -f Makefile.cases studies)" % RUNS, file=sys.stderr)
    sys.exit(2)
THESIS = json.load(open(os.path.join(ROOT, "docs", "data", "thesis-tables.json")))["cases"]
STUDIES = [("sshock-feature", "sshock-feature", "l2_error"),
           ("bl-feature", "boundary-layer-feature", "l2_error"),
           ("sshock-goal", "sshock-goal", "functional_error"),
           ("bl-goal", "boundary-layer-goal", "functional_error")]


def curve(path, col):
    rows = list(csv.DictReader(open(path)))
    return [(float(r["dofs"]), abs(float(r[col]))) for r in rows if r.get(col) not in ("", None)]


def median(values):
    v = sorted(values)
    h = len(v) // 2
    return v[h] if len(v) % 2 else math.exp((math.log(v[h - 1]) + math.log(v[h])) / 2)


def runs_at(study, p, method, col, dofs):
    """(median, its label, the first run's value) over pP-METHOD and its finished seed runs."""
    first = at(curve(os.path.join(RUNS, study, f"p{p}-{method}", "convergence.csv"), col), dofs)
    runs = [first] + [at(curve(os.path.join(RUNS, study, d, "convergence.csv"), col), dofs)
                      for d in sorted(os.listdir(os.path.join(RUNS, study)))
                      if d.startswith(f"p{p}-{method}-seed") and os.path.exists(os.path.join(RUNS, study, d, "loop.done"))]
    m = median(runs)
    label = f"{m:.3g}" + (f" (median of {len(runs)}: " + ", ".join(f"{v:.2g}" for v in runs) + ")" if len(runs) > 1 else "")
    return m, label, first, runs


def at(c, dofs):
    """compare.py's log-log interpolation, without its extrapolation: nan off the curve."""
    y, flag = interp_loglog(c, dofs)
    return y if y is not None and flag == "" else float("nan")


print("| study | p | thesis L_p-CVT DOFs | our L_p-CVT | our BAMG | L_p-CVT / BAMG | thesis best (method) | L_p-CVT / thesis best |")
print("|---|---|---|---|---|---|---|---|")
n = below_bamg = below_bamg_first = below_thesis = bamg_medians = 0
spread = []
for study, key, col in STUDIES:
    for p in (1, 2, 3):
        rows = [r for r in THESIS[key]["rows"] if r["p"] == p]
        best = min(rows, key=lambda r: r["error"])
        dofs = next(r["dofs"] for r in rows if r["method"] == "lpcvt")
        try:
            el, label, _, lruns = runs_at(study, p, "lpcvt", col, dofs)
            eb, blabel, eb1, bruns = runs_at(study, p, "bamg", col, dofs)
            nb = len(bruns)
        except OSError as e:
            print(f"| {study} | {p} | missing run: {e.filename} | | | | | |")
            continue
        n += 1
        below_bamg += el <= eb
        below_bamg_first += el <= eb1
        bamg_medians += nb > 1
        below_thesis += el < best["error"]
        print(f"| {study} | {p} | {dofs:.3g} | {label} | {blabel} | {el / eb:.2f} | {best['error']:.3g} ({best['method']}) | {el / best['error']:.2f} |")
        if len(lruns) >= 3 and len(bruns) >= 3 and all(math.isfinite(v) for v in lruns + bruns):
            spread.append((study, p, len(lruns), len(bruns), geomean(lruns) / geomean(bruns), mann_whitney_p(lruns, bruns)))
print()
print(f"L_p-CVT at or below our BAMG loop: {below_bamg} of {n}; below the thesis's best: {below_thesis} of {n}")
if bamg_medians:
    print(f"(against BAMG's first run alone, no median, in the {bamg_medians} rows with BAMG seed runs: "
          f"at or below in {below_bamg_first} of {n})")
if spread:
    print()
    print("| study | p | runs L_p-CVT / BAMG | geometric mean L_p-CVT / BAMG | Mann-Whitney p (two-sided) |")
    print("|---|---|---|---|---|")
    for study, p, nl, nb, g, pv in spread:
        print(f"| {study} | {p} | {nl} / {nb} | {g:.2f} | {pv:.2f} |")
