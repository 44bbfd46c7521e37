#!/usr/bin/python3
"""Curved anisotropy: the default chain on a quarter-circle boundary layer against its bending
number (docs/quad-quality.md, "Curved anisotropy"; lib/frame/bending.hpp).

Frames: tests/cli/lpcvt_frame.py --kind band (half-axes h1 along the circles about the origin, h1 /
s(d) across, s(d) = 1 + (S - 1) exp(-(d / w)^2), d = |x| - 0.6) on an n x n background of the unit
square. Per (S, h1, w, n): the default chain
    lpcvt F -o T;  recombine T -o Q;  quadsmooth Q --frame F -o M
(and bamgquad F with --bamg), meshquality --frame F figures, lpcvt's frame_bending (the frame it
meshes), and a reference: trapezoids following the circles exactly (the layer's rows as polar
rows, radial edges 2 h1 apart on r = 0.6, rows 2 h2(r) thick) on the annulus |d| <= 3 w,
measured by the same meshquality against the same frame — what straight-edged quads can reach
on the layer itself (the chain's figures are over the whole square, most of it isotropic).

  curved_layer.py BIN OUT [--stretches 10 20 50 100] [--h1 0.05] [--width 0.06] [--n 48] [--bamg]
"""
import argparse, json, math, os, subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
FRAME_PY = os.path.join(HERE, "..", "..", "tests", "cli", "lpcvt_frame.py")


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True)


def polar_mesh(path, S, h1, w):
    """Trapezoids along the circles about the origin on 0.6 - 3w <= r <= 0.6 + 3w, first quadrant:
    rows 2 h2(r) thick (h2 at the row's middle, found by a fixed point), 2 h1 of arc on r = 0.6."""
    h2 = lambda r: h1 / (1 + (S - 1) * math.exp(-((r - 0.6) / w) ** 2))
    def step(r, sign):  # the next row boundary: r + sign 2 h2(mid)
        nxt = r + sign * 2 * h2(r)
        for _ in range(20):
            nxt = r + sign * 2 * h2(0.5 * (r + nxt))
        return nxt
    rs = [0.6]
    while rs[-1] < 0.6 + 3 * w:
        rs.append(step(rs[-1], +1))
    lo = [0.6]
    while lo[-1] > 0.6 - 3 * w:
        lo.append(step(lo[-1], -1))
    rs = sorted(set(lo + rs))
    nphi = max(1, round(math.pi / 2 * 0.6 / (2 * h1)))
    phis = [math.pi / 2 * j / nphi for j in range(nphi + 1)]
    nodes = [(r * math.cos(p), r * math.sin(p)) for r in rs for p in phis]
    cells = []
    for i in range(len(rs) - 1):
        for j in range(nphi):
            k = i * (nphi + 1) + j
            cells.append((k, k + nphi + 1, k + nphi + 2, k + 1))  # counter-clockwise
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        f.write(f"$Nodes\n1 {len(nodes)} 1 {len(nodes)}\n2 1 0 {len(nodes)}\n")
        f.write("".join(f"{k + 1}\n" for k in range(len(nodes))))
        f.write("".join(f"{x!r} {y!r} 0\n" for x, y in nodes))
        f.write("$EndNodes\n")
        f.write(f"$Elements\n1 {len(cells)} 1 {len(cells)}\n2 1 3 {len(cells)}\n")
        f.write("".join(f"{k + 1} {q[0] + 1} {q[1] + 1} {q[2] + 1} {q[3] + 1}\n" for k, q in enumerate(cells)))
        f.write("$EndElements\n")


def figures(binp, mesh, frame):
    d = json.loads(run([f"{binp}/meshquality", mesh, "--frame", frame]).stdout)
    me = d["metric"]
    return dict(cells=d["cells"], target=d["frame"]["continuous_complexity"], dev=me["quad_angle_deviation_mean_deg"],
                right=me["quad_angle_share_80_100"], band=me["edge_length"]["share_in_range"],
                irregular=d["irregular_interior_share"], min_sj=me["scaled_jacobian_min"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin"); ap.add_argument("out")
    ap.add_argument("--stretches", type=float, nargs="+", default=[10, 20, 50, 100])
    ap.add_argument("--h1", type=float, nargs="+", default=[0.05])
    ap.add_argument("--width", type=float, default=0.06)
    ap.add_argument("--n", type=int, nargs="+", default=[48])
    ap.add_argument("--bamg", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for n in a.n:
        for h1 in a.h1:
            for S in a.stretches:
                tag = f"s{S:g}-h{h1:g}-w{a.width:g}-n{n}"
                p = lambda k: os.path.join(a.out, f"{k}-{tag}.msh")
                run(["/usr/bin/python3", FRAME_PY, p("frame"), "--n", str(n), "--kind", "band", "--stretch", repr(S),
                     "--h1", repr(h1), "--band-width", repr(a.width)])
                run([f"{a.bin}/lpcvt", p("frame"), "-o", p("tri"), "-q"])
                run([f"{a.bin}/recombine", p("tri"), "-o", p("quad"), "-q"])
                run([f"{a.bin}/quadsmooth", p("quad"), "--frame", p("frame"), "-o", p("mesh"), "-q"])
                bend = json.load(open(p("tri")[:-4] + ".json"))["frame_bending"]
                r = dict(n=n, h1=h1, stretch=S, bending=bend, chain=figures(a.bin, p("mesh"), p("frame")))
                polar_mesh(p("polar"), S, h1, a.width)
                r["polar"] = figures(a.bin, p("polar"), p("frame"))
                if a.bamg:
                    run([f"{a.bin}/bamgquad", p("frame"), "-o", p("bamg"), "-q"])
                    r["bamg"] = figures(a.bin, p("bamg"), p("frame"))
                rows.append(r)
    json.dump(rows, open(os.path.join(a.out, "curved_layer.json"), "w"), indent=1)
    print("| background | h1 | stretch | B > 2 (share) | largest B | path | mean metric angle dev. | right corners | edges in band | irregular | cells / target |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        for path in ("chain", "polar", "bamg"):
            if path not in r:
                continue
            f = r[path]
            count = f"{f['cells']} / {f['target']:.0f}" if path != "polar" else f"{f['cells']} (the layer only)"
            print(f"| {r['n']}x{r['n']} | {r['h1']:g} | {r['stretch']:g} | {r['bending']['share_over_2']:.2f} | "
                  f"{r['bending']['max']:.1f} | {path} | {f['dev']:.1f}° | {f['right']:.2f} | {100 * f['band']:.0f} % | "
                  f"{100 * f['irregular']:.1f} % | {count} |")


if __name__ == "__main__":
    main()
