#!/usr/bin/env bash
# Makefile.cases `loop` end to end with METHOD=uniform (dgsolve + refine): convergence.csv columns
# and falling error, resume after deleting the last step, the parameter guard, and bad-input
# messages before any work. A missing tool fails; a missing gmsh program is a ctest skip (exit 77).
set -euo pipefail
SRC="${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}"
BIN="${QUADAPT_BIN_DIR:-$SRC/build/bin}"
export PATH="$BIN:$PATH"
for t in dgsolve refine; do
  command -v "$t" >/dev/null || { echo "FAIL: $t not built (tools must be on PATH)" >&2; exit 1; }
done
command -v gmsh >/dev/null || { echo "SKIPPED: gmsh (the program) not installed"; exit 77; }
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
T="$(mktemp -d)"; trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
MK=(make --no-print-directory -f "$SRC/Makefile.cases" BIN="$BIN")

# a user's own case file and start mesh (4x4 grid with the unit square's boundary names)
cat > "$T/smooth.json" <<'JSON'
{ "diffusion": [[1, 0], [0, 1]], "advection": [1, 0.5],
  "exact": "sin(pi*x)*sin(pi*y) + x*y", "functional": {"boundary": "right"} }
JSON
gmsh -2 -format msh41 -setnumber N 4 -o "$T/sq4.msh" "$SRC/examples/geometry/unit_square.geo" >/dev/null 2>&1 || fail "gmsh could not mesh the square"

LOOP=(CASE="$T/smooth.json" MESH="$T/sq4.msh" P=1 METHOD=uniform MODE=feature STEPS=2 GROWTH=1.5
      OUT="$T/run" PICTURES=no)

# ---- 1. a 2-step loop
"${MK[@]}" loop "${LOOP[@]}" > "$T/log1.txt" 2>&1 || { cat "$T/log1.txt"; fail "loop failed"; }
csv="$T/run/convergence.csv"
[ -s "$csv" ] || fail "no convergence.csv"
for k in 0 1 2; do [ -s "$T/run/step-$k/sol.msh" ] || fail "no step-$k/sol.msh"; done
[ -s "$T/run/step-1/adapted.msh" ] && [ -s "$T/run/step-0/refine.log" ] || fail "step files missing"
[ -e "$T/run/step-2/adapted.msh" ] && fail "the last step must not be adapted"
"$PY" - "$csv" <<'PYEOF' || fail "convergence table"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
need = ["step", "cells", "dofs", "l2_error", "functional_error", "t_dgsolve", "t_refine", "t_solve"]
missing = [c for c in need if c not in rows[0]]
assert not missing, "missing columns %s" % missing
assert [int(r["step"]) for r in rows] == [0, 1, 2], rows
cells = [int(r["cells"]) for r in rows]
assert cells == [16, 64, 256], cells
assert [int(r["dofs"]) for r in rows] == [4 * c for c in cells]
e = [float(r["l2_error"]) for r in rows]
assert e[0] > e[1] > e[2] > 0, e
rate = [(e[i] / e[i + 1]) for i in range(2)]
assert min(rate) > 3.5, "uniform refinement at p=1 should reduce the L2 error ~4x (order 2; measured 3.97, 3.99): %s" % rate
assert float(rows[0]["t_refine"]) > 0 and rows[2]["t_refine"] == "", rows
PYEOF

