#!/usr/bin/env python3
"""Geometric means of variant.sh's lines, relative to the "base" setting on the same frame.

  summary.py RESULTS.txt...

Each setting's figure (sum|eta_K| for goal studies, the L2 error for feature studies) is first
scaled to the base mesh's DOFs by (N_base / N)^(-(p+1)/2), i.e. multiplied by (N / N_base)^((p+1)/2),
then divided by the base's; the table gives, per setting, the geometric mean over the frames,
the range and the number of frames, for goal and feature frames apart."""
import collections, math, sys

rows = {}
for f in sys.argv[1:]:
    for line in open(f):
        r = line.split()
        if len(r) == 7 and r[4].isdigit():
            rows[tuple(r[:4])] = (int(r[4]), float(r[6]))
for kind in ("goal", "feature"):
    rel = collections.defaultdict(list)
    for (s, p, k, v), (n, e) in rows.items():
        if kind not in s or (s, p, k, "base") not in rows:
            continue
        nb, eb = rows[(s, p, k, "base")]
        deg = int(p[1:])
        rel[v].append(e * (n / nb) ** ((deg + 1) / 2) / eb)
    if not rel:
        continue
    print("\n%s frames: setting | geometric mean | range | frames" % kind)
    for v, l in sorted(rel.items(), key=lambda t: t[0]):
        g = math.exp(sum(math.log(x) for x in l) / len(l))
        print("%s | %.2f | %.2f-%.2f | %d" % (v, g, min(l), max(l), len(l)))
