#!/usr/bin/python3
"""Error against DOFs for the runs of one study and degree p (thesis Figs. 6.6, 6.14, 6.22, 6.30).

usage: convergence.py --p P [--mode feature|goal] [--measure auto|l2_error|functional_error]
                      [--title T] [--thesis FILE.json --thesis-case KEY] -o PICTURE.(png|svg|pdf)
                      LABEL=convergence.csv [LABEL=convergence.csv ...]

One line per run (LABEL = method name: uniform, fixed-fraction, bamg, lpcvt get fixed colours),
log-log axes, and the dashed grey guide line of the optimal rate: error ~ h^(p+1) for the L2
error (feature mode); for the functional error (goal mode) h^(2p+1) when the solved PDE is pure
advection (upwind DG's superconvergence) and h^(2p) when it has diffusion (SIPG; the PDE is read
from the $SolvedCase record of the first run's step-0/sol.msh; without it h^(2p+1)), with
h ~ DOFs^(-1/2).
With --thesis, the thesis's final-mesh rows for this p and the plotted methods are drawn as
hollow stars in the method's colour. Axes: labelled ticks at 1, 2, 5 x 10^k when the axis spans
less than two decades (a single labelled decade tick otherwise), plain decades beyond. Runs whose table is missing or empty are listed in the legend as "(no data)"; when no run has data it fails (exit 2). A LABEL=DIR takes DIR/convergence.csv.
Needs python3-matplotlib (Debian); run with /usr/bin/python3.
"""
import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

def style_for(label):
    """The method's style; a label that starts with a method name (lpcvt-goal, bamg-seed2) takes
    its colour and marker."""
    if label in STYLE:
        return STYLE[label]
    for k in sorted(STYLE, key=len, reverse=True):
        if label.startswith(k):
            return STYLE[k]
    return dict(marker="o")


STYLE = {
    "uniform": dict(color="#555555", marker="s"),
    "fixed-fraction": dict(color="#2ca02c", marker="^"),
    "bamg": dict(color="#1f77b4", marker="o"),
    "lpcvt": dict(color="#d62728", marker="D"),
}
THESIS_METHOD = {"fixed_fraction": "fixed-fraction", "bamg": "bamg", "lpcvt": "lpcvt"}


def read_curve(path, measure):
    pts = []
    try:
        with open(path) as f:
            for row in csv.DictReader(f):
                try:
                    n, e = float(row["dofs"]), abs(float(row[measure]))
                except (KeyError, ValueError, TypeError):
                    continue
                if n > 0 and e > 0 and math.isfinite(e):
                    pts.append((n, e))
    except OSError:
        pass
    return pts


def tick_label(v, _pos=None):
    """1, 2, 5 x 10^k as '2e4'-style text; decades as '1e4' (or plain below 1e4)."""
    if v <= 0:
        return ""
    k = math.floor(math.log10(v) + 1e-9)
    m = v / 10 ** k
    if 1e-3 <= v < 1e4:
        return "%g" % v
    return "%de%d" % (round(m), k) if abs(m - round(m)) < 1e-6 else ""


def readable_log_ticks(axis, lo, hi):
    """Labelled ticks a reader can use: 1-2-5 per decade when the range spans < 2 decades."""
    if not (lo > 0 and hi > lo):
        return
    subs = (1.0, 2.0, 5.0) if math.log10(hi / lo) < 2 else (1.0,)
    axis.set_major_locator(LogLocator(base=10, subs=subs))
    axis.set_major_formatter(FuncFormatter(tick_label))
    axis.set_minor_formatter(NullFormatter())


def die(msg):
    """One line on stderr, exit 2 (docs/exit-codes.md), nothing written."""
    print("convergence.py: " + msg, file=sys.stderr)
    sys.exit(2)


def check_output(path):
    """Refuses, before any drawing, an output matplotlib cannot write: an unknown extension or a
    missing folder (was: a Python traceback after the work, exit 1)."""
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".png", ".svg", ".pdf"):
        die("%s: a picture is written as .png, .svg or .pdf, not '%s'" % (path, ext))
    folder = os.path.dirname(path) or "."
    if not os.path.isdir(folder):
        die("%s: no such folder '%s'" % (path, folder))


