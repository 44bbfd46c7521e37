#!/usr/bin/python3
"""Do lpcvt's points turn and mirror with a graded frame? (docs/quad-quality.md, "Turned and
mirrored graded frames")

    lpcvt_equivariance.py OUT BIN [BIN ...] [--lpcvt-args '...'] [--frames F ...]

For each frame (default: PHiLiP's eight step-3 frames, --convention philip) and each of the
seven turns and mirrors of the square (tests/cli/frame_transform.py: exact in floating point),
lpcvt is run on the transformed frame (one thread) and its points mapped back; the figure is the
largest distance from a mapped-back point to the nearest point of the original frame's run, in
units of the domain's width. Prints, per build, a table frame x symmetry and how many of the
comparisons are within 1e-12, 1e-6 and 1e-3 of the domain. BIN is a bin directory of a build;
its libraries are taken from BIN/.. (LD_LIBRARY_PATH), so frozen copies of two builds can be
compared. --lpcvt-args '--max-iterations 1 --max-cycles 1' looks at the start (after one
iteration) instead of the default run.
"""
import argparse, os, subprocess, sys
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(SRC, "tests", "cli"))
from golden_compare import read_msh  # noqa: E402
from frame_transform import SYMMETRIES, matrix  # noqa: E402

CASES = ["ss15_fb_p1", "ss15_fb_p2", "ss15_adj_p1", "ss15_adj_p2", "bl15_fb_p2", "bl15_fb_p3", "bl15_adj_p2", "bl15_adj_p3"]


def points(path):
    return np.array(read_msh(path)["nodes"])[:, :2]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("bins", nargs="+")
    ap.add_argument("--lpcvt-args", default="")
    ap.add_argument("--frames", nargs="*", default=None)
    a = ap.parse_args()
    frames = a.frames or [os.path.join(SRC, "tests", "fixtures", "philip", f"input_{c}_3.msh") for c in CASES]
    os.makedirs(a.out, exist_ok=True)
    for b, bin_dir in enumerate(a.bins):
        bin_dir = os.path.abspath(bin_dir)
        env = dict(os.environ, OMP_NUM_THREADS="1", LD_LIBRARY_PATH=os.path.dirname(bin_dir))
        print(f"\nbuild {b} ({bin_dir}), lpcvt {a.lpcvt_args or '(defaults)'}: largest distance of a point from "
              "the original's, mapped back, in units of the domain\n")
        print("| frame | " + " | ".join(SYMMETRIES[1:]) + " |")
        print("|---" * len(SYMMETRIES) + "|")
        worst = []
        for f in frames:
            name = os.path.basename(f).replace("input_", "").replace("_3.msh", "").replace(".msh", "")
            philip = "philip" if "input_" in os.path.basename(f) else "auto"
            runs = {}
            for s in SYMMETRIES:
                fr = os.path.join(a.out, f"{name}-{s}.msh")
                tri = os.path.join(a.out, f"{name}-{s}-b{b}-tri.msh")
                subprocess.run([sys.executable, os.path.join(SRC, "tests", "cli", "frame_transform.py"), f, fr, s], check=True)
                subprocess.run([os.path.join(bin_dir, "lpcvt"), "-q", fr, "--convention", philip, "-o", tri]
                               + a.lpcvt_args.split(), check=True, env=env)
                runs[s] = points(tri) @ np.array(matrix(s), dtype=float)  # Q^T x
            base = runs["id"]
            span = np.ptp(base, axis=0).max()
            row = []
            for s in SYMMETRIES[1:]:
                p = runs[s]
                if len(p) != len(base):
                    row.append(f"{len(p)} points, not {len(base)}")
                    worst.append(1.0)
                    continue
                d = np.sqrt(((base[:, None, :] - p[None, :, :]) ** 2).sum(-1)).min(axis=1).max() / span
                worst.append(d)
                row.append(f"{d:.1e}")
            print(f"| {name} | " + " | ".join(row) + " |", flush=True)
        w = np.array(worst)
        print(f"\nbuild {b}: of {len(w)} comparisons, within 1e-12: {(w <= 1e-12).sum()}, within 1e-6: "
              f"{(w <= 1e-6).sum()}, within 1e-3: {(w <= 1e-3).sum()}; largest {w.max():.2e}")


if __name__ == "__main__":
    main()