# the loop names the tools it runs and why it stopped (a user could not tell a MAXDOFS stop from
# a finished run, nor which build a typo'd BIN fell back to)
grep -q "^\[.*\] tools: $BIN (quadapt " "$T/log1.txt" || { cat "$T/log1.txt"; fail "no tools line"; }
grep -q "stopping after step-2: STEPS=2 reached" "$T/log1.txt" || { cat "$T/log1.txt"; fail "no STEPS stop line"; }
"${MK[@]}" loop "${LOOP[@]}" OUT="$T/run-max" STEPS=5 MAXDOFS=100 > "$T/log-max.txt" 2>&1 || { cat "$T/log-max.txt"; fail "MAXDOFS loop failed"; }
grep -q "stopping after step-0: the DOF limit MAXDOFS=100" "$T/log-max.txt" || { cat "$T/log-max.txt"; fail "no MAXDOFS stop line"; }
[ ! -e "$T/run-max/step-1" ] || fail "MAXDOFS=100: step-1 was run"
rc=0; make --no-print-directory -f "$SRC/Makefile.cases" loop "${LOOP[@]}" BIN="$T/no-such-bin" OUT="$T/run-typo" > "$T/log-typo.txt" 2>&1 || rc=$?
[ $rc -ne 0 ] && grep -q "BIN=$T/no-such-bin: no dgsolve there" "$T/log-typo.txt" || { cat "$T/log-typo.txt"; fail "typo'd BIN accepted"; }
[ ! -e "$T/run-typo" ] || fail "typo'd BIN: OUT created"
# a misspelt variable (METOD=bamg, STEP=1) was ignored: the loop ran lpcvt for 6 steps, exit 0.
# Refused, every misspelling named, nothing created; `check` too; the environment passes
rc=0; make --no-print-directory -f "$SRC/Makefile.cases" loop "${LOOP[@]}" METOD=bamg STEP=1 OUT="$T/run-typo2" > "$T/log-typo2.txt" 2>&1 || rc=$?
[ $rc -ne 0 ] && grep -q "METOD=bamg STEP=1: not read by Makefile.cases" "$T/log-typo2.txt" || { cat "$T/log-typo2.txt"; fail "misspelt variables accepted"; }
[ ! -e "$T/run-typo2" ] || fail "misspelt variables: OUT created"
rc=0; "${MK[@]}" check "${LOOP[@]}" STEP=1 OUT="$T/run-typo3" > "$T/log-typo3.txt" 2>&1 || rc=$?
[ $rc -ne 0 ] || fail "check accepted STEP=1"
"${MK[@]}" check "${LOOP[@]}" OMP_NUM_THREADS=1 OUT="$T/run-typo3" > /dev/null || fail "check refused OMP_NUM_THREADS=1"

# pictures again with another close-up window: drawn again (was: skipped, the close-up being newer
# than its mesh); the same window again: not redrawn; a malformed window: refused
"${MK[@]}" pictures OUT="$T/run" WINDOW=0,0.5,0,0.5 > "$T/logp.txt" 2>&1 || { cat "$T/logp.txt"; fail "pictures"; }
cu="$T/run/final-mesh-closeup.png"
[ -s "$cu" ] || fail "no close-up"
sum1="$(md5sum < "$cu")"; t1="$(stat -c %Y.%N "$cu")"
sleep 1
"${MK[@]}" pictures OUT="$T/run" WINDOW=0,0.5,0,0.5 > "$T/logp.txt" 2>&1 || { cat "$T/logp.txt"; fail "pictures (same window)"; }
[ "$t1" = "$(stat -c %Y.%N "$cu")" ] || fail "the same window drew the close-up again"
"${MK[@]}" pictures OUT="$T/run" WINDOW=0.5,1,0.5,1 > "$T/logp.txt" 2>&1 || { cat "$T/logp.txt"; fail "pictures (new window)"; }
[ "$sum1" != "$(md5sum < "$cu")" ] || fail "another window left the close-up as it was"
rc=0; "${MK[@]}" pictures OUT="$T/run" WINDOW=0.45,0.55,0.3 > "$T/logp.txt" 2>&1 || rc=$?
[ $rc -ne 0 ] && grep -q "WINDOW='0.45,0.55,0.3': give x0,x1,y0,y1" "$T/logp.txt" || { cat "$T/logp.txt"; fail "bad window accepted"; }

