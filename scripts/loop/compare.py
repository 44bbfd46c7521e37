#!/usr/bin/env python3
"""Comparison report of one study against the thesis's table (docs/design.md §5).

usage: compare.py --study DIR --thesis thesis-tables.json --case KEY --mode feature|goal
                  [--ps 1,2,3] [--methods uniform,fixed-fraction,bamg,lpcvt] [-o DIR/report.md]

DIR holds one run per degree and method, DIR/p<P>-<METHOD>/convergence.csv (scripts/loop/run-loop.sh),
and the study's plots DIR/convergence-p<P>.png. For every row of the thesis's table (case KEY):
our error at the thesis's DOF count, by linear interpolation of log(error) against log(DOFs)
along our curve (points sorted by DOFs; outside our range: the end segment's slope up to a factor
1.5 beyond the last point, marked "extrap.", else "not reached"); our solve time interpolated the
same way and our final solve time; and which is better. Also JSON (same name, .json) for
docs/studies.md. Python 3 standard library only.
"""
import argparse
import csv
import itertools
import json
import math
import os
import sys

METHOD_NAME = {"fixed_fraction": "fixed-fraction", "bamg": "bamg", "lpcvt": "lpcvt", "uniform": "uniform"}
EXTRAP = 1.5


def read_csv(path):
    rows = []
    try:
        with open(path) as f:
            for r in csv.DictReader(f):
                rows.append(r)
    except OSError:
        return None
    return rows


def num(r, k):
    try:
        v = float(r.get(k, ""))
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


def interp_loglog(points, x):
    """points: [(x, y)] with x, y > 0. Returns (y, flag) flag in {'', 'extrap.', 'not reached'}."""
    pts = sorted({(px, py) for px, py in points if px and py and px > 0 and py > 0})
    if not pts:
        return None, "no data"
    if len(pts) == 1:
        px, py = pts[0]
        return (py, "") if abs(px / x - 1) < 1e-9 else (None, "not reached")
    lx = math.log(x)
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x0 <= x <= x1 and x1 > x0:
            t = (lx - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0))), ""
    if x > pts[-1][0]:
        (x0, y0), (x1, y1) = pts[-2], pts[-1]
        if x > EXTRAP * x1:
            return None, "not reached"
    else:
        (x0, y0), (x1, y1) = pts[0], pts[1]
        if x < x0 / EXTRAP:
            return None, "not reached"
    if x1 <= x0:
        return None, "not reached"
    slope = (math.log(y1) - math.log(y0)) / (math.log(x1) - math.log(x0))
    ref = (x1, y1) if x > x1 else (x0, y0)
    return math.exp(math.log(ref[1]) + slope * (lx - math.log(ref[0]))), "extrap."


def mann_whitney_p(a, b):
    """Two-sided p-value of the rank-sum (Mann-Whitney U) test that a and b come from one
    distribution. Exact while there are at most 200,000 ways to split the pooled values into
    groups of len(a) and len(b) (e.g. 9 + 9): the share of splits whose U is at least as far from
    its mean as the observed one (ties count half). Beyond that the normal approximation with
    continuity correction (no tie correction)."""
    def u_stat(x, y):
        return sum(1.0 if xi > yj else 0.5 if xi == yj else 0.0 for xi in x for yj in y)
    pooled, na, nb = list(a) + list(b), len(a), len(b)
    mean = na * nb / 2
    d_obs = abs(u_stat(a, b) - mean)
    if math.comb(na + nb, na) > 200000:
        sd = math.sqrt(na * nb * (na + nb + 1) / 12)
        return min(1.0, math.erfc(max(0.0, d_obs - 0.5) / sd / math.sqrt(2)))
    hits = total = 0
    for idx in itertools.combinations(range(len(pooled)), na):
        chosen = set(idx)
        x = [pooled[i] for i in idx]
        y = [pooled[i] for i in range(len(pooled)) if i not in chosen]
        total += 1
        hits += abs(u_stat(x, y) - mean) >= d_obs - 1e-12
    return hits / total


def geomean(v):
    return math.exp(sum(math.log(x) for x in v) / len(v))


def e(v, digits=2):
    return "–" if v is None else ("%.*e" % (digits, v))


