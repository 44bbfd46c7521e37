# Writes a test input for the refine CLI tests (MSH 4.1 ASCII, no dependency on our tools):
# the unit square as N x N quads (or 2 N^2 triangles with "tri"), boundary groups
# bottom/right/top/left, and two cell fields: B (1 component, 1/(0.05 + |x - y|) at the cell
# centroid, so cells on the diagonal are the largest) and Vinv (9 components).
# usage: make_square.py N OUT.msh [tri] [bare]    (bare: no fields)
import sys
n = int(sys.argv[1]); out = sys.argv[2]; tri = "tri" in sys.argv[3:]; bare = "bare" in sys.argv[3:]
nid = lambda i, j: j * (n + 1) + i + 1
nodes = [(nid(i, j), i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
cells = []
for j in range(n):
    for i in range(n):
        a, b, c, d = nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)
        cells += [(a, b, c), (a, c, d)] if tri else [(a, b, c, d)]
sides = [[(nid(i, 0), nid(i + 1, 0)) for i in range(n)],
         [(nid(n, j), nid(n, j + 1)) for j in range(n)],
         [(nid(i, n), nid(i - 1, n)) for i in range(n, 0, -1)],
         [(nid(0, j), nid(0, j - 1)) for j in range(n, 0, -1)]]
names = ["bottom", "right", "top", "left"]
L = []
L += ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", "5"]
L += ['1 %d "%s"' % (k + 1, names[k]) for k in range(4)] + ['2 5 "domain"', "$EndPhysicalNames"]
L += ["$Entities", "0 4 1 0"]
for k in range(4):
    L.append("%d 0 0 0 1 1 0 1 %d 0" % (k + 1, k + 1))
L += ["1 0 0 0 1 1 0 1 5 4 1 2 3 4", "$EndEntities"]
L += ["$Nodes", "1 %d 1 %d" % (len(nodes), len(nodes)), "2 1 0 %d" % len(nodes)]
L += [str(t) for t, _, _ in nodes] + ["%.17g %.17g 0" % (x, y) for _, x, y in nodes] + ["$EndNodes"]
nb = sum(len(s) for s in sides)
L += ["$Elements", "5 %d 1 %d" % (nb + len(cells), nb + len(cells))]
tag = 1
for k in range(4):
    L.append("1 %d 1 %d" % (k + 1, len(sides[k])))
    for a, b in sides[k]:
        L.append("%d %d %d" % (tag, a, b)); tag += 1
first = tag
L.append("2 1 %d %d" % (2 if tri else 3, len(cells)))
for c in cells:
    L.append(" ".join(map(str, (tag,) + c))); tag += 1
L.append("$EndElements")
def centroid(c):
    xs = [nodes[v - 1][1] for v in c]; ys = [nodes[v - 1][2] for v in c]
    return sum(xs) / len(xs), sum(ys) / len(ys)
def view(name, vals):
    nc = len(vals[0])
    return ["$ElementData", "1", '"%s"' % name, "1", "0", "3", "0", str(nc), str(len(vals))] + \
        ["%d %s" % (first + k, " ".join("%.17g" % x for x in v)) for k, v in enumerate(vals)] + ["$EndElementData"]
B = []
for c in cells:
    x, y = centroid(c)
    B.append((1.0 / (0.05 + abs(x - y)),))
if not bare:
    L += view("B", B)
    L += view("Vinv", [(1, 0, 0, 0, 1, 0, 0, 0, 0)] * len(cells))
open(out, "w").write("\n".join(L) + "\n")
