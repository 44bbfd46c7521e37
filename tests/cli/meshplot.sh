#!/usr/bin/env bash
# meshplot CLI: edges, scalar field with --log10, frame glyphs, window, PNG, and bad input.
set -euo pipefail
SRC="${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}"
BIN="${QUADAPT_BIN_DIR:-$SRC/build/bin}"
export PATH="$BIN:$PATH"
command -v meshplot >/dev/null || { echo "FAIL: meshplot not built (tools must be on PATH)" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "SKIPPED: gmsh (the program) not installed"; exit 77; }
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
T="$(mktemp -d)"; trap 'rm -rf "$T"' EXIT
cd "$T"
fail() { echo "FAIL: $*" >&2; exit 1; }

gmsh -2 -format msh41 -setnumber N 8 -o sq.msh "$SRC/examples/geometry/unit_square.geo" >/dev/null 2>&1 || fail "gmsh could not mesh the square"

# Append two $ElementData views: dwr = 10^-(1 + 7 x_c) (known log10 range) and a frame Vinv
# with V = R(30 deg) diag(0.01, 0.05) in every cell.
"$PY" - <<'PYEOF'
import math
lines = open("sq.msh").read().split("\n")
nodes, quads = {}, []
i = lines.index("$Nodes") + 1
nb, _, _, _ = map(int, lines[i].split()); i += 1
for _ in range(nb):
    _, _, _, n = map(int, lines[i].split()); i += 1
    tags = [int(lines[i + k]) for k in range(n)]
    for k in range(n):
        x, y, _ = map(float, lines[i + n + k].split())
        nodes[tags[k]] = (x, y)
    i += 2 * n
i = lines.index("$Elements") + 1
nb, _, _, _ = map(int, lines[i].split()); i += 1
for _ in range(nb):
    _, _, et, n = map(int, lines[i].split()); i += 1
    for k in range(n):
        t = list(map(int, lines[i + k].split()))
        if et == 3:
            quads.append((t[0], t[1:]))
    i += n
th, h1, h2 = math.radians(30), 0.01, 0.05
c, s = math.cos(th), math.sin(th)
# M = V^-1 = diag(1/h1, 1/h2) R(-th)
M = [[c / h1, s / h1], [-s / h2, c / h2]]
out = ["$ElementData", "1", '"dwr"', "1", "0", "3", "0", "1", str(len(quads))]
for tag, vs in quads:
    xc = sum(nodes[v][0] for v in vs) / 4
    out.append("%d %.17g" % (tag, 10 ** (-(1 + 7 * xc))))
out += ["$EndElementData", "$ElementData", "1", '"Vinv"', "1", "0", "3", "0", "9", str(len(quads))]
for tag, _ in quads:
    out.append("%d %.17g %.17g 0 %.17g %.17g 0 0 0 1" % (tag, M[0][0], M[0][1], M[1][0], M[1][1]))
out += ["$EndElementData", "$FrameConvention", "quadapt", "$EndFrameConvention"]
open("f.msh", "w").write("\n".join(lines).rstrip("\n") + "\n" + "\n".join(out) + "\n")
PYEOF

# 1. edges only, SVG: well-formed XML, report beside the picture (not over a mesh report)
meshplot sq.msh -o edges.svg -q || fail "meshplot edges"
"$PY" -c "import xml.dom.minidom,sys; xml.dom.minidom.parse('edges.svg')" || fail "edges.svg is not XML"
[ -s edges.svg.json ] || fail "no report edges.svg.json"
"$PY" - <<'PYEOF' || fail "edges report"
import json; r = json.load(open("edges.svg.json"))
assert r["cells"] == 64 and r["cells_drawn"] == 64 and r["field_kind"] == "none", r
PYEOF

