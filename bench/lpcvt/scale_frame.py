#!/usr/bin/python3
"""scale_frame.py IN.msh OUT.msh (--factor S | --cells N): writes the frame with M = V^-1 scaled
uniformly, M -> S M (so the final all-quad cell count, sum area |det M| / 4 in the quadapt
convention, scales by S^2). --cells N chooses S so that the count is N. Everything else of the
file is copied as it is."""
import argparse
import math


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("inp")
    ap.add_argument("out")
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--factor", type=float)
    g.add_argument("--cells", type=float)
    a = ap.parse_args()
    lines = open(a.inp).read().split("\n")
    # nodes and quads for the areas (MSH 4.1 ASCII, as PHiLiP and quadapt write them)
    nodes, cells, i = {}, {}, 0
    while i < len(lines):
        if lines[i] == "$Nodes":
            nb = int(lines[i + 1].split()[0]); i += 2
            for _ in range(nb):
                k = int(lines[i].split()[3]); i += 1
                tags = [int(lines[i + j]) for j in range(k)]; i += k
                for j in range(k):
                    x = lines[i + j].split(); nodes[tags[j]] = (float(x[0]), float(x[1]))
                i += k
        elif lines[i] == "$Elements":
            nb = int(lines[i + 1].split()[0]); i += 2
            for _ in range(nb):
                dim, _, typ, k = map(int, lines[i].split()); i += 1
                for j in range(k):
                    x = list(map(int, lines[i + j].split()))
                    if dim == 2: cells[x[0]] = x[1:]
                i += k
        else:
            i += 1
    def area(vs):
        p = [nodes[v] for v in vs]
        return 0.5 * sum(p[k][0] * p[(k + 1) % len(p)][1] - p[(k + 1) % len(p)][0] * p[k][1] for k in range(len(p)))
    out, i, total = [], 0, 0.0
    blocks = []
    while i < len(lines):
        out.append(lines[i])
        if lines[i] == "$ElementData" and lines[i + 2].strip() == '"Vinv"':
            j = i + 1
            ns = int(lines[j]); j += 1 + ns
            nr = int(lines[j]); j += 1 + nr
            ni = int(lines[j]); n = int(lines[j + 3]); j += 1 + ni
            out.extend(lines[i + 1:j])
            blocks.append((len(out), j, n))
            for k in range(n):
                x = lines[j + k].split()
                m = [float(t) for t in x[1:]]
                total += area(cells[int(x[0])]) * abs(m[0] * m[4] - m[1] * m[3])
                out.append(lines[j + k])
            i = j + n
            continue
        i += 1
    # cells per unit |det M|: 1/4 for quadapt's files ($FrameConvention quadapt), 1 for PHiLiP's (no section)
    per = 0.25 if "$FrameConvention" in lines and lines[lines.index("$FrameConvention") + 1].strip() == "quadapt" else 1.0
    s = a.factor if a.factor else math.sqrt(a.cells / (total * per))
    for start, _, n in blocks:
        for k in range(n):
            x = out[start + k].split()
            m = [float(t) for t in x[1:]]
            for c in (0, 1, 3, 4):
                m[c] *= s
            out[start + k] = x[0] + " " + " ".join(repr(v) for v in m)
    open(a.out, "w").write("\n".join(out))
    print(f"factor {s!r}: cells {total / 4!r} -> {s * s * total / 4!r}")


if __name__ == "__main__":
    main()
