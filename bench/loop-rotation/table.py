#!/usr/bin/python3
"""The loops on rotated problems against the same loops unrotated (bench/loop-rotation).

For every (study, p) of OUT/ANGLE/STUDY/pP-METHOD and RUNS/STUDY/pP-METHOD (the study matrix,
make -f Makefile.cases studies): the L2 error at the thesis's L_p-CVT DOF count (log-log
interpolation along each curve, as scripts/loop/lpcvt-vs.py), rotated over unrotated for each
method, and L_p-CVT over BAMG at each angle.

  table.py OUT RUNS
"""
import csv, json, math, os, sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts", "loop"))
from compare import geomean, interp_loglog  # noqa: E402

KEYS = {"sshock-feature": "sshock-feature", "bl-feature": "boundary-layer-feature"}


def at(path, dofs):
    rows = list(csv.DictReader(open(path)))
    y, flag = interp_loglog([(float(r["dofs"]), float(r["l2_error"])) for r in rows], dofs)
    return y if y is not None and flag == "" else float("nan")


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__.strip())
    out, runs = sys.argv[1], sys.argv[2]
    thesis = json.load(open(os.path.join(ROOT, "docs", "data", "thesis-tables.json")))["cases"]
    angles = sorted((d for d in os.listdir(out) if d.replace(".", "").isdigit()), key=float)
    print("| study | p | DOFs | angle | L_p-CVT | BAMG | L_p-CVT rotated / unrotated | BAMG rotated / unrotated | L_p-CVT / BAMG |")
    print("|---|---|---|---|---|---|---|---|---|")
    ratios = {"lpcvt": [], "bamg": []}
    wins = total = 0
    for study, key in KEYS.items():
        for p in (1, 2, 3):
            dofs = next(r["dofs"] for r in thesis[key]["rows"] if r["p"] == p and r["method"] == "lpcvt")
            base = {}
            for m in ("lpcvt", "bamg"):
                f = os.path.join(runs, study, f"p{p}-{m}", "convergence.csv")
                base[m] = at(f, dofs) if os.path.exists(f) else float("nan")
            lines = [f"| {study} | {p} | {dofs:.3g} | 0 (the study matrix) | {base['lpcvt']:.3g} | {base['bamg']:.3g} | | "
                     f"| {base['lpcvt'] / base['bamg']:.2f} |"]
            for a in angles:
                e = {}
                for m in ("lpcvt", "bamg"):
                    f = os.path.join(out, a, study, f"p{p}-{m}", "convergence.csv")
                    e[m] = at(f, dofs) if os.path.exists(f) else float("nan")
                if all(math.isnan(v) for v in e.values()):
                    continue
                for m in e:
                    if not math.isnan(e[m] / base[m]):
                        ratios[m].append(e[m] / base[m])
                if not math.isnan(e["lpcvt"] / e["bamg"]):
                    total += 1
                    wins += e["lpcvt"] <= e["bamg"]
                lines.append(f"| {study} | {p} | {dofs:.3g} | {a} | {e['lpcvt']:.3g} | {e['bamg']:.3g} | {e['lpcvt'] / base['lpcvt']:.2f} "
                             f"| {e['bamg'] / base['bamg']:.2f} | {e['lpcvt'] / e['bamg']:.2f} |")
            if len(lines) > 1:  # only the (study, p) rows that were run rotated
                print("\n".join(lines))
    print()
    for m, v in ratios.items():
        if v:
            print(f"{m}: rotated / unrotated over {len(v)} rows: geometric mean {geomean(v):.2f}, range {min(v):.2f}-{max(v):.2f}")
    print(f"L_p-CVT at or below BAMG on the rotated problems: {wins} of {total}")


if __name__ == "__main__":
    main()
