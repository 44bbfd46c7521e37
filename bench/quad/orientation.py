#!/usr/bin/python3
"""Quad quality of the L_p-CVT path at every frame orientation (issue #14, docs/quad-quality.md).

Constant frames on the unit square (16 x 16 background), half-axes h1 = h sqrt(s), h2 = h / sqrt(s)
with h = sqrt(1 / (4 N)) (N = --cells final cells, 1000 by default: h = sqrt(0.05 * 0.005)), long
axis at angle a; the default chain
    lpcvt FRAME -o TRI --seed 3;  recombine TRI -o QUAD;  quadsmooth QUAD --frame FRAME -o MESH
and, with --bamg, bamgquad FRAME -o MESH. Figures from meshquality --frame (each quad mapped by M
at its centroid): mean |corner angle - 90| in the metric, minimum metric scaled Jacobian, share of
edges with metric length in [1/sqrt2, sqrt2], share of interior vertices of valence != 4, cells
against the frame's 1000. 'corner bound': sin of the smallest corner angle of the domain in the
metric, the largest minimum scaled Jacobian any all-quad mesh of the square can have (a quad at a
corner has the corner's angle); 'min SJ beyond 2 / 4': the same minimum over the quads whose centroid is more than 2 / 4 target
edges (in the metric) from every corner of the square (computed here from the mesh; exact for a
constant frame).

  orientation.py BIN OUT [--angles 0 15 ...] [--stretches 1 5 ...] [--cells 1000] [--bamg] [--jobs 2]
  orientation.py BIN OUT --seed-cells 1 16 40 ... [--angles ...] [--stretches ...]
  [--lpcvt-args '...'] [--recombine-args '...'] [--quadsmooth-args '...']: options to try

--seed-cells: the L_p-CVT chain once per listed background cell, that cell's metric made finer by
1e-6 so that lpcvt's lattice start grows from it (lpcvt_frame.py --finer-cell): the spread over
the lattice's phase against the walls, which the default (cell 1) samples once. Prints per angle
and stretch the range and median of the figures and how many phases meet issue #14's item 1
(docs/quad-quality.md, "The lattice's phase").
"""
import argparse, json, math, os, subprocess, sys
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
FRAME_PY = os.path.join(HERE, "..", "..", "tests", "cli", "lpcvt_frame.py")
sys.path.insert(0, os.path.join(HERE, "..", "..", "tests", "cli"))
from golden_compare import read_msh  # noqa: E402


def min_sj_from_corners(path, M, distances=(0, 2, 4)):
    """{d: minimum metric scaled Jacobian over the quads of `path` whose centroid is more than d
    target edges (|M x| / 2, the frame's half-axes convention) from every corner of the unit
    square}; M the constant metric (2x2 rows). Corner k of a quad: cross(M e1, M e2) /
    (|M e1| |M e2|), e1, e2 its two edges from that corner (meshquality's definition; for d = 0 its
    'scaled_jacobian_min')."""
    m = read_msh(path)
    mp = [(M[0][0] * p[0] + M[0][1] * p[1], M[1][0] * p[0] + M[1][1] * p[1]) for p in m["nodes"]]
    corners = [(M[0][0] * x + M[0][1] * y, M[1][0] * x + M[1][1] * y) for x, y in ((0, 0), (1, 0), (1, 1), (0, 1))]
    best = {d: 1.0 for d in distances}
    for q in m["elements"].get(3, []):
        cx, cy = sum(mp[v][0] for v in q) / 4, sum(mp[v][1] for v in q) / 4
        dc = min(math.hypot(cx - c[0], cy - c[1]) for c in corners) / 2
        sj = 1.0
        for k in range(4):
            a, b, c = mp[q[k]], mp[q[(k + 1) % 4]], mp[q[(k - 1) % 4]]
            e1 = (b[0] - a[0], b[1] - a[1]); e2 = (c[0] - a[0], c[1] - a[1])
            sj = min(sj, (e1[0] * e2[1] - e1[1] * e2[0]) / (math.hypot(*e1) * math.hypot(*e2)))
        for d in distances:
            if dc > d:
                best[d] = min(best[d], sj)
    return best