def f(v, digits=2):
    return "–" if v is None else ("%.*f" % (digits, v))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--study", required=True)
    ap.add_argument("--thesis", required=True)
    ap.add_argument("--case", required=True)
    ap.add_argument("--mode", choices=["feature", "goal"], required=True)
    ap.add_argument("--ps", default="1,2,3")
    ap.add_argument("--methods", default="uniform,fixed-fraction,bamg,lpcvt")
    ap.add_argument("--title", default="")
    ap.add_argument("-o", "--output", default="")
    a = ap.parse_args()

    def die(msg):  # one line, exit 2, before anything is written (it gave tracebacks: a review)
        print("compare.py: " + msg, file=sys.stderr)
        sys.exit(2)

    if not os.path.isdir(a.study):
        die("--study %s: no such directory (a study's runs, RUNS/STUDY of make -f Makefile.cases)" % a.study)
    try:
        ps = [int(p) for p in a.ps.split(",") if p]
    except ValueError:
        die("--ps %s: a comma-separated list of degrees, e.g. 1,2,3" % a.ps)
    methods = [m for m in a.methods.split(",") if m]
    unknown = [m for m in methods if m not in METHOD_NAME.values()]
    if unknown or not methods or not ps:
        die("--methods %s / --ps %s: methods among %s, at least one of each" %
            (a.methods, a.ps, ",".join(sorted(set(METHOD_NAME.values())))))
    try:
        with open(a.thesis) as fh:
            cases = json.load(fh)["cases"]
    except (OSError, ValueError, KeyError, TypeError) as err:  # not "e": main() calls the module's e()
        die("--thesis %s: cannot read the thesis's tables (%s)" % (a.thesis, err))
    if a.case not in cases:
        die("--case %s: not in %s (its cases: %s)" % (a.case, a.thesis, ", ".join(sorted(cases))))
    tcase = cases[a.case]
    out = a.output or os.path.join(a.study, "report.md")
    measure = tcase.get("measure", "functional_error" if a.mode == "goal" else "l2_error")
    name = os.path.basename(os.path.normpath(a.study))

    runs = {}
    for p in ps:
        for m in methods:
            d = os.path.join(a.study, "p%d-%s" % (p, m))
            rows = read_csv(os.path.join(d, "convergence.csv"))
            params = {}
            try:
                with open(os.path.join(d, "loop.json")) as fh:
                    params = json.load(fh)
            except (OSError, ValueError):
                pass
            runs[(p, m)] = dict(dir=d, rows=rows or [], done=os.path.exists(os.path.join(d, "loop.done")),
                                params=params)

    L = []
    L.append("# %s: quadapt against the thesis (Table %s)" % (a.title or name, tcase.get("table", "?")))
    L.append("")
    L.append("Measure: **%s** (%s). Generated by `scripts/loop/compare.py` from the runs in this "
             "directory; the thesis's figures are from `thesis-tables.json`." %
             (measure, "L2 error of the solution" if measure == "l2_error" else "|J(u) - J_H(u_H)|"))
    case_file = next((r["params"].get("case") for r in runs.values() if r["params"].get("case")), None)
    if case_file:
        L.append("Case file: `%s`." % os.path.relpath(case_file, os.getcwd()) if os.path.isabs(case_file)
                 else "Case file: `%s`." % case_file)
    L.append("")
    L.append("How to read: *ours @ thesis DOFs* interpolates our convergence curve (log-log) at the "
             "thesis's final DOF count; *better* compares it with the thesis's final error. Times: "
             "the thesis's solve on its final mesh (its machine) against our `dgsolve` time interpolated at "
             "the same DOF count (this machine, OMP_NUM_THREADS as run); the comparison of times across "
             "machines is indicative only.")
    L.append("")

    # ---- comparison rows
    L.append("## Row by row")
    L.append("")
    L.append("| p | method | thesis DOFs | thesis error | ours @ thesis DOFs | ours / thesis | better | "
             "thesis t_solve [s] | our t_solve @ DOFs [s] | faster | our final DOFs | our final error |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    summary = []
    for r in tcase["rows"]:
        p, m = r["p"], METHOD_NAME.get(r["method"], r["method"])
        if p not in ps or m not in methods:
            continue  # a row of a degree or method not asked for (--ps, --methods)
        run = runs.get((p, m), dict(rows=[], done=False))
        pts = [(num(x, "dofs"), num(x, measure)) for x in run["rows"]]
        pts = [(x, abs(y)) for x, y in pts if x and y is not None and y != 0]
        tpts = [(num(x, "dofs"), num(x, "t_solve")) for x in run["rows"]]
        ours, flag = interp_loglog(pts, r["dofs"])
        t_ours, tflag = interp_loglog([(x, y) for x, y in tpts if x and y], r["dofs"])
        final = run["rows"][-1] if run["rows"] else {}
        better = "–"
        ratio = None
        if ours is not None:
            ratio = ours / r["error"]
            better = "**quadapt**" if ours < r["error"] else "thesis"
        faster = "–"
        if t_ours is not None and r.get("t_solve"):
            faster = "quadapt" if t_ours < r["t_solve"] else "thesis"
        status = "" if run["rows"] else " (not run)"
        L.append("| %d | %s%s | %.3g | %s | %s%s | %s | %s | %s | %s%s | %s | %s | %s |" % (
            p, m, status, r["dofs"], e(r["error"]), e(ours), (" (%s)" % flag) if flag and ours is not None else
            ("" if ours is not None else " (%s)" % flag), ("%.2g" % ratio) if ratio is not None else "–", better,
            f(r.get("t_solve")), f(t_ours), (" (%s)" % tflag) if tflag and t_ours is not None else "", faster,
            "%.3g" % num(final, "dofs") if num(final, "dofs") else "–", e(num(final, measure))))
        summary.append(dict(p=p, method=m, thesis_dofs=r["dofs"], thesis_error=r["error"], ours=ours, flag=flag,
                            ratio=ratio, better=better.strip("*"), thesis_t_solve=r.get("t_solve"),
                            our_t_solve=t_ours, faster=faster, final_dofs=num(final, "dofs"),
                            final_error=num(final, measure), final_t_solve=num(final, "t_solve")))
    L.append("")
    won = sum(1 for s in summary if s["better"] == "quadapt")
    compared = sum(1 for s in summary if s["ours"] is not None)
    L.append("quadapt has the smaller error in **%d of %d** compared rows (%d thesis rows)." %
             (won, compared, len(summary)))
    L.append("")

    # ---- our runs
    L.append("## Our runs")
    L.append("")
    L.append("| p | method | status | solves | final DOFs | final cells | final %s | final t_solve [s] | "
             "loop time [s] |" % measure)
    L.append("|---|---|---|---|---|---|---|---|---|")
    for p in ps:
        for m in methods:
            run = runs[(p, m)]
            rows = run["rows"]
            fin = rows[-1] if rows else {}
            total = sum(num(x, "t_step") or 0 for x in rows)
            st = "done" if run["done"] else ("running / stopped" if rows else "not run")
            L.append("| %d | %s | %s | %d | %s | %s | %s | %s | %s |" % (
                p, m, st, len(rows), "%.3g" % num(fin, "dofs") if num(fin, "dofs") else "–",
                "%d" % num(fin, "cells") if num(fin, "cells") else "–", e(num(fin, measure)),
                f(num(fin, "t_solve")), f(total, 1) if rows else "–"))
    L.append("")

    # ---- figures
    L.append("## Figures")
    L.append("")
    for p in ps:
        fig = "convergence-p%d.png" % p
        if os.path.exists(os.path.join(a.study, fig)):
            L.append("### p = %d" % p)
            L.append("")
            L.append("![convergence p=%d](%s)" % (p, fig))
            L.append("")
            pics = []
            for m in methods:
                for pic, what in (("final-mesh.png", "final mesh"), ("final-mesh-closeup.png", "close-up")):
                    rel = "p%d-%s/%s" % (p, m, pic)
                    if os.path.exists(os.path.join(a.study, rel)):
                        pics.append("[%s %s](%s)" % (m, what, rel))
            if pics:
                L.append("Final meshes: " + ", ".join(pics))
                L.append("")
    text = "\n".join(L) + "\n"
    tmp = out + ".tmp-%d" % os.getpid()
    with open(tmp, "w") as fh:
        fh.write(text)
    os.replace(tmp, out)
    js = os.path.splitext(out)[0] + ".json"
    with open(js + ".tmp", "w") as fh:
        json.dump(dict(study=name, case=a.case, measure=measure, rows=summary), fh, indent=1)
    os.replace(js + ".tmp", js)
    print("%s: %d of %d compared rows better than the thesis" % (out, won, compared))


if __name__ == "__main__":
    sys.exit(main())
