#!/usr/bin/env bash
# A frame that spans the domain (docs/lpcvt.md): the unit square, a constant frame at 0 degrees,
# stretch 20, h1 = 0.2, so 1 / (2 h1) = 2.5 cells across along the long axis. lpcvt warns (its
# frame_span is 2.5, below kMinCellsAcross = 4) and puts an interior point on the line between two
# wall points, to ~1e-12. recombine paired the two triangles at that point into a quad with a
# 180-degree corner (sine 3e-12, which passed its "strictly convex" test) and exited 0 with a mesh
# that meshquality and quadsmooth then refused ("degenerate: zero Jacobian at corner 1 (0.5, 0.38)
# (vertices in line)"; --n 8) or just accepted (scaled Jacobian 3e-12; --n 16). Now no pair has a
# corner straight up to rounding (kMinPairSine, lib/quad/metric_matching.hpp), and recombine
# never writes a cell that validate_mesh refuses (it fails with exit 2 instead).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
for t in lpcvt recombine quadsmooth meshquality; do
  command -v $t >/dev/null || { echo "FAIL: $t not built (tools must be on PATH)" >&2; exit 1; }
done
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

for n in 8 16; do
  F="$T/frame$n.msh"
  python3 "$HERE/lpcvt_frame.py" "$F" --n $n --h1 0.2 --h2 0.01 --theta 0
  lpcvt "$F" -o "$T/tri$n.msh" 2> "$T/lpcvt$n.err" || fail "lpcvt --n $n: $(cat "$T/lpcvt$n.err")"
  # the warning fires, with the figure 1 / (2 h1) = 2.5
  grep -q "warning: $F: the frame asks for only 2.500e+00 cells across" "$T/lpcvt$n.err" ||
    fail "lpcvt --n $n: no frame_span warning: $(cat "$T/lpcvt$n.err")"
  python3 - "$T/tri$n.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["frame_span"]
if not (abs(s["cells_across_long_axis"] - 2.5) < 1e-9 and s["warning"]):
    sys.exit("FAIL: frame_span %s" % s)
PY
  # the trap is there: two adjacent triangles whose quad has a corner straight to rounding
  python3 - "$T/tri$n.msh" <<'PY'
import math, sys
from itertools import combinations
L = open(sys.argv[1]).read().split("\n")
i = L.index("$Nodes"); j = i + 2; P = {}
while L[j] != "$EndNodes":
    n = int(L[j].split()[3]); tags = [int(t) for t in L[j + 1:j + 1 + n]]
    for k, t in enumerate(tags): P[t] = tuple(map(float, L[j + 1 + n + k].split()[:2]))
    j += 1 + 2 * n
i = L.index("$Elements"); j = i + 2; tris = []
for _ in range(int(L[i + 1].split()[0])):
    h = L[j].split(); n = int(h[3])
    if h[2] == "2": tris += [list(map(int, l.split()[1:])) for l in L[j + 1:j + 1 + n]]
    j += 1 + n
edges = {}
for t, c in enumerate(tris):
    for k in range(3): edges.setdefault(frozenset((c[k], c[(k + 1) % 3])), []).append(t)
smallest = 1
for e, ts in edges.items():
    if len(ts) != 2: continue
    for a in e:  # the corner at a shared-edge end: the two opposite vertices and a in line?
        o = [next(v for v in tris[t] if v not in e) for t in ts]
        u = [P[o[0]][0] - P[a][0], P[o[0]][1] - P[a][1]]; v = [P[o[1]][0] - P[a][0], P[o[1]][1] - P[a][1]]
        sine = abs(u[0] * v[1] - u[1] * v[0]) / math.hypot(*u) / math.hypot(*v)
        if u[0] * v[0] + u[1] * v[1] < 0 and sine > 0: smallest = min(smallest, sine)
# (a sine of exactly 0 was always refused)
if not smallest < 1e-9:
    sys.exit("FAIL: no pair of triangles with a corner straight to rounding (smallest sine above 0: %.3e): "
             "the test no longer tests it" % smallest)
print("a candidate pair's corner is straight to %.1e" % smallest)
PY
  recombine -q "$T/tri$n.msh" -o "$T/quad$n.msh" || fail "recombine --n $n: exit $?"
  recombine -q --no-split "$T/tri$n.msh" -o "$T/pairs$n.msh" || fail "recombine --no-split --n $n: exit $?"
  for m in quad pairs; do
    meshquality -q "$T/$m$n.msh" > "$T/$m$n.quality.json" 2> "$T/$m$n.err" ||
      fail "meshquality refuses recombine's $m$n.msh: $(cat "$T/$m$n.err")"
    python3 - "$T/$m$n.quality.json" "$m$n" <<'PY'
import json, sys
sj = json.load(open(sys.argv[1]))["physical"]["scaled_jacobian_min"]
if not sj > 1e-6:
    sys.exit("FAIL: %s: a corner straight to rounding (smallest scaled Jacobian %.3e)" % (sys.argv[2], sj))
print("%s: smallest scaled Jacobian %.3e" % (sys.argv[2], sj))
PY
  done
  quadsmooth -q "$T/quad$n.msh" --frame "$F" -o "$T/mesh$n.msh" || fail "quadsmooth --n $n: exit $?"
  meshquality -q "$T/mesh$n.msh" --frame "$F" > /dev/null || fail "meshquality --frame refuses mesh$n.msh"
done
echo "recombine_spanning_frame: ok"
