#!/usr/bin/python3
"""lpcvt benchmark (docs/bench-lpcvt.md). Not a test: run by hand (make -C bench/lpcvt).

  run_bench.py --bin BUILD/bin [--reps 3] [--threads 2] [--out results.json] [--quick]

Sections (each printed as a markdown table, all figures in the JSON):
  scaling     10:1 frames at 30 degrees giving about 1e3, 1e4, 1e5 points: lpcvt wall time
              (median of --reps), iterations, evaluations, cycles, time in the Delaunay graph and
              in the integration; bamgquad --runs 1 (median) on the same frame: its BAMG phase
              (ffbamg) and its total (BAMG + Blossom + split); the time ratios
  anisotropy  10:1 at 30 degrees and the boundary-layer-like frame (10:1, 4x size jumps between
              neighbouring cells) at about 1e4 points: lpcvt (default, --gradation 2, --smooth 2,
              --weight 0) + recombine, and bamgquad (calibrated), measured by meshquality
  fixtures    the eight PHiLiP frames input_*_3.msh at the README's step-3 complexity
              (--complexity, --degree): DOFs after recombine, time; bamgquad on the same frame
              rescaled by scale_frame.py
  own         S-shock and boundary layer frames at 4e4 DOFs (p = 1, 2) from dgsolve ->
              estimate-frame -> size-solve --complexity 40000 on a 64x64 mesh: DOFs, quality
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.abspath(os.path.join(HERE, "..", ".."))
FIXTURES = os.environ.get("QUADAPT_FIXTURES_DIR", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "fixtures", "philip"))
COMPLEXITY = {1: 3456, 2: 7776, 3: 13824}  # README: step 3 of the 1.5x sequences


def run(cmd, env):
    t0 = time.time()
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if p.returncode not in (0, 1):
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}")
    return time.time() - t0


def js(path):
    with open(path) as f:
        return json.load(f)


def quality(b, env, mesh, frame):
    p = subprocess.run([f"{b}/meshquality", mesh, "--frame", frame], env=env, capture_output=True, text=True)
    q = json.loads(p.stdout)
    return {"cells": q["cells"], "frame_stretch_median": q["frame"]["stretch_median"],
            "edge_ratio_median": q["physical"]["edge_ratio_median"],
            "angle_80_100": q["physical"]["quad_angle_share_80_100"],
            "metric_len_in_range": q["metric"]["edge_length"]["share_in_range"],
            "metric_edge_ratio_median": q["metric"]["edge_ratio_median"],
            "min_scaled_jacobian": q["physical"]["scaled_jacobian_min"]}


def lpcvt_run(b, env, frame, out, extra, reps):
    times, rep = [], None
    for _ in range(reps):
        w = run([f"{b}/lpcvt", frame, "-o", out, "-q"] + extra, env)
        rep = js(out[:-4] + ".json")
        times.append(w)
    return {"wall_s": statistics.median(times), "walls": times, "lpcvt_s": rep["timings"]["lpcvt"],
            "points": rep["points"], "requested": rep["requested_points"], "iterations": rep["iterations"],
            "evaluations": rep["evaluations"], "cycles": rep["cycles"], "stop": rep["stop"],
            "converged": rep["converged"], "triangles": rep["triangles"], "target_cells": rep["target_cells"],
            "delaunay_s": rep["energy_seconds"]["delaunay"], "integrate_s": rep["energy_seconds"]["integrate"]}


def bamg_run(b, env, frame, out, reps, runs=1):
    walls, phases, rep = [], [], None
    for _ in range(reps):
        w = run([f"{b}/bamgquad", frame, "-o", out, "-q", "--runs", str(runs)], env)
        rep = js(out[:-4] + ".json")
        walls.append(w)
        phases.append(rep["bamg"]["seconds"])
    return {"wall_s": statistics.median(walls), "bamg_s": statistics.median(phases), "cells": rep["cells"],
            "target": rep["target_complexity"], "triangles": rep["bamg"]["triangles"]}


def md(rows, cols):
    out = ["| " + " | ".join(c for c, _ in cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        out.append("| " + " | ".join(f(r) for _, f in cols) + " |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(SRC, "build", "bin"))
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default="results.json")
    ap.add_argument("--quick", action="store_true", help="no 1e5 case, one repetition")
    ap.add_argument("--only", default="scaling,anisotropy,fixtures,own")
    a = ap.parse_args()
    b = os.path.abspath(a.bin)
    env = dict(os.environ, OMP_NUM_THREADS=str(a.threads), PATH=b + ":" + os.environ["PATH"])
    reps = 1 if a.quick else a.reps
    cpu = platform.processor()
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    res = {"machine": {"cpu": cpu,
                       "cores": os.cpu_count(), "threads": a.threads, "load_before": os.getloadavg()},
           "reps": reps}
    only = a.only.split(",")
    tmp = tempfile.mkdtemp(prefix="bench-lpcvt-")
    frames_py = [sys.executable, os.path.join(HERE, "frames.py")]

    if "scaling" in only:
        rows = []
        for n in ([1e3, 1e4] if a.quick else [1e3, 1e4, 1e5]):
            f = f"{tmp}/c10-{n:.0e}.msh"
            subprocess.run(frames_py + [f, "--kind", "const", "--points", str(n)], check=True)
            lp = lpcvt_run(b, env, f, f"{tmp}/c10-tri.msh", [], reps)
            bq = bamg_run(b, env, f, f"{tmp}/c10-bq.msh", reps)
            row = {"points_asked": n, "lpcvt": lp, "bamgquad": bq,
                   "ratio_bamg_phase": lp["wall_s"] / bq["bamg_s"], "ratio_bamgquad": lp["wall_s"] / bq["wall_s"]}
            rows.append(row)
            print(f"scaling {n:.0e}: lpcvt {lp['wall_s']:.2f} s, bamg {bq['bamg_s']:.2f} s, bamgquad {bq['wall_s']:.2f} s", file=sys.stderr)
        res["scaling"] = rows
        print("\n### Scaling (10:1 frame at 30 degrees)\n")
        print(md(rows, [("points", lambda r: f"{r['lpcvt']['points']}"),
                        ("lpcvt wall s (median)", lambda r: f"{r['lpcvt']['wall_s']:.2f}"),
                        ("iterations / evaluations", lambda r: f"{r['lpcvt']['iterations']} / {r['lpcvt']['evaluations']}"),
                        ("cycles", lambda r: f"{r['lpcvt']['cycles']}"),
                        ("Delaunay / integration s", lambda r: f"{r['lpcvt']['delaunay_s']:.2f} / {r['lpcvt']['integrate_s']:.2f}"),
                        ("BAMG triangles s", lambda r: f"{r['bamgquad']['bamg_s']:.2f}"),
                        ("bamgquad total s", lambda r: f"{r['bamgquad']['wall_s']:.2f}"),
                        ("lpcvt / BAMG", lambda r: f"{r['ratio_bamg_phase']:.1f}"),
                        ("lpcvt / bamgquad", lambda r: f"{r['ratio_bamgquad']:.1f}")]))

    if "anisotropy" in only:
        rows = []
        for kind in ["const", "bl"]:
            f = f"{tmp}/{kind}-1e4.msh"
            subprocess.run(frames_py + [f, "--kind", kind, "--points", "1e4"], check=True)
            for label, extra in [("lpcvt", []), ("lpcvt --gradation 2", ["--gradation", "2"]),
                                 ("lpcvt --smooth 2", ["--smooth", "2"]), ("lpcvt --weight 0", ["--weight", "0"])]:
                lp = lpcvt_run(b, env, f, f"{tmp}/a-tri.msh", extra, 1)
                run([f"{b}/recombine", f"{tmp}/a-tri.msh", "-o", f"{tmp}/a-q.msh", "-q"], env)
                rows.append({"frame": kind, "method": label, "lpcvt": lp, "target": lp["target_cells"],
                             **quality(b, env, f"{tmp}/a-q.msh", f)})
            bq = bamg_run(b, env, f, f"{tmp}/a-bq.msh", 1, runs=3)
            rows.append({"frame": kind, "method": "bamgquad", "target": bq["target"],
                         **quality(b, env, f"{tmp}/a-bq.msh", f)})
            print(f"anisotropy {kind} done", file=sys.stderr)
        res["anisotropy"] = rows
        print("\n### Anisotropy (about 1e4 points; quality of the final all-quad mesh)\n")
        print(md(rows, [("frame", lambda r: "10:1 at 30°" if r["frame"] == "const" else "BL 10:1, 4x jumps"),
                        ("method", lambda r: r["method"]),
                        ("cells / target", lambda r: f"{r['cells']} / {r['target']:.0f} ({r['cells'] / r['target']:.3f})"),
                        ("stretch median (frame)", lambda r: f"{r['edge_ratio_median']:.2f} ({r['frame_stretch_median']:.1f})"),
                        ("angles in [80°,100°]", lambda r: f"{r['angle_80_100']:.2f}"),
                        ("metric edges in [0.71, 1.41]", lambda r: f"{r['metric_len_in_range']:.2f}"),
                        ("min scaled Jacobian", lambda r: f"{r['min_scaled_jacobian']:.2f}"),
                        ("lpcvt s", lambda r: f"{r['lpcvt']['wall_s']:.2f}" if "lpcvt" in r else "")]))

    if "fixtures" in only and os.path.isdir(FIXTURES):
        rows = []
        for name in sorted(os.listdir(FIXTURES)):
            if not (name.startswith("input_") and name.endswith("_3.msh")):
                continue
            p = int(name.split("_p")[1][0])
            C = COMPLEXITY[p]
            f = os.path.join(FIXTURES, name)
            lp = lpcvt_run(b, env, f, f"{tmp}/fx-tri.msh", ["--complexity", str(C), "--degree", str(p)], 1)
            run([f"{b}/recombine", f"{tmp}/fx-tri.msh", "-o", f"{tmp}/fx-q.msh", "-q"], env)
            sf = f"{tmp}/fx-frame.msh"
            subprocess.run([sys.executable, os.path.join(HERE, "scale_frame.py"), f, sf, "--cells", str(C / (p + 1) ** 2)],
                           check=True, capture_output=True)
            ql = quality(b, env, f"{tmp}/fx-q.msh", sf)
            bq = bamg_run(b, env, sf, f"{tmp}/fx-bq.msh", 1, runs=3)
            qb = quality(b, env, f"{tmp}/fx-bq.msh", sf)
            rows.append({"fixture": name, "p": p, "complexity": C, "lpcvt": lp, "dofs": ql["cells"] * (p + 1) ** 2,
                         "quality": ql, "bamgquad": bq, "bamg_dofs": qb["cells"] * (p + 1) ** 2, "bamg_quality": qb})
        res["fixtures"] = rows
        print("\n### PHiLiP frames (step 3, README complexity)\n")
        print(md(rows, [("frame", lambda r: r["fixture"].replace("input_", "").replace(".msh", "")),
                        ("target DOFs", lambda r: str(r["complexity"])),
                        ("lpcvt points", lambda r: str(r["lpcvt"]["points"])),
                        ("DOFs (ratio)", lambda r: f"{r['dofs']} ({r['dofs'] / r['complexity']:.3f})"),
                        ("lpcvt s", lambda r: f"{r['lpcvt']['wall_s']:.2f}"),
                        ("stretch (frame)", lambda r: f"{r['quality']['edge_ratio_median']:.2f} ({r['quality']['frame_stretch_median']:.2f})"),
                        ("angles [80,100]", lambda r: f"{r['quality']['angle_80_100']:.2f}"),
                        ("bamgquad DOFs (ratio)", lambda r: f"{r['bamg_dofs']} ({r['bamg_dofs'] / r['complexity']:.3f})"),
                        ("bamgquad stretch, angles", lambda r: f"{r['bamg_quality']['edge_ratio_median']:.2f}, {r['bamg_quality']['angle_80_100']:.2f}")]))

    if "own" in only:
        rows = []
        m16 = os.path.join(SRC, "examples", "meshes", "square16.msh")
        run([f"{b}/refine", m16, "--uniform", "-o", f"{tmp}/s32.msh", "-q"], env)
        run([f"{b}/refine", f"{tmp}/s32.msh", "--uniform", "-o", f"{tmp}/s64.msh", "-q"], env)
        for case in ["sshock", "boundary-layer"]:
            for p in [1, 2]:
                c = os.path.join(SRC, "examples", "cases", case + ".json")
                run([f"{b}/dgsolve", f"{tmp}/s64.msh", "-c", c, "-p", str(p), "-o", f"{tmp}/sol.msh", "-q"], env)
                run([f"{b}/estimate-frame", f"{tmp}/sol.msh", "-o", f"{tmp}/shape.msh", "-q"], env)
                fr = f"{tmp}/frame-{case}-{p}.msh"
                run([f"{b}/size-solve", f"{tmp}/shape.msh", "--complexity", "40000", "-o", fr, "-q"], env)
                for label, extra in [("lpcvt", []), ("lpcvt --gradation 2", ["--gradation", "2"])]:
                    lp = lpcvt_run(b, env, fr, f"{tmp}/o-tri.msh", extra, 1)
                    run([f"{b}/recombine", f"{tmp}/o-tri.msh", "-o", f"{tmp}/o-q.msh", "-q"], env)
                    q = quality(b, env, f"{tmp}/o-q.msh", fr)
                    rows.append({"case": case, "p": p, "method": label, "lpcvt": lp, "dofs": q["cells"] * (p + 1) ** 2, **q})
                bq = bamg_run(b, env, fr, f"{tmp}/o-bq.msh", 1, runs=3)
                q = quality(b, env, f"{tmp}/o-bq.msh", fr)
                rows.append({"case": case, "p": p, "method": "bamgquad", "bamg": bq, "dofs": q["cells"] * (p + 1) ** 2, **q})
                print(f"own {case} p{p} done", file=sys.stderr)
        res["own"] = rows
        print("\n### Own frames at 4e4 DOFs (size-solve on a 64x64 solution)\n")
        print(md(rows, [("case", lambda r: f"{r['case']} p={r['p']}"), ("method", lambda r: r["method"]),
                        ("DOFs (ratio)", lambda r: f"{r['dofs']} ({r['dofs'] / 40000:.3f})"),
                        ("stretch (frame)", lambda r: f"{r['edge_ratio_median']:.2f} ({r['frame_stretch_median']:.2f})"),
                        ("angles [80,100]", lambda r: f"{r['angle_80_100']:.2f}"),
                        ("metric edges in range", lambda r: f"{r['metric_len_in_range']:.2f}"),
                        ("min sJ", lambda r: f"{r['min_scaled_jacobian']:.2f}"),
                        ("time s", lambda r: f"{r['lpcvt']['wall_s']:.2f}" if "lpcvt" in r else f"{r['bamg']['wall_s']:.2f}"),
                        ("cycles", lambda r: str(r["lpcvt"]["cycles"]) if "lpcvt" in r else "")]))

    res["machine"]["load_after"] = os.getloadavg()
    with open(a.out, "w") as f:
        json.dump(res, f, indent=1)
    print(f"\nmachine: {res['machine']}", file=sys.stderr)


if __name__ == "__main__":
    main()
