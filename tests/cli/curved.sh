#!/usr/bin/env bash
# Curved domains (docs/curved.md): Gmsh's curved quads through meshconvert, dgsolve, meshquality
# and estimate-frame; tools without the curved map refuse them (exit 2, one line, nothing
# written); and the annulus with
# u = 0 as data on the true circles converges at >= p + 0.8 with curved cells (q = p) and stalls
# near 2 with straight-sided cells (p = 2, 3, levels N = 8, 16, 32); the functional on the
# curved wall converges at >= 2p - 0.2 for p = 2 (q = 2), 3 (q = 4, or q = 3 with area-matched
# boundary nodes) and 4 (q = 6).
set -euo pipefail
S=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v gmsh >/dev/null || { echo "SKIPPED: gmsh not installed"; exit 77; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
json() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))$2)" "$1"; }

# --- gmsh's 36- and 49-node quads (q = 5, 6) read and written back as gmsh wrote them
for q in 5 6; do
  gmsh -2 -v 0 -order $q -setnumber N 2 "$S/examples/geometry/annulus.geo" -o "$T/g$q.msh"
  meshconvert -q "$T/g$q.msh" -o "$T/c$q.msh"
  [ "$(json "$T/c$q.json" '["geometric_order"]')" = $q ] || fail "meshconvert lost the order $q"
  gmsh -v 0 "$T/c$q.msh" -0 -o "$T/back$q.msh" -format msh41 >/dev/null 2>&1 || fail "gmsh cannot read our q = $q file"
  meshconvert -q "$T/back$q.msh" -o "$T/back$q-2.msh"
  cmp "$T/back$q-2.msh" "$T/c$q.msh" || fail "gmsh round trip changed the q = $q mesh"
done

# --- meshconvert keeps the curved cells (binary MSH 4.1 and MSH 2.2 of gmsh too)
gmsh -2 -v 0 -order 3 -setnumber N 2 "$S/examples/geometry/annulus.geo" -o "$T/g.msh"
meshconvert -q "$T/g.msh" -o "$T/c.msh"
[ "$(json "$T/c.json" '["geometric_order"]')" = 3 ] || fail "meshconvert lost the order"
for fmt in "msh22" "msh41 -bin"; do
  gmsh -2 -v 0 -order 3 -setnumber N 2 "$S/examples/geometry/annulus.geo" -format $fmt -o "$T/f.msh"
  meshconvert -q "$T/f.msh" -o "$T/f2.msh"
  # (gmsh's ASCII output has 16 significant digits, its binary output all 17)
  python3 "$S/tests/cli/golden_compare.py" "$T/f2.msh" "$T/c.msh" --rtol 0 --atol 1e-14 || fail "gmsh $fmt converts differently"
done
# gmsh reads what we write (and sees 16 cells of type 36)
gmsh -v 0 "$T/c.msh" -0 -o "$T/back.msh" -format msh41 >/dev/null 2>&1 || fail "gmsh cannot read our curved file"
meshconvert -q "$T/back.msh" -o "$T/back2.msh"
cmp "$T/back2.msh" "$T/c.msh" || fail "gmsh round trip changed the mesh"

# --- dgsolve on it; the solution file is curved again
dgsolve -q "$T/c.msh" -c "$S/examples/cases/annulus.json" -p 3 -o "$T/sol.msh"
[ "$(json "$T/sol.json" '["geometric_order"]')" = 3 ] || fail "dgsolve report: geometric_order"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert 0.5 < r['curved_scaled_jacobian_min'] <= 1, r" "$T/sol.json" \
  || fail "dgsolve report: curved_scaled_jacobian_min"
grep -q '^2 1 36 16$' "$T/sol.msh" || fail "solution mesh not curved"

# --- meshquality measures on the curved map: the area of the q = 3 annulus (|A - 3 pi| = 1.1e-3
# on N = 2; the vertex view's polygon has 8.49), the corners on the circles at 90 degrees (the
# cells' other edges are straight in gmsh's mesh: 67.5 / 112.5 there; in the vertex view all are)
meshquality -q "$T/c.msh" --report "$T/quality.json"
python3 -c "
import json, math, sys; r = json.load(open(sys.argv[1]))
assert r['geometric_order'] == 3, r
assert abs(r['area'] - 3 * math.pi) < 2e-3, r['area']
assert 0.5 < r['physical']['scaled_jacobian_min'] <= 1, r['physical']
assert r['physical']['quad_angle_share_80_100'] == 0.5, r['physical']" "$T/quality.json" \
  || fail "meshquality on curved cells"

