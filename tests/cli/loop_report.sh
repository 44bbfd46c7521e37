#!/usr/bin/env bash
# The study report (scripts/loop/compare.py) and plots on synthetic runs with known power laws:
# interpolation at the thesis's DOF counts must be exact for e = c N^-r, extrapolation is marked,
# runs that are missing are reported as such. Needs no quadapt tool.
set -euo pipefail
SRC="${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}"
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
T="$(mktemp -d)"; trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# thesis table with two rows: one inside our range, one beyond it, one for a run we lack
cat > "$T/tables.json" <<'JSON'
{"cases": {"demo": {"table": "9.9", "measure": "l2_error", "rows": [
  {"p": 2, "method": "bamg", "dofs": 3.0e4, "error": 1e-5, "t_solve": 10.0},
  {"p": 2, "method": "lpcvt", "dofs": 2.0e5, "error": 1e-9, "t_solve": 10.0},
  {"p": 2, "method": "fixed_fraction", "dofs": 3.0e4, "error": 1e-9, "t_solve": 10.0}]}}}
JSON
"$PY" - "$T/study" <<'PYEOF'
import os, sys
base = sys.argv[1]
for m, c in (("bamg", 1.0), ("lpcvt", 2.0)):
    d = os.path.join(base, "p2-" + m); os.makedirs(d)
    rows = ["step,cells,dofs,l2_error,functional_error,t_solve"]
    n = 2304.0
    for k in range(8):  # e = c N^-1.5, t = 1e-4 N
        rows.append("%d,%d,%.17g,%.17g,,%.17g" % (k, n / 9, n, c * n ** -1.5, 1e-4 * n)); n *= 1.5
    open(os.path.join(d, "convergence.csv"), "w").write("\n".join(rows) + "\n")
    open(os.path.join(d, "loop.done"), "w").write("7\n")
PYEOF
THESIS_TABLES="$T/tables.json" bash "$SRC/scripts/loop/study-report.sh" "$T/study" feature demo "2" \
  "uniform fixed-fraction bamg lpcvt" "Demo" > "$T/out.txt" 2>&1 || { cat "$T/out.txt"; fail "study-report"; }
[ -s "$T/study/report.md" ] && [ -s "$T/study/report.json" ] || fail "no report"
"$PY" - "$T/study/report.json" <<'PYEOF' || fail "report values"
import json, sys
r = {x["method"]: x for x in json.load(open(sys.argv[1]))["rows"]}
b = r["bamg"]  # inside the range: exact for a power law
assert abs(b["ours"] / (3.0e4 ** -1.5) - 1) < 1e-9, b
assert b["flag"] == "" and b["better"] == "quadapt", b
assert abs(b["our_t_solve"] / 3.0 - 1) < 1e-9 and b["faster"] == "quadapt", b
l = r["lpcvt"]  # 2e5 > 1.5 x our last point 3.9e4: not reached
assert l["ours"] is None and l["flag"] == "not reached", l
f = r["fixed-fraction"]
assert f["ours"] is None and f["flag"] == "no data", f
PYEOF
grep -q "| 2 | fixed-fraction (not run) |" "$T/study/report.md" || fail "missing run not marked"
# compare.py: a wrong --study, --case or --thesis is one line and exit 2 (tracebacks, the first after
# the work: a review, session 38); --ps / --methods keep only their rows
C="$SRC/scripts/loop/compare.py"
for bad in "--study $T/nope --thesis $T/tables.json --case demo" "--study $T/study --thesis $T/tables.json --case dem" \
           "--study $T/study --thesis $T/nope.json --case demo"; do
  rc=0; err=$("$PY" "$C" $bad --mode feature -o "$T/bad.md" 2>&1) || rc=$?
  [ $rc -eq 2 ] && [ "$(wc -l <<<"$err")" -eq 1 ] && grep -q "^compare.py: --" <<<"$err" && [ ! -e "$T/bad.md" ] ||
    fail "compare.py $bad: exit $rc: $err"
done
"$PY" "$C" --study "$T/study" --thesis "$T/tables.json" --case demo --mode feature --methods bamg -o "$T/only.md" >/dev/null
grep -q "^| 2 | bamg " "$T/only.md" && ! grep -q "fixed-fraction\|lpcvt (not run)\|^| 2 | lpcvt" "$T/only.md" || fail "--methods bamg kept other rows: $(cat "$T/only.md")"
grep -q "quadapt has the smaller error in \*\*1 of 1\*\*" "$T/study/report.md" || fail "summary line"
if "$PY" -c "import matplotlib" 2>/dev/null; then
  [ "$(head -c 4 "$T/study/convergence-p2.png" | od -An -tx1 | tr -d ' \n')" = "89504e47" ] || fail "no plot"