CELLS = 1000  # --cells


def frame_metric(a_deg, s):
    """The constant frame of (angle a_deg, stretch s): its half-axes h1 = h sqrt(s), h2 = h / sqrt(s)
    (h = sqrt(1 / (4 CELLS)): CELLS target cells on the unit square; 1000: h = sqrt(0.05 * 0.005)),
    the angle in radians and M = diag(1/h1, 1/h2) R(-a) (2x2 rows): (h1, h2, a, M)."""
    h = math.sqrt(0.05 * 0.005) if CELLS == 1000 else math.sqrt(1 / (4 * CELLS))
    h1, h2, a = h * math.sqrt(s), h / math.sqrt(s), math.radians(a_deg)
    c, sn = math.cos(a), math.sin(a)
    return h1, h2, a, [[c / h1, sn / h1], [-sn / h2, c / h2]]


def corner_bound(M):
    """sin of the unit square's smallest corner angle in the constant metric M."""
    ex = (M[0][0], M[1][0]); ey = (M[0][1], M[1][1])
    cosang = abs(ex[0] * ey[0] + ex[1] * ey[1]) / math.hypot(*ex) / math.hypot(*ey)
    ang = math.acos(min(1.0, cosang))
    return math.sin(min(ang, math.pi - ang))


EXTRA = {"lpcvt": [], "recombine": [], "quadsmooth": []}  # --lpcvt-args etc.: options to try


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def make_frame(out, a_deg, s, seed_cell=0):
    """The constant frame of (angle a_deg, stretch s) in OUT, seed cell made finer when given:
    (path, tag, h1, h2, angle in radians)."""
    h1, h2, a, _ = frame_metric(a_deg, s)
    tag = f"a{a_deg:g}-s{s:g}" + (f"-n{CELLS:g}" if CELLS != 1000 else "") + (f"-c{seed_cell}" if seed_cell else "")
    f = os.path.join(out, f"frame-{tag}.msh")
    run(["/usr/bin/python3", FRAME_PY, f, "--n", "16", "--h1", repr(h1), "--h2", repr(h2), "--theta", repr(a)]
        + (["--finer-cell", str(seed_cell)] if seed_cell else []))
    return f, tag, h1, h2, a