# --- estimate-frame reconstructs on the curved map; its SHAPE mesh is the vertex view, which
# size-solve takes
estimate-frame -q "$T/sol.msh" -o "$T/shape.msh"
[ "$(json "$T/shape.json" '["geometric_order"]')" = 3 ] || fail "estimate-frame report: geometric_order"
meshquality -q "$T/shape.msh" --report "$T/shape-quality.json"
[ "$(json "$T/shape-quality.json" '["geometric_order"]')" = 1 ] || fail "estimate-frame: SHAPE mesh not the vertex view"
size-solve -q "$T/shape.msh" --complexity 1000 -o "$T/frame.msh" >/dev/null || fail "size-solve on the SHAPE of a curved solution"

# --- tools without the curved map refuse it: exit 2, one line naming the file, nothing written
# (every tool the docs list; the message says how to get the vertex view)
for cmd in "refine $T/c.msh --uniform -o $T/out.msh" "lpcvt $T/c.msh -o $T/out.msh" "bamgquad $T/c.msh -o $T/out.msh" \
           "quadsmooth $T/c.msh -o $T/out.msh" "size-solve $T/c.msh --growth 1.5 -o $T/out.msh"; do
  set +e
  $cmd >"$T/stdout" 2>"$T/err"
  rc=$?
  set -e
  [ $rc = 2 ] || fail "$cmd: exit $rc, expected 2"
  grep -q "the mesh has curved cells (geometric order 3)" "$T/err" || fail "$cmd: message: $(cat "$T/err")"
  grep -q "c.msh: the mesh has curved cells (geometric order 3); .* run: meshconvert $T/c.msh --order 1 -o STRAIGHT.msh" "$T/err" \
    || fail "$cmd: message names no remedy: $(cat "$T/err")"
  [ "$(wc -l <"$T/err")" = 1 ] || fail "$cmd: more than one line"
  [ ! -e "$T/out.msh" ] || fail "$cmd wrote an output"
done

# --- adjoint integrates on the curved map: with the exact solution's data on the mesh's own
# boundary (list form, natural outer) the DWR estimate is the functional error
python3 - "$S/examples/cases/annulus-wall.json" "$T/wall-exact.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["dirichlet"] = ["inner"]
del c["neumann"]
json.dump(c, open(sys.argv[2], "w"))
PY
gmsh -2 -v 0 -order 2 -setnumber N 8 "$S/examples/geometry/annulus.geo" -o "$T/q2.msh"
dgsolve -q "$T/q2.msh" -c "$T/wall-exact.json" -p 2 -o "$T/w.msh"
adjoint -q "$T/w.msh" -c "$T/wall-exact.json" -o "$T/dwr.msh"
python3 -c "
import json, sys; d = json.load(open(sys.argv[1])); e = d['effectivity']
assert 0.95 < e < 1.05, d" "$T/dwr.json" || fail "adjoint effectivity on curved cells"

# --- rates.py's bad input: one line "rates.py: error: ...", exit 2, no Python traceback (a copy outside
# the checkout with no tools on PATH: before, FileNotFoundError 'dgsolve'; a failing dgsolve gave
# CalledProcessError)
PY=$(python3 -c "import sys; print(sys.executable)")
mkdir -p "$T/norepo"; cp "$S/scripts/curved/rates.py" "$T/norepo/"
rc=0; env PATH=/nonexistent "$PY" "$T/norepo/rates.py" --geo "$S/examples/geometry/annulus.geo" \
  --case "$S/examples/cases/annulus.json" --degrees 2 --levels 4 8 --out "$T/norepo/o" 2>"$T/err" || rc=$?
[ $rc -eq 2 ] && grep -q "rates.py: error: tool(s) not found on PATH: gmsh dgsolve" "$T/err" && ! grep -q Traceback "$T/err" \
  || fail "rates.py without tools: exit $rc: $(cat "$T/err")"
rc=0; "$PY" "$S/scripts/curved/rates.py" --geo "$S/examples/geometry/annulus.geo" --case "$S/examples/cases/cylinder.json" \
  --degrees 2 --levels 4 --out "$T/bad" 2>"$T/err" || rc=$?
