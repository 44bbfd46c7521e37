#!/usr/bin/python3
"""How far a frame changes from one background cell to the next, against what the default chain
reaches on it (docs/quad-quality.md, "How rough the frames are, measured").

For every interior face between background cells a and b: the unit square of a's metric
(edges M_a^-1 e1, M_a^-1 e2) measured in b's metric, P = M_b M_a^-1:
  corner distortion = 90 deg - the angle between P e1 and P e2,
  length factor     = exp(max |log sigma_i(P)|)  (sigma the singular values of P),
both directions of every face. A quad the size of a background cell whose centroid lies in b
but that fits a is measured with that distortion: issue #14's item 2 asks for corners within
90 +- 10 deg and edge lengths within a factor sqrt 2, in the metric at the quad's centroid.

With --bin BIN the default chain (lpcvt -> recombine -> quadsmooth --frame, as bench/quad/figures.sh)
is also run on each frame, and its share of right corners (within 90 +- 10 deg) and of edges in
range is measured against the frame itself and against the frame lpcvt actually meshed (after its
smoothing and gradation, lpcvt --write-frame). With --fit-meshed also the same mesh smoothed by
quadsmooth against the frame lpcvt meshed instead of FRAME (two more columns, both frames).

  frame_roughness.py FRAME.msh... [--bin BIN --work DIR] [--philip] [--fit-meshed]
"""
import argparse, json, math, os, subprocess, sys
from collections import defaultdict

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "cli"))
from golden_compare import read_msh  # noqa: E402


def distortion(Ma, Mb):
    """Cell a's unit square measured in b's metric, P = M_b M_a^-1: its corner distortion
    90 - angle(P e1, P e2) in degrees and its length factor exp max |log sigma_i(P)|."""
    P = Mb @ np.linalg.inv(Ma)
    u, w = P[:, 0], P[:, 1]
    c = abs(u @ w) / (np.linalg.norm(u) * np.linalg.norm(w))
    s = np.linalg.svd(P, compute_uv=False)
    return 90 - math.degrees(math.acos(min(1.0, c))), math.exp(max(abs(math.log(s[0])), abs(math.log(s[1]))))


def roughness(path):
    m = read_msh(path)
    V = m["views"]["Vinv"]["values"]
    Ms, conn = [], []
    for t in (3, 2):  # quads, then triangles (the view's keys are (type, index))
        for i, c in enumerate(m["elements"].get(t, [])):
            v = V[(t, i)]
            Ms.append(np.array([[v[0], v[1]], [v[3], v[4]]]))
            conn.append(c)
    faces = defaultdict(list)
    for k, c in enumerate(conn):
        for i in range(len(c)):
            a, b = c[i], c[(i + 1) % len(c)]
            faces[(min(a, b), max(a, b))].append(k)
    dev, fac = [], []
    for ks in faces.values():
        if len(ks) != 2:
            continue
        for a, b in (ks, ks[::-1]):
            d, f = distortion(Ms[a], Ms[b])
            dev.append(d)
            fac.append(f)
    dev, fac = np.array(dev), np.array(fac)
    return dict(cells=len(conn), faces=len(dev) // 2, dev_median=float(np.median(dev)),
                dev_over_10=float(np.mean(dev > 10)), len_median=float(np.median(fac)),
                len_over_sqrt2=float(np.mean(fac > math.sqrt(2))))


def chain(binp, frame, work, philip, fit_meshed=False):
    name = os.path.splitext(os.path.basename(frame))[0]
    conv = ["--convention", "philip"] if philip else []
    t, q, m, w = (os.path.join(work, f"{name}-{s}.msh") for s in ("tri", "quad", "mesh", "meshed-frame"))
    run = lambda c: subprocess.run(c, check=True, stdout=subprocess.DEVNULL)
    run([f"{binp}/lpcvt", "-q", frame, *conv, "-o", t, "--write-frame", w])
    run([f"{binp}/recombine", "-q", t, "-o", q])
    run([f"{binp}/quadsmooth", "-q", q, "--frame", frame, "-o", m])
    meshes = [("", m)]
    if fit_meshed:
        mf = os.path.join(work, f"{name}-mesh-fit-meshed.msh")
        run([f"{binp}/quadsmooth", "-q", q, "--frame", w, "-o", mf])
        meshes.append(("fit ", mf))
    out = {}
    for tag, mesh in meshes:
        for key, f in (("raw", frame), ("meshed", w)):
            d = json.loads(subprocess.run([f"{binp}/meshquality", mesh, "--frame", f], check=True,
                                          capture_output=True, text=True).stdout)["metric"]
            out[tag + key] = (d["quad_angle_share_80_100"], d["edge_length"]["share_in_range"])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("frames", nargs="+")
    ap.add_argument("--bin")
    ap.add_argument("--work", default="roughness-work")
    ap.add_argument("--philip", action="store_true", help="frames in PHiLiP's convention (lpcvt --convention philip)")
    ap.add_argument("--fit-meshed", action="store_true", help="also quadsmooth against the frame lpcvt meshed")
    a = ap.parse_args()
    head = "| frame | cells | faces | corner distortion, median (deg) | faces > 10° | length factor, median | faces > √2 |"
    if a.bin:
        os.makedirs(a.work, exist_ok=True)
        head += " chain: right corners / edges in range (raw frame) | (frame lpcvt meshed) |"
        if a.fit_meshed:
            head += " fitting the meshed frame: vs raw | vs meshed |"
    print(head)
    print("|---" * (head.count("|") - 1) + "|")
    for f in a.frames:
        r = roughness(f)
        row = (f"| {os.path.basename(f)} | {r['cells']} | {r['faces']} | {r['dev_median']:.1f} | {r['dev_over_10']:.2f} "
               f"| {r['len_median']:.2f} | {r['len_over_sqrt2']:.2f} |")
        if a.bin:
            c = chain(a.bin, f, a.work, a.philip, a.fit_meshed)
            for k in (("raw", "meshed", "fit raw", "fit meshed") if a.fit_meshed else ("raw", "meshed")):
                row += f" {c[k][0]:.2f} / {c[k][1]:.2f} |"
        print(row, flush=True)


if __name__ == "__main__":
    main()
