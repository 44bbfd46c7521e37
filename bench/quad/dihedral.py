#!/usr/bin/env python3
"""The default chain on a frame and its seven exact turns and mirrors (docs/quad-quality.md,
"Turned and mirrored graded frames").

    dihedral.py OUT BIN [BIN ...] [--frames F ...] [--jobs 2]

For every frame (default: PHiLiP's eight step-3 frames and the curved band of
`make -C bench/quad`), tests/cli/frame_transform.py makes the eight symmetries of the square
(id, r1-r3 turns by 90 degrees, m0-m3 mirrors); each BIN runs `lpcvt F -o T` -> `recombine T -o Q`
-> `quadsmooth Q --frame F -o M` -> `meshquality M --frame F` on each (one thread; PHiLiP's
frames with --convention philip; BIN/.. on LD_LIBRARY_PATH, where the build keeps libquadapt).
A chain that does not depend on the axes gives the same figures on all eight; the table gives
each frame's mean and range over them — issue #14 item 2's figures (metric right corners, edges in
range) without the luck of one orientation. Prints a Markdown table; OUT keeps the files.
"""
import argparse
import json
import os
import statistics as st
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(SRC, "tests", "cli"))
from frame_transform import SYMMETRIES, transform  # noqa: E402

PHILIP = ["ss15_fb_p1", "ss15_fb_p2", "ss15_adj_p1", "ss15_adj_p2",
          "bl15_fb_p2", "bl15_fb_p3", "bl15_adj_p2", "bl15_adj_p3"]


def chain(binary, frame, prefix, philip):
    env = dict(os.environ, OMP_NUM_THREADS="1",
               LD_LIBRARY_PATH=os.path.dirname(os.path.abspath(binary)))
    conv = ["--convention", "philip"] if philip else []
    b = lambda t: os.path.join(binary, t)  # noqa: E731
    steps = [[b("lpcvt"), frame, "-o", prefix + ".T.msh", "-q", "--report", prefix + ".T.json"] + conv,
             [b("recombine"), prefix + ".T.msh", "-o", prefix + ".Q.msh", "-q"],
             [b("quadsmooth"), prefix + ".Q.msh", "--frame", frame, "-o", prefix + ".M.msh", "-q"]]
    for s in steps:
        subprocess.run(s, check=True, env=env)
    with open(prefix + ".mq.json", "w") as f:
        subprocess.run([b("meshquality"), prefix + ".M.msh", "--frame", frame], check=True, env=env, stdout=f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("bins", nargs="+", help="build bin directories (tools), compared side by side")
    ap.add_argument("--frames", nargs="*", help="NAME=PATH[:philip] (default: PHiLiP's eight and the band)")
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    frames = []
    if a.frames:
        for spec in a.frames:
            name, path = spec.split("=", 1)
            philip = path.endswith(":philip")
            frames.append((name, path[: -len(":philip")] if philip else path, philip))
    else:
        fix = os.path.join(SRC, "tests", "fixtures", "philip")
        frames = [(c, os.path.join(fix, f"input_{c}_3.msh"), True) for c in PHILIP]
        band = os.path.join(a.out, "band_frame.msh")
        subprocess.run(["/usr/bin/python3", os.path.join(SRC, "tests", "cli", "lpcvt_frame.py"), band,
                        "--n", "48", "--kind", "band", "--h1", "0.02", "--stretch", "10",
                        "--band-radius", "0.6", "--band-width", "0.06"], check=True)
        frames.append(("band", band, False))
    jobs = []
    for name, path, philip in frames:
        for sym in SYMMETRIES:
            f = os.path.join(a.out, f"{name}_{sym}.msh")
            transform(path, f, sym)
            for k, binary in enumerate(a.bins):
                jobs.append((binary, f, os.path.join(a.out, f"b{k}_{name}_{sym}"), philip))
    with ThreadPoolExecutor(a.jobs) as ex:
        list(ex.map(lambda j: chain(*j), jobs))
    print("| frame | build | right corners: mean (min-max) | edges in range: mean (min-max) | "
          "metric min SJ (lowest) | irregular vertices (mean) | lpcvt evaluations (mean) |")
    print("|---|---|---|---|---|---|---|")
    means = {k: [] for k in range(len(a.bins))}
    for name, _, philip in frames:
        for k in range(len(a.bins)):
            R, E, S, I, V = [], [], [], [], []
            for sym in SYMMETRIES:
                p = os.path.join(a.out, f"b{k}_{name}_{sym}")
                q = json.load(open(p + ".mq.json"))
                R.append(q["metric"]["quad_angle_share_80_100"])
                E.append(q["metric"]["edge_length"]["share_in_range"])
                S.append(q["metric"]["scaled_jacobian_min"])
                I.append(q["irregular_interior_vertices"])
                V.append(json.load(open(p + ".T.json"))["evaluations"])
            if philip:
                means[k].append((st.mean(R), st.mean(E)))
            print(f"| {name} | {k} | {st.mean(R):.3f} ({min(R):.3f}-{max(R):.3f}) | {st.mean(E):.3f} "
                  f"({min(E):.3f}-{max(E):.3f}) | {min(S):.3f} | {st.mean(I):.1f} | {st.mean(V):.0f} |")
    for k, b in enumerate(a.bins):
        if means[k]:
            print(f"\nbuild {k} ({b}): over the PHiLiP frames, mean right corners "
                  f"{st.mean(r for r, _ in means[k]):.3f}, edges in range {st.mean(e for _, e in means[k]):.3f}")


if __name__ == "__main__":
    main()
