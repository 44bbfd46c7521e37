#!/usr/bin/env python3
"""Compare a result with a stored golden file, numbers within an absolute + relative tolerance.

usage: golden_compare.py RESULT GOLDEN [--rtol R] [--atol A] [--ignore KEY]... [--keep KEY]...
                                       [--format json|msh]

JSON (reports): compared recursively. Objects must have the same keys, arrays the same length,
strings / booleans / null must be equal, numbers a and b must satisfy
    |a - b| <= atol + rtol * |b|          (b from GOLDEN; defaults rtol = 1e-9, atol = 1e-12).
Keys that are provenance, not results, are ignored at any depth by default:
    timings peak_memory_mb command version threads inputs outputs options provenance
--ignore KEY (repeatable) adds a key (a plain name, matched at any depth, or a dotted path such as
frame.file); --keep KEY compares a default-ignored key after all.

MSH (Gmsh MSH 4.1 or 2.2, ASCII): compares the physical names, the node coordinates (in file
order), the elements of each type (connectivity by node position, in file order) and every
$ElementData / $ElementNodeData view (by name; values per element in element order), numbers
with the same tolerance. Binary files are not supported here (convert them with meshconvert).

The format is taken from --format, else from the extension (.msh -> msh, else json).
Exit status: 0 equal within tolerance, 1 different (the differences are listed on stdout, at
most 30), 2 usage or read error. Python 3 standard library only.
"""
import argparse
import json
import math
import os
import sys

DEFAULT_IGNORED = ["timings", "peak_memory_mb", "command", "version", "threads", "inputs", "outputs", "options",
                   "provenance"]


class Comparer:
    def __init__(self, rtol, atol, ignored):
        self.rtol, self.atol, self.ignored = rtol, atol, set(ignored)
        self.diffs = []

    def diff(self, path, msg):
        self.diffs.append(f"{path or '(root)'}: {msg}")

    def number(self, path, a, b):
        if isinstance(a, bool) or isinstance(b, bool):
            if a is not b:
                self.diff(path, f"{a!r} != {b!r}")
            return
        if math.isnan(a) and math.isnan(b):
            return
        if not (abs(a - b) <= self.atol + self.rtol * abs(b)):
            self.diff(path, f"{a!r} != {b!r} (|diff| {abs(a - b):.3g} > atol {self.atol:g} + rtol {self.rtol:g} * |golden|)")

    def json(self, a, b, path=""):
        num = (int, float)
        if isinstance(a, dict) and isinstance(b, dict):
            keys = [k for k in sorted(set(a) | set(b)) if k not in self.ignored and self.join(path, k) not in self.ignored]
            for k in keys:
                p = self.join(path, k)
                if k not in a:
                    self.diff(p, "missing in the result")
                elif k not in b:
                    self.diff(p, "not in the golden file")
                else:
                    self.json(a[k], b[k], p)
        elif isinstance(a, list) and isinstance(b, list):
            if len(a) != len(b):
                self.diff(path, f"{len(a)} entries != {len(b)}")
            for i, (x, y) in enumerate(zip(a, b)):
                self.json(x, y, f"{path}[{i}]")
        elif isinstance(a, num) and isinstance(b, num) and not isinstance(a, bool) and not isinstance(b, bool):
            self.number(path, float(a), float(b))
        elif a != b or type(a) != type(b):
            self.diff(path, f"{a!r} != {b!r}")

    @staticmethod
    def join(path, key):
        return f"{path}.{key}" if path else str(key)


def read_msh(path):
    """Minimal ASCII MSH 4.1 / 2.2 reader: names, nodes, elements by type, element views."""
    with open(path, "r", encoding="utf-8", errors="replace") as f:
        lines = f.read().split("\n")
    out = {"names": [], "nodes": [], "elements": {}, "views": {}}
    node_pos, elem_pos = {}, {}
    i, version = 0, None

    def tokens_until(end):
        nonlocal i
        toks = []
        while i < len(lines) and lines[i].strip() != end:
            toks.extend(lines[i].split())
            i += 1
        if i >= len(lines):
            raise ValueError(f"{path}: no {end}")
        i += 1
        return toks

    nper = {1: 2, 2: 3, 3: 4, 15: 1, 4: 4, 5: 8, 8: 3, 9: 6, 10: 9, 26: 4, 27: 5, 36: 16, 37: 25}
    while i < len(lines):
        line = lines[i].strip()
        i += 1
        if not line.startswith("$") or line.startswith("$End"):
            continue
        name = line[1:]
        if name == "MeshFormat":
            t = tokens_until("$EndMeshFormat")
            version = t[0]
            if t[1] != "0":
                raise ValueError(f"{path}: binary MSH is not supported by golden_compare.py")
        elif name == "PhysicalNames":
            n = int(lines[i])
            for k in range(n):
                d, tag, rest = lines[i + 1 + k].split(None, 2)
                out["names"].append((int(d), int(tag), rest.strip().strip('"')))
            i += n + 1
            tokens_until("$EndPhysicalNames")
        elif name == "Nodes":
            t = tokens_until("$EndNodes")
            if version.startswith("4"):
                nb, p = int(t[0]), 4
                for _ in range(nb):
                    dim, par, n = int(t[p]), int(t[p + 2]), int(t[p + 3])
                    p += 4
                    tags = t[p:p + n]
                    p += n
                    w = 3 + (dim if par else 0)
                    for k in range(n):
                        node_pos[tags[k]] = len(out["nodes"])
                        out["nodes"].append([float(x) for x in t[p + w * k:p + w * k + 3]])
                    p += w * n
            else:
                n = int(t[0])
                for k in range(n):
                    node_pos[t[1 + 4 * k]] = len(out["nodes"])
                    out["nodes"].append([float(x) for x in t[2 + 4 * k:5 + 4 * k]])
        elif name == "Elements":
            t = tokens_until("$EndElements")

            def add(etype, etag, nodes):
                lst = out["elements"].setdefault(etype, [])
                elem_pos[etag] = (etype, len(lst))
                lst.append([node_pos[x] for x in nodes])

            if version.startswith("4"):
                nb, p = int(t[0]), 4
                for _ in range(nb):
                    etype, n = int(t[p + 2]), int(t[p + 3])
                    p += 4
                    m = nper[etype]
                    for k in range(n):
                        add(etype, t[p], t[p + 1:p + 1 + m])
                        p += 1 + m
            else:
                n, p = int(t[0]), 1
                for _ in range(n):
                    etag, etype, ntags = t[p], int(t[p + 1]), int(t[p + 2])
                    m = nper[etype]
                    add(etype, etag, t[p + 3 + ntags:p + 3 + ntags + m])
                    p += 3 + ntags + m
        elif name in ("ElementData", "ElementNodeData"):
            ns = int(lines[i])
            vname = lines[i + 1].strip().strip('"')
            i += 1 + ns
            t = tokens_until(f"$End{name}")
            nr = int(t[0])
            p = 1 + nr
            ni = int(t[p])
            ints = [int(x) for x in t[p + 1:p + 1 + ni]]
            p += 1 + ni
            ncomp, nent = ints[1], ints[2]
            view = {}
            for _ in range(nent):
                etag = t[p]
                p += 1
                mult = 1
                if name == "ElementNodeData":
                    mult = int(t[p])
                    p += 1
                view[elem_pos.get(etag, etag)] = [float(x) for x in t[p:p + mult * ncomp]]
                p += mult * ncomp
            out["views"][vname] = {"kind": name, "ncomp": ncomp, "values": view}
    return out


