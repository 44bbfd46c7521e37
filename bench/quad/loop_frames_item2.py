#!/usr/bin/python3
"""Issue #14 item 2's figures on the frames quadapt's own loops produce (docs/quad-quality.md,
"Item 2 on the loops' own frames").

For every step of the L_p-CVT and BAMG loops of a study-matrix run (`make -f Makefile.cases
studies`, RUNS/STUDY/pP-METHOD/step-K/{frame.msh, adapted.msh (L_p-CVT) or quad.msh (BAMG)}): the step's mesh measured against
the frame that step meshed (`meshquality MESH --frame frame.msh`): share of metric corners
within 90 +- 10 deg, share of edges in range [1/sqrt2, sqrt2] (metric at each quad's centroid),
metric min scaled Jacobian (> 0: valid), cells over the frame's continuous count; and the frame's
roughness (frame_roughness.py: median corner distortion between neighbouring background cells,
share of faces over 10 deg and over a factor sqrt2 in size). Nothing is rerun: it measures the loops as they ran.

  loop_frames_item2.py RUNS [--bin BIN] [--min-step K] [--csv OUT.csv]
"""
import argparse, csv, json, os, subprocess, sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from frame_roughness import roughness  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def measure(binp, mesh, frame):
    out = subprocess.run([f"{binp}/meshquality", "-q", mesh, "--frame", frame], check=True,
                         capture_output=True, text=True).stdout
    d = json.loads(out)
    m = d["metric"]
    return dict(corners=m["quad_angle_share_80_100"], edges=m["edge_length"]["share_in_range"],
                sj=m["scaled_jacobian_min"], count=d["frame"]["cells_over_continuous"],
                cells=d["frame"]["actual_cells"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs")
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    ap.add_argument("--min-step", type=int, default=1, help="first step measured (default 1)")
    ap.add_argument("--csv", help="also write every step's figures here")
    a = ap.parse_args()
    rows = []
    for study in sorted(os.listdir(a.runs)):
        for p in (1, 2, 3):
            for method in ("lpcvt", "bamg"):
                d = os.path.join(a.runs, study, f"p{p}-{method}")
                if not os.path.isdir(d):
                    continue
                steps = sorted(int(s.split("-")[1]) for s in os.listdir(d) if s.startswith("step-"))
                for k in steps:
                    sd = os.path.join(d, f"step-{k}")
                    f, m = os.path.join(sd, "frame.msh"), os.path.join(sd, "adapted.msh")
                    if not os.path.exists(m):  # the BAMG loop's step writes bamgquad's quad.msh
                        m = os.path.join(sd, "quad.msh")
                    if k < a.min_step or not (os.path.exists(f) and os.path.exists(m)):
                        continue
                    r = measure(a.bin, m, f)
                    r.update(study=study, p=p, method=method, step=k)
                    r.update({"rough_" + x: y for x, y in roughness(f).items() if x in ("dev_median", "dev_over_10", "len_over_sqrt2")})
                    rows.append(r)
    if a.csv:
        with open(a.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
    print("| study | p | method | steps | right corners (min-max) | edges in range (min-max) | "
          "steps with both >= 0.6 / 0.8 | min metric SJ (lowest) | cells / frame count (range) | "
          "frame: corner distortion median, faces > 10 deg, faces > sqrt2 in size (medians over the steps) |")
    print("|---" * 10 + "|")
    tot = {}
    for key in sorted({(r["study"], r["p"], r["method"]) for r in rows}, key=lambda t: (t[0], t[1], t[2] != "lpcvt")):
        rs = [r for r in rows if (r["study"], r["p"], r["method"]) == key]
        c = np.array([r["corners"] for r in rs])
        e = np.array([r["edges"] for r in rs])
        both = int(np.sum((c >= 0.6) & (e >= 0.8)))
        n = tot.setdefault(key[2], [0, 0])
        n[0] += both
        n[1] += len(rs)
        print(f"| {key[0]} | {key[1]} | {key[2]} | {len(rs)} | {c.min():.2f}-{c.max():.2f} | {e.min():.2f}-{e.max():.2f} "
              f"| {both} / {len(rs)} | {min(r['sj'] for r in rs):.3f} "
              f"| {min(r['count'] for r in rs):.3f}-{max(r['count'] for r in rs):.3f} "
              f"| {np.median([r['rough_dev_median'] for r in rs]):.1f} deg, "
              f"{np.median([r['rough_dev_over_10'] for r in rs]):.2f}, "
              f"{np.median([r['rough_len_over_sqrt2'] for r in rs]):.2f} |")
    for m, (b, n) in tot.items():
        print(f"\n{m}: both of item 2's figures on {b} of {n} steps")
    # how the figures follow the frame's roughness: Spearman rank correlation over the L_p-CVT steps
    lp = [r for r in rows if r["method"] == "lpcvt"]
    if len(lp) > 2:
        def rank(v):
            return np.argsort(np.argsort(v)).astype(float)
        for fig in ("corners", "edges"):
            for rough in ("rough_dev_median", "rough_len_over_sqrt2"):
                rho = np.corrcoef(rank([r[fig] for r in lp]), rank([r[rough] for r in lp]))[0, 1]
                print(f"lpcvt, {len(lp)} steps: Spearman correlation of {fig} with {rough[6:]}: {rho:+.2f}")


if __name__ == "__main__":
    main()