def one(binp, out, a_deg, s, bamg, seed_cell=0):
    f, tag, h1, h2, a = make_frame(out, a_deg, s, seed_cell)
    M = frame_metric(a_deg, s)[3]
    rows = []
    paths = ["lpcvt"] + (["bamgquad"] if bamg and not seed_cell else [])
    for path in paths:
        m = os.path.join(out, f"{path}-{tag}.msh")
        if path == "lpcvt":
            t, q = os.path.join(out, f"tri-{tag}.msh"), os.path.join(out, f"quad-{tag}.msh")
            run([f"{binp}/lpcvt", f, "-o", t, "--seed", "3", "-q", "--threads", "1"] + EXTRA["lpcvt"])
            run([f"{binp}/recombine", t, "-o", q, "-q", "--threads", "1"] + EXTRA["recombine"])
            run([f"{binp}/quadsmooth", q, "--frame", f, "-o", m, "-q", "--threads", "1"] + EXTRA["quadsmooth"])
        else:
            run([f"{binp}/bamgquad", f, "-o", m, "-q", "--threads", "1"])
        d = json.loads(subprocess.run([f"{binp}/meshquality", m, "--frame", f], check=True,
                                      capture_output=True, text=True).stdout)
        me = d["metric"]
        rows.append(dict(angle=f"{a_deg:g}", stretch=s, path=path, cells=d["cells"],
                         target=d["frame"]["continuous_complexity"],
                         dev=me["quad_angle_deviation_mean_deg"], min_sj=me["scaled_jacobian_min"],
                         in_band=me["edge_length"]["share_in_range"], irregular=d["irregular_interior_share"],
                         bound=corner_bound(M), min_sj_beyond=min_sj_from_corners(m, M)))
        # the same definition as meshquality's: over all quads the same minimum
        assert abs(rows[-1]["min_sj_beyond"][0] - rows[-1]["min_sj"]) < 1e-9, (tag, path, rows[-1])
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin"); ap.add_argument("out")
    ap.add_argument("--angles", type=float, nargs="+", default=[0, 15, 30, 45, 60, 75])
    ap.add_argument("--stretches", type=float, nargs="+", default=[1, 5, 10, 20])
    ap.add_argument("--cells", type=float, default=1000, help="target cells of every frame")
    ap.add_argument("--bamg", action="store_true")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed-cells", type=int, nargs="+", default=[])
    for tool in EXTRA:
        ap.add_argument(f"--{tool}-args", default="", help=f"extra {tool} options (one string, split at spaces)")
    a = ap.parse_args()
    global CELLS
    CELLS = a.cells
    for tool in EXTRA:
        EXTRA[tool] = getattr(a, f"{tool}_args").split()
    os.makedirs(a.out, exist_ok=True)
    if a.seed_cells:
        return phases(a)
    jobs = [(ang, s) for s in a.stretches for ang in a.angles]
    with ThreadPoolExecutor(a.jobs) as ex:
        res = list(ex.map(lambda j: one(a.bin, a.out, j[0], j[1], a.bamg), jobs))
    rows = [r for rr in res for r in rr]
    json.dump(rows, open(os.path.join(a.out, "orientation.json"), "w"), indent=1)
    print("| angle | stretch | path | mean metric angle dev. (deg) | min metric SJ | corner bound | min SJ beyond 2 / 4 edges of a corner | edges in band | irregular | cells / target |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['angle']} | {r['stretch']:g} | {r['path']} | {r['dev']:.1f} | {r['min_sj']:.2f} | {r['bound']:.2f} | {r['min_sj_beyond'][2]:.3f} / {r['min_sj_beyond'][4]:.3f} | "
              f"{100 * r['in_band']:.1f} % | {100 * r['irregular']:.1f} % | {r['cells']} / {r['target']:.0f} ({100 * (r['cells'] / r['target'] - 1):+.1f} %) |")


def phases(a):
    jobs = [(ang, s, c) for s in a.stretches for ang in a.angles for c in a.seed_cells]
    with ThreadPoolExecutor(a.jobs) as ex:
        res = list(ex.map(lambda j: one(a.bin, a.out, j[0], j[1], False, j[2])[0] | {"cell": j[2]}, jobs))
    json.dump(res, open(os.path.join(a.out, "phases.json"), "w"), indent=1)
    k = len(a.seed_cells)
    print(f"Over {k} lattice phases (seed cells {' '.join(map(str, a.seed_cells))}): range (median); "
          "'met' = phases meeting issue #14 item 1's target")
    print("| angle | stretch | mean metric angle dev. | ≤ 8° met | irregular | ≤ 3 % met | edges in band (min) | ≥ 95 % met | cells / target |")
    print("|---|---|---|---|---|---|---|---|---|")
    med = lambda v: sorted(v)[len(v) // 2]
    for s in a.stretches:
        for ang in a.angles:
            rr = [r for r in res if r["angle"] == f"{ang:g}" and r["stretch"] == s]
            dev = [r["dev"] for r in rr]; irr = [100 * r["irregular"] for r in rr]
            band = [100 * r["in_band"] for r in rr]; cells = [r["cells"] / r["target"] - 1 for r in rr]
            print(f"| {ang:g} | {s:g} | {min(dev):.1f}–{max(dev):.1f}° ({med(dev):.1f}°) | {sum(d <= 8 for d in dev)} of {k} | "
                  f"{min(irr):.1f}–{max(irr):.1f} % ({med(irr):.1f} %) | {sum(i <= 3 for i in irr)} of {k} | "
                  f"{min(band):.1f} % | {sum(b >= 95 for b in band)} of {k} | {100 * min(cells):+.1f} to {100 * max(cells):+.1f} % |")


if __name__ == "__main__":
    main()
