#!/usr/bin/env bash
# CLI test: inputs that parse but mean something else than they seem (a semantic review's
# findings). Each was a silent wrong answer or a misleading message before:
#  - a boundary name the mesh knows but with no edge (a physical curve on the wrong entity):
#    Dirichlet data on it were dropped and J over it was 0, exit 0 -> exit 2 naming it;
#  - two boundary groups with one name: Dirichlet used both, J only the first -> J over both;
#  - D = 1e30 I: the block ILU's single-precision factors overflowed ("singular pivot block")
#    -> the system is scaled by a power of two and solves as D = I; |D| > 1e100 is refused;
#  - a case with "exact": 5 and no D or c said "there is no PDE" -> names the bad 'exact';
#  - estimate-frame --exact not finite blamed the mesh's field -> names the expression and point;
#  - lpcvt on a frame it cannot meet (elements longer than the domain) -> a warning on stderr.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
for t in dgsolve estimate-frame lpcvt; do
  command -v $t >/dev/null || { echo "FAIL: $t not built (tools must be on PATH)" >&2; exit 1; }
done
PY=/usr/bin/python3; [ -x $PY ] || PY=python3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
cd "$T"
fail() { echo "FAIL: $*" >&2; exit 1; }
SQ="$SRC/examples/meshes/square16.msh"
jget() { $PY -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }

# --- an empty named group: the right side's curve entity loses its physical tag
sed 's/^2 1 0 0 1 1 0 1 2 0$/2 1 0 0 1 1 0 0 0/' "$SQ" > noright.msh
cmp -s "$SQ" noright.msh && fail "the sed did not change square16.msh"
rc=0; msg=$(dgsolve -q noright.msh -c "$SRC/examples/cases/sshock.json" -p 1 -o a.msh 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q "Dirichlet boundary 'right' is a boundary group of the mesh without any edge" <<<"$msg" ||
  fail "empty group 'right': exit $rc, $msg"
[ ! -e a.msh ] || fail "empty group: a.msh written"

# --- two groups named 'bottom' (top renamed): J over both = J(bottom) + J(top) of the original
sed 's/"top"/"bottom"/' "$SQ" > twobottom.msh
base='"diffusion": [[0.3, 0.1], [0.1, 0.5]], "advection": [1.0, -0.7], "exact": "sin(2*x + 0.5)*cos(3*y - 0.2) + exp(x*y)"'
for g in bottom top; do echo "{ $base, \"functional\": {\"boundary\": \"$g\"} }" > j$g.json; done
dgsolve -q "$SQ" -c jbottom.json -p 2 -o b.msh --report b.json
dgsolve -q "$SQ" -c jtop.json -p 2 -o t.msh --report t.json
dgsolve -q twobottom.msh -c jbottom.json -p 2 -o bb.msh --report bb.json
$PY - <<'PY' || exit 1
import json, sys
b, t, bb = (json.load(open(f)) for f in ("b.json", "t.json", "bb.json"))
for key in ("functional", "functional_exact"):
    want = b[key] + t[key]
    if not abs(bb[key] - want) <= 1e-12 + 1e-12 * abs(want):
        sys.exit(f"FAIL: two groups named bottom: {key} {bb[key]}, want {b[key]} + {t[key]} = {want}")
print(f"ok: J over two groups named bottom = {bb['functional']:.12g} (the two sides' sum)")
PY

# --- D far from 1: the same solution as D = I (the source scales with D); beyond 1e100 refused
for d in 1 1e30 1e-30; do
  echo "{ \"diffusion\": [[$d, 0], [0, $d]], \"exact\": \"x*y + sin(x)\" }" > d$d.json
  dgsolve -q "$SQ" -c d$d.json -p 2 -o d$d.msh --report d$d.json.r
done
$PY - <<'PY' || exit 1
import json, sys
e = {d: json.load(open(f"d{d}.json.r"))["l2_error"] for d in ("1", "1e30", "1e-30")}
for d in ("1e30", "1e-30"):
    if not abs(e[d] - e["1"]) <= 1e-6 * e["1"]:
        sys.exit(f"FAIL: D = {d} I: L2 error {e[d]}, D = I: {e['1']}")
print(f"ok: D = 1e30 I and 1e-30 I solve as D = I (L2 {e['1']:.6e})")
PY
echo '{ "diffusion": [[1e200, 0], [0, 1]], "exact": "x" }' > dhuge.json
rc=0; msg=$(dgsolve -q "$SQ" -c dhuge.json -p 1 -o h.msh 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q "dhuge.json: key 'diffusion': entry 1.000e+200 is outside 1e-100..1e100" <<<"$msg" || fail "D = 1e200: exit $rc, $msg"

# --- the bad key is named before "no PDE"
echo '{ "exact": 5 }' > ex5.json
rc=0; msg=$(dgsolve -q "$SQ" -c ex5.json -p 1 -o e.msh 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q "ex5.json: key 'exact' must be an expression string" <<<"$msg" || fail "exact 5: exit $rc, $msg"

# --- estimate-frame --exact not finite: the expression and the point
rc=0; msg=$(estimate-frame -q "$SQ" --exact '1/(x-0.5)' -p 2 -o f.msh 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q -- "--exact '1/(x-0.5)' is not finite at (5.000e-01, " <<<"$msg" || fail "estimate-frame --exact: exit $rc, $msg"

# --- lpcvt: a frame whose elements are longer than the domain: the count is far from the frame's
$PY "$SRC/tests/cli/lpcvt_frame.py" long.msh --n 4 --h1 50 --h2 0.005
rc=0; msg=$(lpcvt long.msh -o long-tri.msh 2>&1) || rc=$?
[ $rc -eq 0 ] && grep -q "warning: about [0-9]* cells after recombine for the frame's [0-9]* (ratio " <<<"$msg" ||
  fail "lpcvt on an unmeetable frame: exit $rc, no warning: $msg"
$PY "$SRC/tests/cli/lpcvt_frame.py" fine.msh --n 4 --h1 0.05 --h2 0.05
msg=$(lpcvt fine.msh -o fine-tri.msh 2>&1)
grep -q "cells after recombine for the frame" <<<"$msg" && fail "lpcvt warns on a frame it meets: $msg"
echo "PASS: case_mesh_semantics"
