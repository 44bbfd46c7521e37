#!/usr/bin/env python3
"""Two loops' errors at equal DOFs: for every step of loop A, B's error at A's DOF count.

usage: equal-dofs.py A/convergence.csv B/convergence.csv [--mode feature|goal] [--labels A,B]
       (A or B may be the run's directory)

The runs of scripts/loop/run-loop.sh (Makefile.cases loop) on the same case: each row of A's
table against B's curve, log(error) interpolated linearly in log(DOFs) between B's two steps
around A's DOF count (compare.py's interp_loglog; outside B's range: "-", no extrapolation). The error is the L2 error
(--mode feature, the default) or |functional_error| (--mode goal). Prints a Markdown table and
the geometric mean of A / B over the rows compared — a row both tables hold (the same DOFs and
error: the start mesh the two loops share) is shown but not counted; exit 2 on a missing or
malformed table or labels that are not two names.
For the thesis's studies, scripts/loop/compare.py compares against the thesis's own figures.
Python 3 standard library only.
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare import geomean, interp_loglog  # noqa: E402  (the study reports' interpolation)


def die(msg):
    print("equal-dofs: " + msg, file=sys.stderr)
    sys.exit(2)


def curve(path, column):
    if os.path.isdir(path):  # a run's directory: its table (it said "Is a directory": a review)
        path = os.path.join(path, "convergence.csv")
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        die("%s: %s" % (path, e.strerror or e))
    if not rows or "dofs" not in rows[0] or column not in rows[0]:
        die("%s: not a loop's convergence.csv (needs the columns dofs and %s)" % (path, column))
    out = []
    for r in rows:
        try:
            n, e = float(r["dofs"]), abs(float(r[column]))
        except ValueError:
            continue  # a step without that figure (e.g. no functional)
        if n > 0 and e > 0:
            out.append((n, e))
    if not out:
        die("%s: no step with both dofs and %s" % (path, column))
    return sorted(out)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a", metavar="A", help="loop A's convergence.csv (or its run directory): the rows")
    ap.add_argument("b", metavar="B", help="loop B's convergence.csv (or its run directory): the curve")
    ap.add_argument("--mode", choices=("feature", "goal"), default="feature")
    ap.add_argument("--labels", default="A,B")
    o = ap.parse_args(argv)
    labels = o.labels.split(",")
    if len(labels) != 2 or not all(labels):
        die("--labels '%s': give two names, A's and B's, e.g. --labels lpcvt,bamg" % o.labels)
    la, lb = labels
    column = "l2_error" if o.mode == "feature" else "functional_error"
    A, B = curve(o.a, column), curve(o.b, column)
    print("| DOFs | %s %s | %s %s at those DOFs | %s / %s |" % (la, column, lb, column, la, lb))
    print("|---|---|---|---|")
    ratios = []
    shared = set(B)
    for n, e in A:
        if (n, e) in shared:  # the same DOFs and error: the start mesh both loops share
            print("| %d | %.3e | %.3e | same step (not in the mean) |" % (n, e, e))
            continue
        eb, flag = interp_loglog(B, n)
        if eb is None or flag:  # off B's curve: no extrapolation here
            print("| %d | %.3e | - | - |" % (n, e))
            continue
        ratios.append(e / eb)
        print("| %d | %.3e | %.3e | %.3g |" % (n, e, eb, e / eb))
    if ratios:
        print("\n%s / %s at equal DOFs: geometric mean %.3g over %d steps (range %.3g-%.3g)"
              % (la, lb, geomean(ratios), len(ratios), min(ratios), max(ratios)))
    else:
        print("\nno step of %s within %s's DOF range" % (la, lb))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
