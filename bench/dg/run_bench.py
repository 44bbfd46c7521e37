#!/usr/bin/env python3
"""dgsolve benchmark (issue 3): wall time of assembly and solve, peak memory, iterations, for
p = 1, 2, 3 on the S-shock near 2e4, 4e4 and 6.5e4 DOFs, on an adapted-like anisotropic mesh
(columns graded to 50:1 cells at x = 1/2), with UMFPACK for comparison, and the ratio to the
thesis's final-mesh solve times (docs/data/thesis-tables.json).

usage: run_bench.py [--bin DIR] [--reps N] [--threads T] [--quick] [--out FILE.json]

Every configuration runs N times (default 3); the medians are reported. "wall" is the whole
process (start-up, reading, assembly, solve, L2 error and functional, writing), measured from
outside; "assemble" / "solve" are the phases of dgsolve's report. Prints a Markdown table and
writes all figures plus machine facts to --out (default results-<host>.json beside this file).
"""
import argparse
import json
import math
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.abspath(os.path.join(HERE, "..", ".."))
TABLES = os.path.join(SRC, "docs", "data", "thesis-tables.json")

# (label, case, p, nx, ny, stretch, solver): n x n grids with (p+1)^2 n^2 ~ 2e4, 4e4, 6.5e4 DOFs.
FULL = [
    ("sshock", "sshock", 1, 71, 71, None, "auto"),
    ("sshock", "sshock", 1, 100, 100, None, "auto"),
    ("sshock", "sshock", 1, 128, 128, None, "auto"),
    ("sshock", "sshock", 2, 47, 47, None, "auto"),
    ("sshock", "sshock", 2, 67, 67, None, "auto"),
    ("sshock", "sshock", 2, 85, 85, None, "auto"),
    ("sshock", "sshock", 3, 35, 35, None, "auto"),
    ("sshock", "sshock", 3, 50, 50, None, "auto"),
    ("sshock", "sshock", 3, 64, 64, None, "auto"),
    ("sshock 50:1", "sshock", 3, 64, 64, 50, "auto"),
    ("boundary layer 50:1", "boundary-layer", 3, 64, 64, 50, "auto"),
    ("sshock advection", "sshock-advection", 3, 64, 64, None, "auto"),
    ("sshock", "sshock", 1, 128, 128, None, "umfpack"),
    ("sshock", "sshock", 2, 85, 85, None, "umfpack"),
    ("sshock", "sshock", 3, 64, 64, None, "umfpack"),
    ("sshock 50:1", "sshock", 3, 64, 64, 50, "umfpack"),
]
QUICK = [c for c in FULL if c[3] in (35, 64) and c[6] == "auto"]


def machine_facts():
    cpu = "unknown"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    facts = {"cpu": cpu, "cores": os.cpu_count(), "platform": platform.platform(),
             "python": platform.python_version(), "date": time.strftime("%Y-%m-%d %H:%M:%S")}
    try:
        facts["loadavg_start"] = open("/proc/loadavg").read().split()[:3]
        mem = [l for l in open("/proc/meminfo") if l.startswith("MemTotal")]
        facts["mem_total"] = mem[0].split(":")[1].strip() if mem else "?"
    except OSError:
        pass
    try:
        facts["blas"] = os.path.realpath("/usr/lib/x86_64-linux-gnu/libblas.so.3")
    except OSError:
        pass
    return facts


def run_one(dgsolve, mesh, case, p, solver, threads, out):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([dgsolve, "-q", mesh, "-c", case, "-p", str(p), "--solver", solver, "-o", out],
                   check=True, env=env)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    rep = json.load(open(os.path.splitext(out)[0] + ".json"))
    rep["_cpu_s"] = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return wall, rep


def thesis_rows():
    path = TABLES
    try:
        return json.load(open(path))["cases"]["sshock-feature"]["rows"]
    except (OSError, KeyError):
        return []


