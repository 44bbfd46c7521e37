#!/usr/bin/env python3
"""Geometric means of variant.sh's lines, relative to a reference setting on the same frame.

  summary.py [--ref SETTING] RESULTS.txt...      (SETTING default: base)

Each setting's figure (sum|eta_K| on goal frames, the L2 error on feature frames) is first
scaled to the reference mesh's DOFs N_ref by (N / N_ref)^r, with the convergence exponent in
DOFs r = (2p + 1) / 2 for the DWR sum (functional errors of DG converge as h^(2p+1), N ~ h^-2)
and r = (p + 1) / 2 for the L2 error, then divided by the reference's. Per setting: the
geometric mean over the frames, the range, the number of frames and the largest DOF ratio
|N / N_ref - 1| (the correction's size), for goal and feature frames apart. A frame that
appears twice for one setting (several result files) is an error."""
import collections, math, sys

args = sys.argv[1:]
ref = "base"
if args[:1] == ["--ref"]:
    ref, args = args[1], args[2:]
if not args:
    sys.exit(__doc__)
rows = {}
for f in args:
    for line in open(f):
        r = line.split()
        if len(r) == 7 and r[4].isdigit():
            key = tuple(r[:4])
            if key in rows:
                sys.exit("summary.py: %s appears twice (%s)" % (" ".join(key), f))
            rows[key] = (int(r[4]), float(r[6]))
for kind in ("goal", "feature"):
    rel = collections.defaultdict(list)
    dof = collections.defaultdict(float)
    for (s, p, k, v), (n, e) in rows.items():
        if kind not in s or (s, p, k, ref) not in rows:
            continue
        nb, eb = rows[(s, p, k, ref)]
        deg = int(p[1:])
        r = (2 * deg + 1) / 2 if kind == "goal" else (deg + 1) / 2
        rel[v].append(e * (n / nb) ** r / eb)
        dof[v] = max(dof[v], abs(n / nb - 1))
    if not rel:
        continue
    print("\n%s frames, relative to %s: setting | geometric mean | range | frames | largest DOF difference" % (kind, ref))
    for v, l in sorted(rel.items(), key=lambda t: t[0]):
        g = math.exp(sum(math.log(x) for x in l) / len(l))
        print("%s | %.2f | %.2f-%.2f | %d | %.1f %%" % (v, g, min(l), max(l), len(l), 100 * dof[v]))