def functional_rate(runs, p):
    """The functional error's optimal order: 2p with diffusion (SIPG), 2p + 1 for pure advection
    (upwind), from the first run whose step-0/sol.msh has dgsolve's $SolvedCase record."""
    for spec in runs:
        sol = os.path.join(os.path.dirname(spec.split("=", 1)[-1]) or ".", "step-0", "sol.msh")
        try:
            with open(sol, errors="replace") as f:
                for line in f:
                    if line.strip() == "$SolvedCase":
                        rec = json.loads(next(f))
                        diffusive = any(abs(float(v)) > 0 for row in rec.get("diffusion", []) for v in row)
                        return 2 * p if diffusive else 2 * p + 1
        except (OSError, ValueError, StopIteration, TypeError):
            continue
    return 2 * p + 1


def make_figure(argv):
    """Parses the command line and draws the figure; returns (fig, ax, output path)."""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--p", type=int, required=True)
    ap.add_argument("--mode", choices=["feature", "goal"], default="feature")
    ap.add_argument("--measure", choices=["auto", "l2_error", "functional_error"], default="auto")
    ap.add_argument("--title", default="")
    ap.add_argument("--thesis", default="")
    ap.add_argument("--thesis-case", default="")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("runs", nargs="+", metavar="LABEL=CSV")
    a = ap.parse_args(argv)
    check_output(a.output)
    measure = a.measure if a.measure != "auto" else ("functional_error" if a.mode == "goal" else "l2_error")
    rate = functional_rate(a.runs, a.p) if measure == "functional_error" else (a.p + 1)

    fig, ax = plt.subplots(figsize=(6.4, 4.8), dpi=110)
    all_pts = []
    labels = set()
    for spec in a.runs:
        if "=" not in spec:
            die("run '%s' is not LABEL=CSV" % spec)
        label, path = spec.split("=", 1)
        labels.add(label)
        if os.path.isdir(path):  # a run's directory: its table (it drew "(no data)": a review)
            path = os.path.join(path, "convergence.csv")
        pts = read_curve(path, measure)
        st = style_for(label)
        if not pts:
            ax.plot([], [], label=label + " (no data)", **st)
            continue
        all_pts += pts
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "-", label=label, markersize=4, linewidth=1.4, **st)

    if not all_pts:  # an empty plot is nobody's result (it was drawn, exit 0: a review)
        die("no run has data for %s: %s (each LABEL=CSV a loop's convergence.csv or its directory)" %
            (measure, " ".join(a.runs)))
    if a.thesis and a.thesis_case:
        with open(a.thesis) as f:
            rows = json.load(f)["cases"][a.thesis_case]["rows"]
        for r in rows:
            m = THESIS_METHOD.get(r["method"], r["method"])
            if r["p"] != a.p or m not in labels:
                continue
            ax.loglog([r["dofs"]], [r["error"]], linestyle="none", marker="*", markersize=11,
                      markerfacecolor="none", markeredgewidth=1.2, color=STYLE.get(m, {}).get("color", "k"),
                      label="thesis %s (final)" % m)
            all_pts.append((r["dofs"], r["error"]))

    if all_pts:
        nmin = min(p[0] for p in all_pts)
        nmax = max(p[0] for p in all_pts)
        # guide line through the smallest error at the largest DOF count, shifted down by 3x
        ends = sorted(all_pts, key=lambda p: -p[0])[: max(1, len(all_pts) // 4)]
        e_anchor = min(p[1] for p in ends) / 3.0
        xs = [nmin, nmax]
        ys = [e_anchor * (x / nmax) ** (-rate / 2.0) for x in xs]
        ax.loglog(xs, ys, "--", color="#999999", linewidth=1.0,
                  label=r"$\mathcal{O}(h^{%d})$" % rate)
    if all_pts:
        readable_log_ticks(ax.xaxis, *ax.get_xlim())
        readable_log_ticks(ax.yaxis, *ax.get_ylim())
    ax.set_xlabel("degrees of freedom")
    ax.set_ylabel(r"$|\mathcal{J}(u) - \mathcal{J}_H(u_H)|$" if measure == "functional_error"
                  else r"$\|u - u_H\|_{L_2}$")
    ax.set_title(a.title or ("p = %d" % a.p))
    ax.grid(True, which="both", linewidth=0.3, alpha=0.5)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig, ax, a.output


def main():
    fig, _, output = make_figure(sys.argv[1:])
    tmp = "%s.tmp-%d%s" % (os.path.splitext(output)[0], os.getpid(), os.path.splitext(output)[1])
    try:
        fig.savefig(tmp)
        os.replace(tmp, output)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        die("%s: cannot write: %s" % (output, e.strerror or e))


if __name__ == "__main__":
    main()
