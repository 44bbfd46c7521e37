#!/usr/bin/env bash
# Cells in messages are numbered alike by every tool (issue #16 item 6; docs/exit-codes.md
# "Messages"): from 1 in file order, which is the element tag in files quadapt writes, with the
# centroid as "(centroid (x, y))". lpcvt, bamgquad, quadsmooth, meshquality (frame reader) and
# meshplot (frame glyphs) numbered from 0, size-solve too; meshplot's message named no file.
# Each bad cell here is tag 7 of a 4 x 4 grid (rows from the bottom): centroid (0.625, 0.375).
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
WANT="cell 7 (centroid (0.625, 0.375))"
has_cell() { case "$ERR" in *"$WANT"*) ;; *) fail "$1: message does not say '$WANT': $ERR" ;; esac; }

# --- a frame that is singular in cell 7: every tool that reads a frame
python3 "$S/tests/cli/lpcvt_frame.py" f.msh --n 4 --corrupt singular --corrupt-cell 7
python3 "$S/tests/golden/refine/make_square.py" 4 sq.msh
for cmd in "lpcvt f.msh -o t.msh" "bamgquad f.msh -o q.msh" "quadsmooth sq.msh --frame f.msh -o s.msh" \
           "meshquality sq.msh --frame f.msh --report r.json" "meshplot f.msh --field Vinv -o p.svg"; do
  expect_exit 2 "f.msh: " $cmd -q
  has_cell "${cmd%% *}"
done
# the determinant in %.3e (it printed as 0.000000)
expect_exit 2 "f.msh: " lpcvt f.msh -o t.msh -q
case "$ERR" in *"det M = "*e[-+]*) ;; *) fail "det not in %.3e: $ERR" ;; esac

# --- size-solve: a shape file (our writer: tags 1..16) whose B is negative in cell 7
dgsolve -q sq.msh -c "$E/cases/smooth.json" -p 1 -o sol.msh
estimate-frame -q sol.msh -o shape.msh
python3 - shape.msh badB.msh <<'PY'
import sys
t = open(sys.argv[1]).read()
i = t.index('"B"', t.index("$ElementData")); j = t.index("\n7 ", i); k = t.index("\n", j + 1)
open(sys.argv[2], "w").write(t[:j + 1] + "7 -1" + t[k:])
PY
if cmp -s shape.msh badB.msh; then fail "badB.msh did not change"; fi
expect_exit 2 "badB.msh: " size-solve badB.msh --complexity 100 -o z.msh -q
has_cell size-solve

# --- the mesh validator (every tool's reader) says the same for an inverted 7th cell (nodes 8 9
# 14 13; make_square.py writes the boundary lines first, so its tag is 23: numbers are file order)
sed -E 's/^([0-9]+) 8 9 14 13$/\1 8 13 14 9/' sq.msh > inv.msh
if cmp -s sq.msh inv.msh; then fail "inv.msh did not change"; fi
expect_exit 2 "inv.msh: " meshconvert inv.msh -o c.msh
has_cell meshconvert

for f in t.msh q.msh s.msh r.json p.svg z.msh c.msh; do
  if [ -e "$f" ]; then fail "$f written"; fi
done
echo "ok: cells numbered from 1 with their centroid in every tool's message"