# ---- 2. resume: delete the last step, rerun -> the same table (times aside); step 0 is not redone
strip() { "$PY" -c "import csv,sys
for r in csv.DictReader(open(sys.argv[1])): print({k: v for k, v in r.items() if not k.startswith('t_')})" "$1"; }
strip "$csv" > "$T/table1.txt"
before="$(stat -c %Y.%N "$T/run/step-0/sol.msh")"
rm -rf "$T/run/step-2"
"${MK[@]}" loop "${LOOP[@]}" > "$T/log2.txt" 2>&1 || { cat "$T/log2.txt"; fail "resumed loop failed"; }
strip "$csv" > "$T/table2.txt"
diff "$T/table1.txt" "$T/table2.txt" >&2 || fail "resumed table differs"
[ "$before" = "$(stat -c %Y.%N "$T/run/step-0/sol.msh")" ] || fail "step 0 was recomputed on resume"
grep -q "step-2: dgsolve" "$T/log2.txt" || fail "step 2 was not recomputed"
grep -q "step-0: dgsolve" "$T/log2.txt" && fail "step 0's dgsolve ran again"
# the same OUT with other parameters is refused
rc=0; "${MK[@]}" loop "${LOOP[@]}" P=2 > "$T/log3.txt" 2>&1 || rc=$?
[ $rc -ne 0 ] && grep -q "other parameters" "$T/log3.txt" || { cat "$T/log3.txt"; fail "parameter guard"; }
# ... and the finished run stays finished (its loop.done was removed before the check: the study
# targets then took it for unfinished; a new-user review, session 38)
[ -e "$T/run/loop.done" ] || fail "a run refused for other parameters lost its loop.done"
# the case re-indented, its keys reordered, a description added: the same case, nothing recomputed
# (was: refused, "case_sha256: was …, now …" — the file's bytes were hashed); another value: refused
"$PY" - "$T/smooth.json" "$T/smooth2.json" <<'PYEOF'
import json, sys
c = json.load(open(sys.argv[1]))
c = dict(reversed(list(c.items())), description="the same problem, re-saved")
open(sys.argv[2], "w").write(json.dumps(c, indent=4) + "\n")
PYEOF
"${MK[@]}" loop "${LOOP[@]}" CASE="$T/smooth2.json" > "$T/log3b.txt" 2>&1 || { cat "$T/log3b.txt"; fail "re-saved case refused"; }
grep -q "dgsolve" "$T/log3b.txt" && { cat "$T/log3b.txt"; fail "re-saved case: a step was recomputed"; }
sed 's/"advection": \[1, 0.5\]/"advection": [1, 0.25]/' "$T/smooth.json" > "$T/smooth3.json"
cmp -s "$T/smooth.json" "$T/smooth3.json" && fail "test setup: advection not changed"
rc=0; "${MK[@]}" loop "${LOOP[@]}" CASE="$T/smooth3.json" > "$T/log3c.txt" 2>&1 || rc=$?
[ $rc -ne 0 ] && grep -q "case_sha256" "$T/log3c.txt" || { cat "$T/log3c.txt"; fail "changed case accepted"; }

# ---- 3. bad input: a clear message and no run directory
bad() {  # bad PATTERN VAR=VALUE...
  local pat="$1"; shift
  local rc=0
  "${MK[@]}" loop "${LOOP[@]}" OUT="$T/bad" "$@" > "$T/bad.txt" 2>&1 || rc=$?
  [ $rc -ne 0 ] || fail "loop $* succeeded"
  grep -q -- "$pat" "$T/bad.txt" || { cat "$T/bad.txt" >&2; fail "message for '$*' lacks '$pat'"; }
  [ ! -e "$T/bad" ] || fail "loop $* created its OUT before failing"
}
bad "unknown METHOD 'simplex'" METHOD=simplex
bad "unknown MODE 'magic'" MODE=magic
bad "unknown CASE '$T/nope.json'" CASE="$T/nope.json"
echo '{"exact": ' > "$T/broken.json"
bad "not valid JSON" CASE="$T/broken.json"
bad "MESH '$T/none.msh': no such file" MESH="$T/none.msh"
bad "P='x'" P=x
bad "STEPS='-1'" STEPS=-1
# a missing tool: only dgsolve and refine on PATH
mkdir "$T/fakebin"
ln -s "$(command -v dgsolve)" "$T/fakebin/dgsolve"; ln -s "$(command -v refine)" "$T/fakebin/refine"
rc=0
PATH="/usr/bin:/bin" make --no-print-directory -f "$SRC/Makefile.cases" BIN="$T/fakebin" loop "${LOOP[@]}" \
  OUT="$T/bad" METHOD=lpcvt > "$T/bad.txt" 2>&1 || rc=$?
[ $rc -ne 0 ] && grep -q "tool(s) not found: estimate-frame size-solve lpcvt recombine quadsmooth .*put their directory on PATH" "$T/bad.txt" \
  || { cat "$T/bad.txt" >&2; fail "missing-tool message (one line)"; }
[ ! -e "$T/bad" ] || fail "missing tool: OUT created"
echo "loop (uniform) CLI: all checks passed"