fi
# extrapolation within 1.5x is marked
"$PY" - "$SRC/scripts/loop" <<'PYEOF' || fail "extrapolation"
import sys; sys.path.insert(0, sys.argv[1])
from compare import interp_loglog
pts = [(1e3, 1e-2), (1e4, 1e-4)]
y, flag = interp_loglog(pts, 1.2e4)
assert flag == "extrap." and abs(y / (1e-4 * 1.2 ** -2) - 1) < 1e-12, (y, flag)
assert interp_loglog(pts, 1e5) == (None, "not reached")
y, flag = interp_loglog(pts, 3e3)
assert flag == "" and abs(y / (1e-2 * 3 ** -2) - 1) < 1e-12
PYEOF
# the rank-sum test lpcvt-vs.py prints for the goal rows (compare.py): exact two-sided p-values
# of small samples (separated 5 + 5: 2 / C(10, 5); separated 4 + 3: 2 / C(7, 3); interleaved 3 + 3:
# 14 of the 20 splits as far from the mean), the geometric mean
"$PY" - "$SRC/scripts/loop" <<'PYEOF'
import sys
sys.path.insert(0, sys.argv[1])
from compare import geomean, mann_whitney_p
assert abs(mann_whitney_p([1, 2, 3, 4, 5], [6, 7, 8, 9, 10]) - 2 / 252) < 1e-15
assert abs(mann_whitney_p([10, 20, 30, 40], [1, 2, 3]) - 2 / 35) < 1e-15
assert abs(mann_whitney_p([1, 3, 5], [2, 4, 6]) - 0.7) < 1e-15
assert abs(geomean([1e-9, 1e-11]) / 1e-10 - 1) < 1e-12
# 18 + 18 (too many splits to count): the normal approximation; separated samples give
# |U - 162| = 162, sd = sqrt(18 * 18 * 37 / 12) = 31.61, p = erfc(161.5 / 31.61 / sqrt 2) = 3.2e-7
import math
p = mann_whitney_p(list(range(18)), list(range(100, 118)))
assert abs(p / math.erfc(161.5 / math.sqrt(18 * 18 * 37 / 12) / math.sqrt(2)) - 1) < 1e-12 and p < 1e-6, p
assert mann_whitney_p(list(range(0, 36, 2)), list(range(1, 37, 2))) > 0.5
PYEOF
# the convergence table's row: the effectivity of an error at J's rounding level is flagged in
# `warnings` (a reviewer's p = 3 step printed 3.97 for |J - J_H| = 1.2e-13, J = 1.1); a resolved
# error is not
"$PY" - "$SRC/scripts/loop" "$T/steps" <<'PYEOF' || fail "effectivity at the rounding level"
import json, os, sys
sys.path.insert(0, sys.argv[1])
from loopctl import row_for
for k, (err, est) in enumerate([(1.17e-13, 4.64e-13), (2.1e-10, 2.05e-10)]):
    d = os.path.join(sys.argv[2], "step-%d" % k); os.makedirs(d)
    json.dump({"cells": 10, "dofs": 90, "functional": 1.1 - err, "functional_exact": 1.1, "functional_error": err,
               "time_s": 0.1}, open(os.path.join(d, "sol.json"), "w"))
    json.dump({"tool": "adjoint", "functional_error_estimate": est, "timings": {"total": 0.2}}, open(os.path.join(d, "dwr.json"), "w"))
r0 = row_for(os.path.join(sys.argv[2], "step-0"), 0)
r1 = row_for(os.path.join(sys.argv[2], "step-1"), 1)
assert abs(r0["effectivity"] / (4.64 / 1.17) - 1) < 1e-2 and "at the rounding level of J" in (r0["warnings"] or ""), r0
assert abs(r1["effectivity"] / (2.05 / 2.1) - 1) < 1e-4 and r1["warnings"] is None, r1
PYEOF
# lpcvt-vs.py's command line: --help is its usage (exit 0); an unknown option, an extra argument or
# a missing RUNS directory is one line on stderr and exit 2
"$PY" "$SRC/scripts/loop/lpcvt-vs.py" --help > "$T/vs-help" || fail "lpcvt-vs.py --help: exit $?"
grep -q "^usage: lpcvt-vs.py \[RUNS\]" "$T/vs-help" || fail "lpcvt-vs.py --help: $(head -3 "$T/vs-help")"
for args in "-x" "$T/study $T/study" "-h $T/study" "$T/no-such-runs"; do
  rc=0; "$PY" "$SRC/scripts/loop/lpcvt-vs.py" $args > "$T/vs-out" 2> "$T/vs-err" || rc=$?
  [ $rc -eq 2 ] && [ ! -s "$T/vs-out" ] && [ "$(wc -l < "$T/vs-err")" -eq 1 ] \
    || fail "lpcvt-vs.py $args: exit $rc, stdout $(wc -c < "$T/vs-out") bytes, stderr: $(cat "$T/vs-err")"
done
echo "loop report: all checks passed"
