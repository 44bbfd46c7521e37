#!/usr/bin/env python3
"""dgsolve on the stretched meshes of the boundary-layer loops (docs/bench-dgsolve.md,
"Stretched adapted meshes"): GMRES iterations and solve time of gmres-2level per coarse degree
q, and against another build (BASE, e.g. the commit before the Q_2 coarse space).

usage: stretched.py --bin DIR [--base DIR] [--reps N] [--threads T] [--work DIR] [--out FILE.json]

Meshes: the L_p-CVT feature loops of examples/cases/boundary-layer.json at p = 1, 2, 3 (the
study matrix's settings, scripts/loop/run-loop.sh with --bin's tools; made once into --work and
reused), every step from 3 on. On each mesh, at the loop's p: dgsolve of --bin with
--coarse-degree 1 to min(p, 3) (the default is min(p, 2)), and --base's dgsolve (its default), in
turn (A B C ... A B C ...), --reps times (default 3), one thread unless --threads. Reported:
iterations, the report's "solve" phase (assembly of the preconditioner included) and the whole
process's wall time, medians. Prints a Markdown table and writes the figures to --out.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.abspath(os.path.join(HERE, "..", ".."))
CASE = os.path.join(SRC, "examples", "cases", "boundary-layer.json")
MAXDOFS = {1: "3.6e4", 2: "5.3e4", 3: "9.3e4"}  # Makefile.cases STUDY_MAXDOFS_p


def loops(bin_dir, work):
    env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ.get("PATH", ""), OMP_NUM_THREADS="1")
    out = {}
    for p in (1, 2, 3):
        d = os.path.join(work, f"bl-feature-p{p}")
        if not os.path.exists(os.path.join(d, "loop.done")):
            subprocess.run([os.path.join(SRC, "scripts", "loop", "run-loop.sh"), "--case", CASE, "--mesh",
                            os.path.join(SRC, "examples", "meshes", "square16.msh"), "--p", str(p), "--method",
                            "lpcvt", "--mode", "feature", "--steps", "30", "--maxdofs", MAXDOFS[p], "--out", d,
                            "--pictures", "no"], env=env, check=True, capture_output=True)
        steps = sorted((int(s.split("-")[1]) for s in os.listdir(d) if s.startswith("step-")))
        out[p] = [(k, os.path.join(d, f"step-{k}", "mesh.msh")) for k in steps if k >= 3]
    return out


def run(dgsolve, mesh, p, extra, threads, tmp):
    o = os.path.join(tmp, "sol.msh")
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_WAIT_POLICY="passive")
    t0 = time.perf_counter()
    subprocess.run([dgsolve, mesh, "-c", CASE, "-p", str(p), "-o", o, "-q"] + extra, env=env, check=True)
    wall = time.perf_counter() - t0
    with open(os.path.join(tmp, "sol.json")) as f:
        r = json.load(f)
    return {"iterations": r["solver_iterations"], "solver": r["solver"], "solve": r["timings"]["solve"],
            "wall": wall, "dofs": r["dofs"], "l2_error": r["l2_error"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", required=True)
    ap.add_argument("--base", help="another build's bin directory (its dgsolve with its defaults)")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--work", default="/tmp/quadapt-dg-stretched")
    ap.add_argument("--out", default=os.path.join(HERE, "stretched-results.json"))
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    meshes = loops(os.path.abspath(a.bin), a.work)
    rows = []
    for p, ms in meshes.items():
        variants = [(f"q={q}", os.path.join(a.bin, "dgsolve"), ["--coarse-degree", str(q)]) for q in range(1, min(p, 3) + 1)]
        if a.base:
            variants.append(("base", os.path.join(a.base, "dgsolve"), []))
        for step, mesh in ms:
            runs = {name: [] for name, _, _ in variants}
            for _ in range(a.reps):
                for name, exe, extra in variants:
                    runs[name].append(run(exe, mesh, p, extra, a.threads, a.work))
            row = {"p": p, "step": step, "dofs": runs[variants[0][0]][0]["dofs"], "variants": {}}
            for name, rs in runs.items():
                row["variants"][name] = {"iterations": rs[0]["iterations"], "solver": rs[0]["solver"],
                                         "solve_s": statistics.median(r["solve"] for r in rs),
                                         "wall_s": statistics.median(r["wall"] for r in rs),
                                         "l2_error": rs[0]["l2_error"]}
            rows.append(row)
            print(json.dumps(row), file=sys.stderr)
    allnames = sorted({n for r in rows for n in r["variants"]}, key=lambda n: (n == "base", n))
    print("| p | step | DOFs | " + " | ".join(f"{n}: iterations, solve s" for n in allnames) + " |")
    print("|---|---|---|" + "---|" * len(allnames))
    for r in rows:
        cells = []
        for n in allnames:
            v = r["variants"].get(n)
            cells.append(f"{v['iterations']}, {v['solve_s']:.3f}" if v else "-")
        print(f"| {r['p']} | {r['step']} | {r['dofs']:,} | " + " | ".join(cells) + " |")
    with open(a.out, "w") as f:
        json.dump({"threads": a.threads, "reps": a.reps, "bin": a.bin, "base": a.base, "rows": rows,
                   "load_average": os.getloadavg()}, f, indent=1)


if __name__ == "__main__":
    main()
