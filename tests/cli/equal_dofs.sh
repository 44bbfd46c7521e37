#!/usr/bin/env bash
# scripts/loop/equal-dofs.py: two loops' errors at equal DOFs, for a user's own case (compare.py
# needs one of the thesis's studies). Exact on power laws: B's error is 2 C N^-1.5 and A's
# C N^-1.5, sampled at other DOF counts, so log-log interpolation gives A / B = 0.5 at every A
# step inside B's range; outside it "-"; goal mode reads |functional_error|; bad tables exit 2.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
PY=/usr/bin/python3; [ -x $PY ] || PY=python3
$PY - <<'PY'
def law(c, n): return c * n ** -1.5
with open("a.csv", "w") as f:
    f.write("step,cells,dofs,l2_error,functional_error\n")
    for k, n in enumerate([1000, 2000, 4000, 9000]):
        f.write("%d,%d,%d,%.17g,%.17g\n" % (k, n // 4, n, law(1, n), -law(3, n)))
with open("b.csv", "w") as f:
    f.write("step,cells,dofs,l2_error,functional_error\n")
    for k, n in enumerate([900, 1700, 3100, 6000]):
        f.write("%d,%d,%d,%.17g,%.17g\n" % (k, n // 4, n, law(2, n), law(1, n)))
PY
out="$($PY "$S/scripts/loop/equal-dofs.py" a.csv b.csv --labels lpcvt,bamg)"
echo "$out"
printf '%s\n' "$out" | grep -q "| 1000 | 3.162e-05 | 6.325e-05 | 0.5 |" || fail "row at 1000 DOFs"
printf '%s\n' "$out" | grep -q "| 9000 | .* | - | - |" || fail "9000 DOFs is outside B's range"
printf '%s\n' "$out" | grep -q "lpcvt / bamg at equal DOFs: geometric mean 0.5 over 3 steps (range 0.5-0.5)" || fail "summary"
goal="$($PY "$S/scripts/loop/equal-dofs.py" a.csv b.csv --mode goal)"
printf '%s\n' "$goal" | grep -q "geometric mean 3 over 3 steps" || { echo "$goal"; fail "goal mode (|functional_error|)"; }
# a shared start (step 0 of both: the same DOFs and error) is shown, not counted (it pulled the
# mean towards 1: a reviewer's 0.536 over 7 steps was 0.48 over the 6 that differ)
{ head -1 a.csv; echo "0,200,800,1e-2,1e-3"; tail -n +2 a.csv; } > a0.csv
{ head -1 b.csv; echo "0,200,800,1e-2,1e-3"; tail -n +2 b.csv; } > b0.csv
out0="$($PY "$S/scripts/loop/equal-dofs.py" a0.csv b0.csv --labels lpcvt,bamg)"
printf '%s
' "$out0" | grep -q "| 800 | 1.000e-02 | 1.000e-02 | same step (not in the mean) |" || { echo "$out0"; fail "shared step"; }
printf '%s
' "$out0" | grep -q "geometric mean 0.5 over 3 steps" || { echo "$out0"; fail "shared step counted"; }
expect_exit 2 "give two names" $PY "$S/scripts/loop/equal-dofs.py" a.csv b.csv --labels lpcvt
echo "step,cells" > bad.csv
expect_exit 2 "bad.csv: not a loop's convergence.csv" $PY "$S/scripts/loop/equal-dofs.py" bad.csv b.csv
expect_exit 2 "none.csv" $PY "$S/scripts/loop/equal-dofs.py" none.csv b.csv
# a run's directory stands for its convergence.csv (it was "Is a directory": a review, session 38)
mkdir -p runA && cp a.csv runA/convergence.csv
[ "$($PY "$S/scripts/loop/equal-dofs.py" runA b.csv --labels lpcvt,bamg)" = "$out" ] || fail "A given as its run directory"
expect_exit 2 "empty/convergence.csv" $PY "$S/scripts/loop/equal-dofs.py" "$(mkdir -p empty && echo empty)" b.csv
echo "ok: equal-dofs"
