#!/usr/bin/python3
"""How well can lpcvt choose its lattice phase? (docs/quad-quality.md, "Best of four phases")

For every constant frame of the phase sweep (angles x stretches x seed cells, as
`orientation.py --seed-cells`), runs the default chain once per phase of `lpcvt --phases N`
(`lpcvt --lattice-phase` with lib/lpcvt/phases.cpp's offsets), measures each final mesh, and replays
the choice with several scores: what lpcvt can see (the recombined mesh: irregular count, mean
metric pair quality, combinations) and what only the whole chain can (the final figures). Prints,
per score, the cases whose chosen phase misses one of issue #14 item 1's targets.

  phase_scores.py BIN OUT [--phases 4] [--angles ...] [--stretches ...] [--seed-cells ...] [--jobs 2]
"""
import argparse, collections, json, math, os, subprocess
from concurrent.futures import ThreadPoolExecutor

import orientation


def phase_offset(k, n):
    """lib/lpcvt/phases.cpp's phase_offset(k, n)."""
    if n <= 1:
        return (0.0, 0.0)
    a = max(1, round(n * 0.6180339887498949))
    while math.gcd(a, n) != 1:
        a += 1
    return ((k % n) / n, ((k * a) % n) / n)


def ok(x):
    return x["dev"] <= 8 and x["irr"] <= 0.03 and x["band"] >= 0.95 and abs(x["cells"] / x["target"] - 1) <= 0.05


def chain(binp, out, job, n, frames):
    a_deg, s, c, k = job
    f, tag = frames[(a_deg, s, c)]
    t, q, m = (os.path.join(out, f"{x}-{tag}-k{k}.msh") for x in ("tri", "quad", "mesh"))
    run = orientation.run
    run([f"{binp}/lpcvt", f, "-o", t, "--seed", "3", "-q", "--threads", "1", "--lattice-phase"]
        + [repr(v) for v in phase_offset(k, n)])
    run([f"{binp}/recombine", t, "-o", q, "-q", "--threads", "1"])
    run([f"{binp}/quadsmooth", q, "--frame", f, "-o", m, "-q", "--threads", "1"])
    d = json.loads(subprocess.run([f"{binp}/meshquality", m, "--frame", f], check=True, capture_output=True,
                                  text=True).stdout)
    qm = json.load(open(q[:-4] + ".json"))["after_metric_matching"]
    me = d["metric"]
    return dict(a=a_deg, s=s, c=c, k=k, dev=me["quad_angle_deviation_mean_deg"], irr=d["irregular_interior_share"],
                nirr=d["irregular_interior_vertices"], band=me["edge_length"]["share_in_range"], cells=d["cells"],
                target=d["frame"]["continuous_complexity"], q=qm["mean_metric_quality"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin"); ap.add_argument("out")
    ap.add_argument("--phases", type=int, default=4)
    ap.add_argument("--angles", type=float, nargs="+", default=[0, 15, 30, 45, 60, 75, 90, 105, 120, 135, 150, 165])
    ap.add_argument("--stretches", type=float, nargs="+", default=[1, 5, 10, 20])
    ap.add_argument("--seed-cells", type=int, nargs="+", default=[1, 16, 40, 77, 100, 137, 170, 203, 241])
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    keys = [(an, s, c) for s in a.stretches for an in a.angles for c in a.seed_cells]
    with ThreadPoolExecutor(a.jobs) as ex:  # the frames first: the phases of a case share one
        frames = dict(zip(keys, ex.map(lambda key: orientation.make_frame(a.out, *key)[:2], keys)))
        jobs = [key + (k,) for key in keys for k in range(a.phases)]
        res = list(ex.map(lambda j: chain(a.bin, a.out, j, a.phases, frames), jobs))
    json.dump(res, open(os.path.join(a.out, "phase_scores.json"), "w"), indent=1)
    cases = collections.defaultdict(list)
    for x in res:
        cases[(x["a"], x["s"], x["c"])].append(x)
    scores = {
        "phase 0 alone": lambda x: x["k"],
        "irregular count, then pair quality (lpcvt's)": lambda x: (x["nirr"], -x["q"]),
        "pair quality": lambda x: -x["q"],
    }
    for w in (1, 3, 5, 10, 30):
        scores[f"-pair quality + {w} x irregular share"] = (lambda w: lambda x: -x["q"] + w * x["irr"])(w)
    scores["final: deviation"] = lambda x: x["dev"]
    scores["final: irregular, then deviation"] = lambda x: (x["nirr"], x["dev"])
    scores["final: deviation + irregular %"] = lambda x: x["dev"] + 100 * x["irr"]
    scores["final: max(deviation / 8, irregular / 3 %) (the targets)"] = lambda x: max(x["dev"] / 8, x["irr"] / 0.03)
    print(f"{len(cases)} cases x {a.phases} phases; cases with no phase meeting every target: "
          f"{sum(not any(ok(x) for x in v) for v in cases.values())}")
    print("| score | cases missing a target | deviation > 8° | irregular > 3 % | worst deviation | worst irregular |")
    print("|---|---|---|---|---|---|")
    for name, key in scores.items():
        picks = [min(sorted(v, key=lambda x: x["k"]), key=key) for v in cases.values()]
        print(f"| {name} | {sum(not ok(p) for p in picks)} | {sum(p['dev'] > 8 for p in picks)} | "
              f"{sum(p['irr'] > 0.03 for p in picks)} | {max(p['dev'] for p in picks):.2f}° | "
              f"{100 * max(p['irr'] for p in picks):.2f} % |")


if __name__ == "__main__":
    main()
