#!/usr/bin/python3
"""lpcvt at scale against BAMG (issue #17; docs/bench-lpcvt.md, "Current figures";
docs/bench-lpcvt-history.md, "At scale"). Not a test: run by hand.

  scale_bench.py --bin BUILD/bin [--reps 3] [--sizes 4e5,4e6] [--threads 1,2] [--out results.json]
                 [--work DIR] [--big-reps 1]

Frames: an S-shock p = 2 loop (examples/cases/sshock.json from examples/meshes/square16.msh,
scripts/loop/run-loop.sh --method bamg, 6 steps, about 20 s) and estimate-frame on its step-6
solution give shape.msh; size-solve
--complexity C makes the frames (C = 4e5, 4e6, 4e7: about 1.1e4, 1.1e5, 1.1e6 lpcvt points).
C >= 1e7 is run --big-reps times (default 1) and only with one thread count (the last of --threads).

Per frame and thread count, lpcvt (defaults) and bamgquad (defaults) alternate, A B A B ..., each
under /usr/bin/time -v: wall, CPU (user + sys), peak memory; lpcvt's report: iterations,
evaluations, cycles, converged, stop, the time in the Delaunay graph and in the integration;
bamgquad's: its ffbamg seconds (BAMG alone, all calibration runs), BAMG and Blossom runs.
Medians over the repetitions; lpcvt / bamgquad is the median of the per-pair ratios.
OMP_WAIT_POLICY=passive (a busy machine; docs/bench-lpcvt.md).
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.abspath(os.path.join(HERE, "..", ".."))


def timed(cmd, env):
    """Runs cmd under /usr/bin/time -v: (wall s, cpu s, peak MB)."""
    p = subprocess.run(["/usr/bin/time", "-v"] + cmd, env=env, capture_output=True, text=True)
    if p.returncode not in (0, 1):
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr[-2000:]}")
    t = p.stderr

    def field(name):
        return re.search(re.escape(name) + r":\s*(\S+)", t).group(1)

    w = field("Elapsed (wall clock) time (h:mm:ss or m:ss)").split(":")
    wall = sum(float(x) * 60 ** (len(w) - 1 - i) for i, x in enumerate(w))
    cpu = float(field("User time (seconds)")) + float(field("System time (seconds)"))
    return wall, cpu, float(field("Maximum resident set size (kbytes)")) / 1024


def js(path):
    with open(path) as f:
        return json.load(f)


def frames(b, env, work, sizes):
    # run-loop.sh finds the tools on PATH (or BIN): the build's first, whoever calls this
    env = dict(env, PATH=b + os.pathsep + env.get("PATH", ""))
    shape = os.path.join(work, "loop", "step-6", "shape.msh")
    if not os.path.exists(shape):
        subprocess.run([os.path.join(SRC, "scripts", "loop", "run-loop.sh"), "--case",
                        os.path.join(SRC, "examples", "cases", "sshock.json"), "--mesh",
                        os.path.join(SRC, "examples", "meshes", "square16.msh"), "--p", "2", "--method", "bamg",
                        "--mode", "feature", "--steps", "6", "--out", os.path.join(work, "loop"), "--pictures", "no"],
                       env=env, check=True, capture_output=True)
        subprocess.run([f"{b}/estimate-frame", os.path.join(work, "loop", "step-6", "sol.msh"), "-o", shape, "-q"],
                       env=env, check=True)
    out = {}
    for c in sizes:
        f = os.path.join(work, f"frame-{c}.msh")
        if not os.path.exists(f):
            subprocess.run([f"{b}/size-solve", shape, "--complexity", c, "-o", f, "-q"], env=env, check=True)
        out[c] = f
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--big-reps", type=int, default=1)
    ap.add_argument("--sizes", default="4e5,4e6")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--work", default="/tmp/quadapt-scale-bench")
    ap.add_argument("--out", default=os.path.join(HERE, "scale-results.json"))
    a = ap.parse_args()
    b = os.path.abspath(a.bin)
    os.makedirs(a.work, exist_ok=True)
    env = dict(os.environ, PATH=b + os.pathsep + os.environ.get("PATH", ""), OMP_WAIT_POLICY="passive")
    fr = frames(b, env, a.work, a.sizes.split(","))
    threads = [int(t) for t in a.threads.split(",")]
    rows = []
    for c, f in fr.items():
        big = float(c) >= 1e7
        for th in (threads[-1:] if big else threads):
            e = dict(env, OMP_NUM_THREADS=str(th))
            lp, bq = [], []
            for _ in range(a.big_reps if big else a.reps):
                t = os.path.join(a.work, "lp.msh")
                w, cpu, mem = timed([f"{b}/lpcvt", f, "-o", t, "-q", "--threads", str(th)], e)
                r = js(t[:-4] + ".json")
                lp.append({"wall": w, "cpu": cpu, "mem_mb": mem, "points": r["points"], "iterations": r["iterations"],
                           "evaluations": r["evaluations"], "cycles": r["cycles"], "converged": r["converged"],
                           "stop": r["stop"], "delaunay_s": r["energy_seconds"]["delaunay"],
                           "integrate_s": r["energy_seconds"]["integrate"], "lpcvt_s": r["timings"]["lpcvt"]})
                q = os.path.join(a.work, "bq.msh")
                w, cpu, mem = timed([f"{b}/bamgquad", f, "-o", q, "-q", "--threads", str(th)], e)
                r = js(q[:-4] + ".json")
                bq.append({"wall": w, "cpu": cpu, "mem_mb": mem, "cells": r["cells"], "bamg_s": r["bamg"]["seconds"],
                           "bamg_runs": r["calibration"]["runs"], "blossom_runs": r["calibration"]["blossom_runs"]})
                print(f"{c} threads {th}: lpcvt {lp[-1]['wall']:.2f} s, bamgquad {bq[-1]['wall']:.2f} s", file=sys.stderr)
            med = lambda l, k: statistics.median(x[k] for x in l)
            rows.append({"complexity": c, "threads": th, "reps": len(lp), "lpcvt": lp, "bamgquad": bq,
                         "ratio_wall": statistics.median(x["wall"] / y["wall"] for x, y in zip(lp, bq)),
                         "lpcvt_wall": med(lp, "wall"), "lpcvt_cpu": med(lp, "cpu"), "lpcvt_mem": med(lp, "mem_mb"),
                         "bamgquad_wall": med(bq, "wall"), "bamgquad_cpu": med(bq, "cpu"),
                         "bamgquad_mem": med(bq, "mem_mb"), "ffbamg_s": med(bq, "bamg_s")})
            with open(a.out, "w") as o:
                json.dump({"rows": rows, "load": os.getloadavg()}, o, indent=1)
    print("| points | threads | lpcvt wall s | CPU s | peak MB | iterations / evaluations | cycles | converged | "
          "Delaunay / integration s | bamgquad wall s | CPU s | peak MB | ffbamg alone s | BAMG / Blossom runs | "
          "lpcvt / bamgquad |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        l, q = r["lpcvt"][-1], r["bamgquad"][-1]
        print(f"| {l['points']:,} | {r['threads']} | {r['lpcvt_wall']:.2f} | {r['lpcvt_cpu']:.2f} | {r['lpcvt_mem']:.0f} | "
              f"{l['iterations']} / {l['evaluations']} | {l['cycles']} | {'yes' if l['converged'] else 'no'} | "
              f"{statistics.median(x['delaunay_s'] for x in r['lpcvt']):.2f} / "
              f"{statistics.median(x['integrate_s'] for x in r['lpcvt']):.2f} | {r['bamgquad_wall']:.2f} | "
              f"{r['bamgquad_cpu']:.2f} | {r['bamgquad_mem']:.0f} | {r['ffbamg_s']:.2f} | "
              f"{q['bamg_runs']} / {q['blossom_runs']} | {r['ratio_wall']:.2f} |")


if __name__ == "__main__":
    main()
