#!/usr/bin/env python3
"""Distance of a mesh's boundary nodes to a circle (docs/curved.md).

  check_boundary.py MESH.msh --group cylinder --circle CX CY R [--max 1e-12]

Reads MSH 4.1 ASCII (quadapt's and Gmsh's; other formats: `meshconvert IN -o OUT.msh` first), takes every node of the line elements (of any order:
the high-order nodes of curved edges too) of the physical curve GROUP and prints, as JSON, the
number of nodes, the largest | |x - c| - R | and, with --max, the number of nodes farther than
that ("off"); exit 1 when more than --allow-off (default 0) nodes are.
"""
import argparse
import json
import math
import sys


def die(msg):
    print(f"check_boundary.py: error: {msg}", file=sys.stderr)
    sys.exit(2)


def read(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        die(f"{path}: cannot read it ({e.strerror})")
    head = data[:200].split(b"\n")
    fmt = head[1].split() if len(head) > 1 and head[0].strip() == b"$MeshFormat" else []
    if len(fmt) < 2 or not fmt[0].startswith(b"4.") or fmt[1] != b"0":
        if not fmt:
            die(f"{path}: not a Gmsh MSH file (it does not start with $MeshFormat)")
        kind = "binary" if fmt[1:2] == [b"1"] else "ASCII"
        die(f"{path}: MSH {fmt[0].decode(errors='replace')} {kind}; this script reads MSH 4.1 ASCII only "
            f"(convert it: meshconvert {path} -o OUT.msh)")
    lines = data.decode("utf-8", errors="replace").split("\n")
    i = 0
    names, curve_phys, nodes, lines_of = {}, {}, {}, {}
    while i < len(lines):
        s = lines[i].strip()
        if s == "$PhysicalNames":
            n = int(lines[i + 1])
            for k in range(n):
                dim, tag, name = lines[i + 2 + k].split(maxsplit=2)
                if dim == "1":
                    names[name.strip('"')] = int(tag)
            i += n + 2
        elif s == "$Entities":
            np_, nc = [int(x) for x in lines[i + 1].split()[:2]]
            for k in range(nc):
                t = lines[i + 2 + np_ + k].split()
                nphys = int(t[7])
                curve_phys[int(t[0])] = [int(x) for x in t[8:8 + nphys]]
            i += 1
        elif s == "$Nodes":
            nb = int(lines[i + 1].split()[0])
            j = i + 2
            for _ in range(nb):
                _, _, _, n = [int(x) for x in lines[j].split()]
                tags = [int(lines[j + 1 + k]) for k in range(n)]
                for k in range(n):
                    x, y = [float(v) for v in lines[j + 1 + n + k].split()[:2]]
                    nodes[tags[k]] = (x, y)
                j += 1 + 2 * n
            i = j
        elif s == "$Elements":
            nb = int(lines[i + 1].split()[0])
            j = i + 2
            for _ in range(nb):
                dim, ent, _, n = [int(x) for x in lines[j].split()]
                if dim == 1:
                    for k in range(n):
                        lines_of.setdefault(ent, []).extend(int(v) for v in lines[j + 1 + k].split()[1:])
                j += 1 + n
            i = j
        else:
            i += 1
    return names, curve_phys, nodes, lines_of


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh")
    ap.add_argument("--group", required=True)
    ap.add_argument("--circle", nargs=3, type=float, required=True, metavar=("CX", "CY", "R"))
    ap.add_argument("--max", type=float)
    ap.add_argument("--allow-off", type=int, default=0)
    a = ap.parse_args()
    names, curve_phys, nodes, lines_of = read(a.mesh)
    if a.group not in names:
        sys.exit(f"{a.mesh}: no physical curve '{a.group}' (curves: {', '.join(sorted(names))})")
    tag = names[a.group]
    ids = set()
    for ent, phys in curve_phys.items():
        if tag in phys:
            ids.update(lines_of.get(ent, []))
    cx, cy, r = a.circle
    dist = [abs(math.hypot(nodes[v][0] - cx, nodes[v][1] - cy) - r) for v in ids]
    out = {"nodes": len(ids), "max_distance": max(dist, default=0.0)}
    if a.max is not None:
        out["off"] = sum(d > a.max for d in dist)
    print(json.dumps(out))
    if a.max is not None and (not ids or out["off"] > a.allow_off):
        sys.exit(1)


if __name__ == "__main__":
    main()