[ $rc -eq 2 ] && grep -q "rates.py: error: dgsolve exited with status 2" "$T/err" && ! grep -q Traceback "$T/err" \
  || fail "rates.py with a failing dgsolve: exit $rc: $(cat "$T/err")"

# --- check_boundary.py reads MSH 4.1 ASCII only: Gmsh's MSH 2.2 and binary files, a missing file and
# a case file are refused with one line and exit 2 (before: ValueError / UnicodeDecodeError /
# FileNotFoundError tracebacks); the 4.1 ASCII file is read
gmsh -2 -v 0 -order 2 -setnumber N 2 "$S/examples/geometry/annulus.geo" -format msh22 -o "$T/cb22.msh"
gmsh -2 -v 0 -order 2 -setnumber N 2 "$S/examples/geometry/annulus.geo" -bin -o "$T/cbbin.msh"
for f in "$T/cb22.msh:MSH 2.2 ASCII" "$T/cbbin.msh:MSH 4.1 binary" "$T/none.msh:cannot read it" \
         "$S/examples/cases/annulus.json:not a Gmsh MSH file"; do
  rc=0; python3 "$S/scripts/curved/check_boundary.py" "${f%%:*}" --group inner --circle 0 0 1 --max 1e-12 2>"$T/err" || rc=$?
  [ $rc -eq 2 ] && grep -q "check_boundary.py: error: .*${f#*:}" "$T/err" && [ "$(wc -l <"$T/err")" -eq 1 ] \
    || fail "check_boundary.py ${f%%:*}: exit $rc: $(cat "$T/err")"
done
meshconvert -q "$T/cb22.msh" -o "$T/cb41.msh"
python3 "$S/scripts/curved/check_boundary.py" "$T/cb41.msh" --group inner --circle 0 0 1 --max 1e-12 >/dev/null \
  || fail "check_boundary.py on meshconvert's output"

# --- rates on the annulus
python3 "$S/scripts/curved/rates.py" --geo "$S/examples/geometry/annulus.geo" --case "$S/examples/cases/annulus.json" \
  --degrees 2 3 --levels 8 16 32 --out "$T/rates" --check-curved 0.8 --check-straight 2.3 || fail "annulus rates"
python3 "$S/scripts/curved/rates.py" --geo "$S/examples/geometry/annulus.geo" --case "$S/examples/cases/annulus-wall.json" \
  --degrees 2 --levels 8 16 --kinds curved --wall-radius 2 --out "$T/rates" --check-functional 0.2 || fail "wall functional rate"
# p = 3, 4 need super-parametric cells for 2p (Gmsh's equal-angle nodes: the wall's geometric error
# is O(h^(q+1)) for odd q, O(h^(q+2)) for even q): q = 4 for p = 3 (measured 5.98 on N = 4, 8),
# q = 6 for p = 4 (7.87 on N = 6, 8; N = 8 is 25x above the solver's rounding floor of ~1e-10)
python3 "$S/scripts/curved/rates.py" --geo "$S/examples/geometry/annulus.geo" --case "$S/examples/cases/annulus-wall.json" \
  --degrees 3 --levels 4 8 --kinds curved --q-plus 1 --wall-radius 2 --out "$T/rates" --check-functional 0.2 \
  || fail "wall functional rate, p = 3, q = 4"
python3 "$S/scripts/curved/rates.py" --geo "$S/examples/geometry/annulus.geo" --case "$S/examples/cases/annulus-wall.json" \
  --degrees 4 --levels 6 8 --kinds curved --q-plus 2 --wall-radius 2 --out "$T/rates" --check-functional 0.2 \
  || fail "wall functional rate, p = 4, q = 6"
# ... or isoparametric p = 3 with area-matched boundary nodes (meshconvert --boundary-nodes area;
# measured 5.95 on N = 4, 8)
python3 "$S/scripts/curved/rates.py" --geo "$S/examples/geometry/annulus.geo" --case "$S/examples/cases/annulus-wall.json" \
  --degrees 3 --levels 4 8 --kinds curved --boundary-nodes area --wall-radius 2 --out "$T/rates" --check-functional 0.2 \
  || fail "wall functional rate, p = q = 3, area-matched nodes"
echo "curved: ok"