def compare_msh(c, a, b):
    if sorted(a["names"]) != sorted(b["names"]):
        c.diff("PhysicalNames", f"{sorted(a['names'])} != {sorted(b['names'])}")
    if len(a["nodes"]) != len(b["nodes"]):
        c.diff("Nodes", f"{len(a['nodes'])} nodes != {len(b['nodes'])}")
    else:
        for k, (p, q) in enumerate(zip(a["nodes"], b["nodes"])):
            for d in range(3):
                c.number(f"node {k + 1} coordinate {d}", p[d], q[d])
    for t in sorted(set(a["elements"]) | set(b["elements"])):
        ea, eb = a["elements"].get(t, []), b["elements"].get(t, [])
        if len(ea) != len(eb):
            c.diff(f"elements of type {t}", f"{len(ea)} != {len(eb)}")
        elif ea != eb:
            k = next(k for k in range(len(ea)) if ea[k] != eb[k])
            c.diff(f"element {k + 1} of type {t}", f"nodes {ea[k]} != {eb[k]}")
    for v in sorted(set(a["views"]) | set(b["views"])):
        if v not in a["views"] or v not in b["views"]:
            c.diff(f"view '{v}'", "missing in the result" if v not in a["views"] else "not in the golden file")
            continue
        va, vb = a["views"][v], b["views"][v]
        if (va["kind"], va["ncomp"]) != (vb["kind"], vb["ncomp"]) or set(va["values"]) != set(vb["values"]):
            c.diff(f"view '{v}'", "different kind, components or elements")
            continue
        for e in sorted(va["values"], key=str):
            x, y = va["values"][e], vb["values"][e]
            where = f"view '{v}' element {e[1] + 1} (type {e[0]})" if isinstance(e, tuple) else f"view '{v}' element tag {e}"
            if len(x) != len(y):
                c.diff(where, f"{len(x)} values != {len(y)}")
                continue
            for k, (p, q) in enumerate(zip(x, y)):
                c.number(f"{where} value {k}", p, q)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n", 2)[2],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result", help="the file produced by the test")
    ap.add_argument("golden", help="the stored golden file")
    ap.add_argument("--rtol", type=float, default=1e-9, help="relative tolerance (default 1e-9)")
    ap.add_argument("--atol", type=float, default=1e-12, help="absolute tolerance (default 1e-12)")
    ap.add_argument("--ignore", action="append", default=[], metavar="KEY", help="also ignore KEY (repeatable)")
    ap.add_argument("--keep", action="append", default=[], metavar="KEY", help="compare a default-ignored KEY (repeatable)")
    ap.add_argument("--format", choices=["json", "msh"])
    args = ap.parse_args()
    fmt = args.format or ("msh" if args.golden.endswith(".msh") else "json")
    ignored = [k for k in DEFAULT_IGNORED if k not in args.keep] + args.ignore
    c = Comparer(args.rtol, args.atol, ignored)
    try:
        if fmt == "json":
            with open(args.result) as f:
                a = json.load(f)
            with open(args.golden) as f:
                b = json.load(f)
            c.json(a, b)
        else:
            compare_msh(c, read_msh(args.result), read_msh(args.golden))
    except (OSError, ValueError, KeyError, IndexError) as e:
        print(f"golden_compare.py: cannot compare {args.result} with {args.golden}: {e}", file=sys.stderr)
        return 2
    if c.diffs:
        print(f"{args.result} differs from {os.path.basename(args.golden)} ({len(c.diffs)} differences):")
        for d in c.diffs[:30]:
            print("  " + d)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
