#!/usr/bin/env python3
"""Convergence of dgsolve on a curved domain under uniform refinement (docs/curved.md).

For every degree p and every level N it meshes GEO with gmsh (`gmsh -2 -order q -setnumber N N`),
once with curved cells of order q = min(p + K, 6) (--q-plus K, default 0: isoparametric) and once
straight-sided (q = 1), solves CASE with dgsolve and prints a markdown table of the L2 errors with
the observed rates log(e(N0) / e(N1)) / log(N1 / N0) between consecutive levels N0 < N1 (h ~ 1/N;
log2(e(N/2) / e(N)) when the levels double). With --wall-radius R the case's functional J = int over its boundary of u^2
is compared with its value on the true circle of radius R around the origin (periodic
trapezoidal rule, exact to rounding), and a second table gives those errors and rates.

--boundary-nodes equal|area: the curved meshes are gmsh's straight ones curved by meshconvert
  (`--geometry GEO --order q --boundary-nodes ...`; area: docs/curved.md) instead of gmsh -order q.
--check-curved D: exit 1 unless the last curved L2 rate of every p is >= p + D.
--check-straight X: exit 1 unless the last straight-sided L2 rate of every p >= 2 is <= X.
--check-functional D: exit 1 unless the last curved functional rate of every p is >= 2 p - D.

Example (the table in docs/curved.md):
  scripts/curved/rates.py --geo examples/geometry/annulus.geo --case examples/cases/annulus.json \
      --degrees 1 2 3 4 --levels 4 8 16 32 --out /tmp/annulus
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys


def die(msg):
    print(f"rates.py: error: {msg}", file=sys.stderr)
    sys.exit(2)


def run(cmd):
    r = subprocess.run(cmd)
    if r.returncode != 0:
        die(f"{cmd[0]} exited with status {r.returncode} (its message above): {' '.join(cmd)}")


def find_tools(needed):
    """The tools on PATH, else those built in this checkout (build/bin), as run-loop.sh does."""
    build = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "bin")
    if shutil.which("dgsolve") is None and os.access(os.path.join(build, "dgsolve"), os.X_OK):
        os.environ["PATH"] = os.path.abspath(build) + os.pathsep + os.environ.get("PATH", "")
    missing = [t for t in needed if shutil.which(t) is None]
    if missing:
        die(f"tool(s) not found on PATH: {' '.join(missing)} (build the project, cmake --build build, and put "
            "build/bin on PATH; gmsh from your package manager)")


def mesh(geo, q, n, out, nodes="gmsh"):
    """Gmsh's mesh of order q (nodes = gmsh), or Gmsh's straight mesh curved by meshconvert with
    --boundary-nodes NODES (equal or area)."""
    if nodes == "gmsh" or q == 1:
        path = os.path.join(out, f"mesh-q{q}-N{n}.msh")
        if not os.path.exists(path):
            run(["gmsh", "-2", "-v", "0", "-order", str(q), "-setnumber", "N", str(n), geo, "-o", path])
        return path
    path = os.path.join(out, f"mesh-q{q}-{nodes}-N{n}.msh")
    if not os.path.exists(path):
        run(["meshconvert", "-q", mesh(geo, 1, n, out), "--geometry", geo, "--order", str(q),
             "--boundary-nodes", nodes, "-o", path])
    return path


def exact_on_circle(expr, radius, points=4096):
    """J = int over the circle of u^2 ds by the periodic trapezoidal rule."""
    src = expr.replace("^", "**")
    env = {k: getattr(math, k) for k in ("sin", "cos", "tan", "exp", "log", "sqrt", "tanh", "sinh", "cosh", "atan")}
    env.update(pi=math.pi, e=math.e, abs=abs, pow=pow)
    code = compile(src, "exact", "eval")
    s = 0.0
    for k in range(points):
        t = 2 * math.pi * k / points
        env["x"], env["y"] = radius * math.cos(t), radius * math.sin(t)
        s += eval(code, env) ** 2
    return s * 2 * math.pi * radius / points


def rate(a, b, na=1, nb=2):
    """Observed order between errors a (level na) and b (level nb): h ~ 1/N."""
    return math.log(a / b) / math.log(nb / na) if a > 0 and b > 0 else float("nan")


def table(title, rows, levels, kinds):
    lines = [f"| p | cells | " + " | ".join(f"{k} error | rate" for k in kinds) + " |",
             "|---|---|" + "---|---|" * len(kinds)]
    for p, per_kind in rows:
        for i, n in enumerate(levels):
            cells = per_kind[kinds[0]][i][0]
            cols = []
            for k in kinds:
                e = per_kind[k][i][1]
                r = rate(per_kind[k][i - 1][1], e, levels[i - 1], n) if i > 0 else None
                cols.append(f"{e:.3e} | " + (f"{r:.2f}" if r is not None else "—"))
            lines.append(f"| {p} | {cells} | " + " | ".join(cols) + " |")
    return f"{title}\n\n" + "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--geo", required=True)
    ap.add_argument("--case", required=True)
    ap.add_argument("--degrees", type=int, nargs="+", default=[1, 2, 3, 4])
    ap.add_argument("--levels", type=int, nargs="+", default=[4, 8, 16])
    ap.add_argument("--out", required=True)
    ap.add_argument("--kinds", nargs="+", default=["curved", "straight"], choices=["curved", "straight"])
    ap.add_argument("--q-plus", type=int, default=0, help="curved cells of order min(p + K, 6)")
    ap.add_argument("--boundary-nodes", default="gmsh", choices=["gmsh", "equal", "area"],
                    help="curved meshes from gmsh -order q (default), or gmsh's straight mesh curved by "
                         "meshconvert --geometry GEO --order q --boundary-nodes equal|area")
    ap.add_argument("--wall-radius", type=float, default=None)
    ap.add_argument("--check-curved", type=float, default=None)
    ap.add_argument("--check-straight", type=float, default=None)
    ap.add_argument("--check-functional", type=float, default=None)
    a = ap.parse_args()
    for f in (a.geo, a.case):
        if not os.path.isfile(f):
            die(f"{f}: no such file")
    try:
        with open(a.case) as fh:
            case = json.load(fh)
    except ValueError as e:
        die(f"{a.case}: not valid JSON ({e})")
    if a.wall_radius and (not isinstance(case, dict) or "exact" not in case):
        die(f"{a.case}: --wall-radius needs the case's \"exact\" expression")
    find_tools(["gmsh", "dgsolve"] + (["meshconvert"] if a.boundary_nodes != "gmsh" else []))
    os.makedirs(a.out, exist_ok=True)
    j_true = exact_on_circle(case["exact"], a.wall_radius) if a.wall_radius else None
    rows, frows = [], []
    for p in a.degrees:
        per_kind, fper_kind = {}, {}
        for kind in a.kinds:
            q = min(p + a.q_plus, 6) if kind == "curved" else 1
            per_kind[kind], fper_kind[kind] = [], []
            for n in a.levels:
                m = mesh(a.geo, q, n, a.out, a.boundary_nodes)
                sol = os.path.join(a.out, f"sol-{kind}-q{q}-{a.boundary_nodes}-p{p}-N{n}.msh")
                run(["dgsolve", "-q", m, "-c", a.case, "-p", str(p), "-o", sol])
                r = json.load(open(sol[:-4] + ".json"))
                per_kind[kind].append((r["cells"], r["l2_error"]))
                if j_true is not None:
                    fper_kind[kind].append((r["cells"], abs(r["functional"] - j_true)))
        rows.append((p, per_kind))
        frows.append((p, fper_kind))
    qdesc = ("q = p" if a.q_plus == 0 else f"q = min(p + {a.q_plus}, 6)") + \
        ("" if a.boundary_nodes == "gmsh" else f", meshconvert --boundary-nodes {a.boundary_nodes}")
    print(table(f"L2 error, {os.path.basename(a.case)} on {os.path.basename(a.geo)} (curved: {qdesc}; straight: q = 1)",
                rows, a.levels, a.kinds))
    if j_true is not None:
        print(table(f"Functional error |J(u_h) - J| on the true circle r = {a.wall_radius} (J = {j_true:.15g})",
                    frows, a.levels, a.kinds))
    ok = True
    for p, per_kind in rows:
        last = lambda k: rate(per_kind[k][-2][1], per_kind[k][-1][1], a.levels[-2], a.levels[-1])
        if a.check_curved is not None and "curved" in per_kind and not last("curved") >= p + a.check_curved:
            print(f"FAIL: curved p = {p}: L2 rate {last('curved'):.2f} < {p + a.check_curved}", file=sys.stderr)
            ok = False
        if a.check_straight is not None and "straight" in per_kind and p >= 2 and not last("straight") <= a.check_straight:
            print(f"FAIL: straight p = {p}: L2 rate {last('straight'):.2f} > {a.check_straight}", file=sys.stderr)
            ok = False
    for p, fk in frows:
        if a.check_functional is not None and fk.get("curved"):
            r = rate(fk["curved"][-2][1], fk["curved"][-1][1], a.levels[-2], a.levels[-1])
            if not r >= 2 * p - a.check_functional:
                print(f"FAIL: curved p = {p}: functional rate {r:.2f} < {2 * p - a.check_functional}", file=sys.stderr)
                ok = False
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
