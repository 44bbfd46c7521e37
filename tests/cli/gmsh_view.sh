#!/usr/bin/env bash
# FILE.msh.opt (lib/io/gmsh_options.hpp): tools that write the DG solution u write it beside the
# file, and Gmsh itself picks it up when it opens FILE.msh (AdaptVisualizationGrid = 1, so u is
# drawn smoothly instead of one colour gradient per cell); files without u get none, and a stale
# one written by quadapt is removed.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cp "$S/examples/meshes/square16.msh" "$T/sq.msh"
dgsolve -q "$T/sq.msh" -c "$S/examples/cases/smooth.json" -p 3 -o "$T/sol.msh"
[ -s "$T/sol.msh.opt" ] || fail "dgsolve wrote no sol.msh.opt"
grep -q '^View\[PostProcessing.NbViews - 1\].AdaptVisualizationGrid = 1;$' "$T/sol.msh.opt" || fail "no AdaptVisualizationGrid"
# Gmsh reads FILE.opt by itself on open (batch mode '-': parse the files, then exit)
printf 'Printf("adapt=%%g level=%%g", View[0].AdaptVisualizationGrid, View[0].MaxRecursionLevel);\n' > "$T/chk.geo"
out=$(cd "$T" && gmsh sol.msh chk.geo - 2>&1)
grep -q 'adapt=1 level=3' <<<"$out" || fail "Gmsh did not apply sol.msh.opt: $(echo "$out" | grep adapt)"
# two solutions opened together (p = 3, then p = 2): each file's options reach its own view (with
# View[0] in both, the second file's set the first view and left its own blocky)
dgsolve -q "$T/sq.msh" -c "$S/examples/cases/smooth.json" -p 2 -o "$T/sol2.msh"
printf 'Printf("v0 adapt=%%g level=%%g", View[0].AdaptVisualizationGrid, View[0].MaxRecursionLevel);\nPrintf("v1 adapt=%%g level=%%g", View[1].AdaptVisualizationGrid, View[1].MaxRecursionLevel);\n' > "$T/chk2.geo"
out=$(cd "$T" && gmsh sol.msh sol2.msh chk2.geo - 2>&1)
grep -q 'v0 adapt=1 level=3' <<<"$out" && grep -q 'v1 adapt=1 level=2' <<<"$out" ||
  fail "two files opened together: $(echo "$out" | grep adapt)"
# without the file Gmsh's default is blocky (0): the check above can fail
mv "$T/sol.msh.opt" "$T/keep.opt"
out=$(cd "$T" && gmsh sol.msh chk.geo - 2>&1)
grep -q 'adapt=0' <<<"$out" || fail "Gmsh's default changed: $(echo "$out" | grep adapt)"
mv "$T/keep.opt" "$T/sol.msh.opt"
# the other tools that keep u (meshconvert, adjoint) write one too; a mesh without u gets none
meshconvert -q "$T/sol.msh" -o "$T/copy.msh"
[ -s "$T/copy.msh.opt" ] || fail "meshconvert of a solution wrote no .opt"
meshconvert -q "$T/sq.msh" -o "$T/plain.msh"
[ ! -e "$T/plain.msh.opt" ] || fail "a mesh without u got a .opt"
# a stale .opt of ours goes when the file is rewritten without u; someone else's stays
meshconvert -q "$T/sq.msh" -o "$T/copy.msh"
[ ! -e "$T/copy.msh.opt" ] || fail "stale copy.msh.opt kept"
echo 'General.Axes = 1;' > "$T/plain.msh.opt"
meshconvert -q "$T/sq.msh" -o "$T/plain.msh"
grep -q 'General.Axes' "$T/plain.msh.opt" || fail "a user's .opt was removed"
# many cells: the recursion level is capped (cells * 4^L <= 4e6)
python3 - "$T/sol.msh.opt" <<'PY'
import sys
t = open(sys.argv[1]).read()
assert "MaxRecursionLevel = 3;" in t and "TargetError = -1;" in t, t
PY
echo "gmsh_view: ok"