# 2. scalar field with --log10: colour range = log10 of the data range, and a colour bar label
meshplot f.msh --field dwr --log10 -o dwr.svg -q || fail "meshplot --field dwr --log10"
grep -q "log10 |dwr|" dwr.svg || fail "no colour-bar label"
"$PY" - <<'PYEOF' || fail "dwr report"
import json; r = json.load(open("dwr.svg.json"))
lo, hi = r["data_range"]
# cell centres x_c = 1/16 ... 15/16 -> log10 dwr = -(1 + 7 x_c)
assert abs(lo - (-(1 + 7 * 15 / 16))) < 1e-9 and abs(hi - (-(1 + 7 / 16))) < 1e-9, (lo, hi)
assert r["field_kind"] == "cell" and r["polygons"] == 64
PYEOF

# 3. the frame as crosses (one glyph per cell), parallelograms in a close-up, PNG output
meshplot f.msh --field Vinv -o frame.svg -q || fail "meshplot --field Vinv"
"$PY" -c "import json; r=json.load(open('frame.svg.json')); assert r['glyphs']==64 and r['field_kind']=='frame', r" \
  || fail "frame report"
if command -v rsvg-convert >/dev/null; then
  meshplot f.msh --field Vinv --glyph parallelogram --window 0,0.5,0.5,1 -o close.png -q || fail "PNG close-up"
  [ "$(head -c 8 close.png | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "close.png is not a PNG"
  "$PY" -c "import json; r=json.load(open('close.png.json')); assert r['glyphs']==16, r" || fail "close-up glyph count"
else
  echo "note: rsvg-convert missing, PNG part skipped"
fi

# a window off the mesh: the picture is empty, and said so (was "wrote x.svg (0 cells)" only)
meshplot sq.msh --window 5,6,5,6 -o off.svg 2>off.txt || fail "window off the mesh: exit $?"
grep -q "warning: --window 5,6,5,6 holds none of sq.msh's cells: off.svg is empty" off.txt || { cat off.txt >&2; fail "no empty-window warning"; }
meshplot sq.msh --window 0,0.5,0,0.5 -o on.svg 2>on.txt
! grep -q "holds none" on.txt || fail "empty-window warning on a window inside the mesh"

# 4. bad input: one-line message naming the file and the problem, exit 2, nothing written
expect_fail() {  # expect_fail PATTERN ARGS...
  local pat="$1"; shift
  local rc=0
  meshplot "$@" 2>err.txt >/dev/null || rc=$?
  [ $rc -eq 2 ] || fail "meshplot $* exited $rc, expected 2"
  grep -q -- "$pat" err.txt || { cat err.txt >&2; fail "message for '$*' lacks '$pat'"; }
}
expect_fail "no field 'nope' (available: dwr, Vinv)" f.msh --field nope -o bad1.svg
expect_fail "unknown picture format '.jpg'" sq.msh -o bad2.jpg
expect_fail "need x0 < x1" sq.msh --window 1,0,0,1 -o bad3.svg
expect_fail "unknown glyph" f.msh --field Vinv --glyph arrow -o bad4.svg
printf '$MeshFormat\n4.1 0 8\n' > broken.msh
expect_fail "broken.msh" broken.msh -o bad5.svg
# colour options without colours are refused (they were ignored, exit 0: a new-user review)
expect_fail "--log10 colours a scalar field or the DG solution; --field Vinv is a frame, drawn as glyphs" \
  f.msh --field Vinv --log10 -o bad6.svg
expect_fail "--range colours a scalar field or the DG solution; give --field NAME" sq.msh --range 0,1 -o bad7.svg
for f in bad1.svg bad2.jpg bad3.svg bad4.svg bad5.svg bad6.svg bad7.svg; do [ ! -e "$f" ] || fail "$f written despite the error"; done
# --title '' is documented as "no title" (it was refused as an empty value: a docs audit)
meshplot -q sq.msh --title '' -o notitle.svg || fail "--title '' refused"
meshplot -q sq.msh -o titled.svg
grep -q '<text' titled.svg || fail "the default picture has no title text"
[ "$(grep -c '<text' notitle.svg)" -lt "$(grep -c '<text' titled.svg)" ] || fail "--title '' still drew a title"
echo "meshplot CLI: all checks passed"