def interp_loglog(points, x):
    """Our time at x DOFs from (dofs, time) points (log-log, linear extrapolation at the ends)."""
    pts = sorted(points)
    if len(pts) == 1:
        return pts[0][1]
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x <= x1 or (x1, y1) == pts[-1]:
            s = (math.log(y1) - math.log(y0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + s * (math.log(x) - math.log(x0)))
    return pts[-1][1]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(SRC, "build", "bin"))
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    dgsolve = os.path.join(a.bin, "dgsolve")
    if not os.path.exists(dgsolve):
        sys.exit(f"no dgsolve in {a.bin} (build it, or pass --bin)")
    configs = QUICK if a.quick else FULL
    facts = machine_facts()
    facts["threads"] = a.threads
    facts["OMP_WAIT_POLICY"] = os.environ.get("OMP_WAIT_POLICY", "(unset: libgomp default, spins)")
    facts["reps"] = a.reps
    tmp = tempfile.mkdtemp(prefix="bench-dg-")
    results = []
    try:
        for label, case, p, nx, ny, stretch, solver in configs:
            mesh = os.path.join(tmp, f"m{nx}x{ny}{'s%g' % stretch if stretch else ''}.msh")
            if not os.path.exists(mesh):
                cmd = [sys.executable, os.path.join(HERE, "make_mesh.py"), str(nx), str(ny), mesh]
                if stretch:
                    cmd += ["--stretch", str(stretch)]
                subprocess.run(cmd, check=True)
            casef = os.path.join(SRC, "examples", "cases", case + ".json")
            runs = [run_one(dgsolve, mesh, casef, p, solver, a.threads, os.path.join(tmp, "sol.msh"))
                    for _ in range(a.reps)]
            med = lambda f: statistics.median(f(w, r) for w, r in runs)
            rep = runs[0][1]
            row = {"label": label, "case": case, "p": p, "cells": rep["cells"], "dofs": rep["dofs"],
                   "stretch": stretch or 1, "solver": rep["solver"], "iterations": rep["solver_iterations"],
                   "wall_s": med(lambda w, r: w), "cpu_s": med(lambda w, r: r["_cpu_s"]),
                   "time_s": med(lambda w, r: r["time_s"]),
                   "assemble_s": med(lambda w, r: r["timings"]["assemble"]),
                   "solve_s": med(lambda w, r: r["timings"]["solve"]),
                   "peak_memory_mb": med(lambda w, r: r["peak_memory_mb"]), "l2_error": rep["l2_error"]}
            results.append(row)
            print(f"{label:22s} p={p} dofs={row['dofs']:6d} {row['solver']:14s} it={row['iterations']:3d} "
                  f"wall={row['wall_s']:.3f} cpu={row['cpu_s']:.3f} assemble={row['assemble_s']:.3f} solve={row['solve_s']:.3f} "
                  f"mem={row['peak_memory_mb']:.0f}MB", flush=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    try:
        facts["loadavg_end"] = open("/proc/loadavg").read().split()[:3]
    except OSError:
        pass

    # Ratio to the thesis's final-mesh solve times (S-shock, feature-based, Table 6.1).
    ratios = []
    for t in thesis_rows():
        ours = [(r["dofs"], r["wall_s"]) for r in results
                if r["case"] == "sshock" and r["p"] == t["p"] and r["stretch"] == 1 and r["solver"] != "umfpack"]
        if not ours:
            continue
        mine = interp_loglog(ours, t["dofs"])
        ratios.append({"p": t["p"], "method": t["method"], "dofs": t["dofs"], "thesis_t_solve": t["t_solve"],
                       "ours_wall_s": mine, "speedup": t["t_solve"] / mine})

    print("\n| case | p | DOFs | solver | iterations | wall (s) | CPU (s) | assemble (s) | solve (s) | peak MB |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        print(f"| {r['label']} | {r['p']} | {r['dofs']} | {r['solver']} | {r['iterations']} | {r['wall_s']:.3f} | "
              f"{r['cpu_s']:.3f} | {r['assemble_s']:.3f} | {r['solve_s']:.3f} | {r['peak_memory_mb']:.0f} |")
    if ratios:
        print("\n| p | thesis method | thesis DOFs | thesis t (s) | ours (s) | speed-up |")
        print("|---|---|---|---|---|---|")
        for q in ratios:
            print(f"| {q['p']} | {q['method']} | {q['dofs']:.0f} | {q['thesis_t_solve']:.2f} | "
                  f"{q['ours_wall_s']:.3f} | {q['speedup']:.0f}x |")
    print("\nmachine:", json.dumps(facts))
    out = a.out or os.path.join(HERE, f"results-{platform.node() or 'host'}.json")
    with open(out, "w") as f:
        json.dump({"machine": facts, "results": results, "thesis_ratio": ratios}, f, indent=2)
    print("written", out)


if __name__ == "__main__":
    main()
