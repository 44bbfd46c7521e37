#!/usr/bin/env python3
"""Fixed-fraction feature indicator: adds the cell field A1h = A1 * |K|^((p+1)/2) to a SHAPE mesh.

usage: ff-indicator.py SHAPE.msh P -o IND.msh

A1 (estimate-frame, the largest (p+1)-th directional derivative of the reconstructed solution)
scaled by the cell area |K| to the power (p+1)/2, i.e. ~ A1 h^(p+1): the local interpolation
error, so that cells already refined stop being flagged. This is the "hessian" indicator of the
thesis's solver (PHiLiP GridRefinement_FixedFraction: max directional derivative times
measure^((p+1)/dim)); A1 alone would keep flagging the same cells. Reads and writes Gmsh MSH 4.1
ASCII as quadapt writes it (the file is copied and one $ElementData view appended), atomically,
with a small JSON report IND.json. Standard library only.
"""
import json
import os
import sys
import time


def fail(msg):
    sys.exit("ff-indicator: %s" % msg)


def main():
    t0 = time.time()
    a = sys.argv[1:]
    if len(a) != 4 or a[2] != "-o":
        fail("usage: ff-indicator.py SHAPE.msh P -o IND.msh")
    src, p, out = a[0], int(a[1]), a[3]
    try:
        text = open(src).read()
    except OSError as e:
        fail("%s: cannot read (%s)" % (src, e.strerror))
    lines = text.split("\n")
    try:
        i = lines.index("$MeshFormat")
        if not lines[i + 1].startswith("4.1 0"):
            fail("%s: not an ASCII MSH 4.1 file" % src)
        nodes = {}
        i = lines.index("$Nodes") + 1
        nblocks = int(lines[i].split()[0])
        i += 1
        for _ in range(nblocks):
            n = int(lines[i].split()[3])
            i += 1
            tags = [int(lines[i + k]) for k in range(n)]
            for k in range(n):
                x, y = lines[i + n + k].split()[:2]
                nodes[tags[k]] = (float(x), float(y))
            i += 2 * n
        area = {}
        i = lines.index("$Elements") + 1
        nblocks = int(lines[i].split()[0])
        i += 1
        for _ in range(nblocks):
            _, _, etype, n = map(int, lines[i].split())
            i += 1
            if etype in (2, 3):
                for k in range(n):
                    t = list(map(int, lines[i + k].split()))
                    pts = [nodes[v] for v in t[1:]]
                    s = 0.0
                    for j in range(len(pts)):
                        x0, y0 = pts[j]
                        x1, y1 = pts[(j + 1) % len(pts)]
                        s += x0 * y1 - x1 * y0
                    area[t[0]] = abs(0.5 * s)
            i += n
        # the A1 view
        a1 = None
        i = 0
        while True:
            try:
                i = lines.index("$ElementData", i) + 1
            except ValueError:
                break
            nstr = int(lines[i])
            name = lines[i + 1].strip().strip('"')
            j = i + 1 + nstr
            nreal = int(lines[j])
            j += 1 + nreal
            nint = int(lines[j])
            ints = [int(lines[j + 1 + k]) for k in range(nint)]
            j += 1 + nint
            if name == "A1":
                if ints[1] != 1:
                    fail("%s: field A1 has %d components, expected 1" % (src, ints[1]))
                a1 = {}
                for k in range(ints[2]):
                    tag, v = lines[j + k].split()[:2]
                    a1[int(tag)] = float(v)
    except (ValueError, IndexError, KeyError) as e:
        fail("%s: cannot parse the mesh (%s)" % (src, e))
    if a1 is None:
        fail("%s: no cell field 'A1' (run estimate-frame first)" % src)
    if set(a1) != set(area):
        fail("%s: field A1 does not cover every cell" % src)
    view = ["$ElementData", "1", '"A1h"', "1", "0", "3", "0", "1", str(len(area))]
    for tag in sorted(area):
        view.append("%d %.17g" % (tag, a1[tag] * area[tag] ** ((p + 1) / 2.0)))
    view.append("$EndElementData")
    tmp = "%s.tmp-%d" % (out, os.getpid())
    with open(tmp, "w") as fh:
        fh.write(text.rstrip("\n") + "\n" + "\n".join(view) + "\n")
    os.replace(tmp, out)
    rep = os.path.splitext(out)[0] + ".json"
    with open(rep + ".tmp", "w") as fh:
        json.dump({"tool": "ff-indicator", "inputs": [src], "outputs": [out], "p": p, "cells": len(area),
                   "timings": {"total": time.time() - t0}}, fh, indent=1)
    os.replace(rep + ".tmp", rep)


if __name__ == "__main__":
    main()
