#!/usr/bin/env bash
# CLI test of `size-solve`: feature-based golden (S-shock 16x16, p = 2, growth 1.5), complexity
# within 0.1%, the Vinv layout against PHiLiP's fixture, the goal-oriented fit, bad input.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
FIX=${QUADAPT_FIXTURES_DIR:-$SRC/tests/fixtures/philip}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v size-solve >/dev/null || { echo "FAIL: size-solve not built (tools must be on PATH)" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
json() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))$2)" "$1"; }
GOLD="$SRC/tests/golden/frame"
CMP="$SRC/tests/cli/golden_compare.py"
SHAPE="$GOLD/sshock16_p2_shape.msh"

# --- feature-based golden: growth 1.5 -> C = 1.5 x 256 x 9 = 3456
size-solve -q "$SHAPE" --growth 1.5 -o "$T/frame.msh"
python3 - "$T/frame.json" 3456 <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); C = float(sys.argv[2])
assert r["target_complexity"] == C, r
assert abs(r["continuous_complexity"] - C) <= 1e-3 * C, r
assert r["p"] == 2 and r["cells"] == 256 and r["current_dofs"] == 2304, r
for k in ("lambda", "h_min", "h_max", "timings"):
    assert k in r, k
assert 0 < r["h_min"] < r["h_max"] <= r["hmax_bound"] * (1 + 1e-12), r
PY
python3 "$CMP" "$T/frame.msh" "$GOLD/sshock16_p2_frame.msh" --rtol 1e-6 --atol 1e-9 || fail "FRAME differs from the golden"
python3 "$CMP" "$T/frame.json" "$GOLD/sshock16_p2_frame.json" --rtol 1e-6 --atol 1e-9 || fail "report differs from the golden"
for f in Vinv h theta rho; do grep -q "^\"$f\"\$" "$T/frame.msh" || fail "field $f missing"; done

# --- explicit complexity, safeguards on: still within 0.1%
size-solve -q "$SHAPE" --complexity 5000 --max-anisotropy 5 --gradation 2 -o "$T/f5000.msh"
python3 - "$T/f5000.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert abs(r["continuous_complexity"] - 5000) <= 5, r
assert r["rho_max"] <= 5 * (1 + 1e-12), r
assert r["cells_anisotropy_capped"] > 0, r
PY

# --- Vinv layout: same view shape as PHiLiP's frame files (9 components, zeros outside the 2x2),
# and det M integrates to the complexity: sum area_k det(M_k) / 4 = C / (p+1)^2
python3 - "$T/frame.msh" "$FIX/input_ss15_fb_p2_3.msh" <<'PY'
import sys
def views(path):
    L = open(path).read().split("\n"); out = {}
    for i, l in enumerate(L):
        if l == "$ElementData":
            name = L[i + 2].strip('"'); nr = int(L[i + 3]); j = i + 4 + nr
            ni = int(L[j]); ncomp = int(L[j + 2]); n = int(L[j + 3]); s = j + 1 + ni
            out[name] = (ncomp, [list(map(float, x.split()[1:])) for x in L[s:s + n]])
    return out
ours, phil = views(sys.argv[1])["Vinv"], views(sys.argv[2])["Vinv"]
assert ours[0] == phil[0] == 9, (ours[0], phil[0])
for rows in (ours[1], phil[1]):
    for v in rows:
        assert len(v) == 9 and all(v[i] == 0 for i in (2, 5, 6, 7, 8)), v
# unit-square 16x16: every cell has area 1/256
tot = sum((v[0] * v[4] - v[1] * v[3]) / 4 / 256 for v in ours[1])
assert abs(tot - 3456 / 9) < 1e-6 * 384, tot
PY

# --- goal-oriented: a synthetic DWR on the same mesh meets C and respects r_max, c_max
python3 "$GOLD/add_view.py" "$SHAPE" "$T/dwr.msh" dwr B
size-solve -q "$SHAPE" --dwr "$T/dwr.msh" --growth 1.5 -o "$T/goal.msh"
python3 - "$T/goal.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert abs(r["continuous_complexity"] - 3456) <= 3.456, r
assert r["alpha_min"] >= 1 / 20 * (1 - 1e-12) and r["alpha_max"] <= 4 * (1 + 1e-12), r
assert r["options"]["mode"] == "goal", r
PY
# independent of the solver's own complexity sum: the written frame's det integrates to C / (p+1)^2
# (goal mode and the safeguarded 5000 too; a wrong (p+1)^2 or area factor fails here)
python3 - "$T/goal.msh" 3456 "$T/f5000.msh" 5000 <<'PY'
import sys
def vinv(path):
    L = open(path).read().split("\n")
    for i, l in enumerate(L):
        if l == "$ElementData" and L[i + 2].strip('"') == "Vinv":
            nr = int(L[i + 3]); j = i + 4 + nr; ni = int(L[j]); n = int(L[j + 3]); s = j + 1 + ni
            return [list(map(float, x.split()[1:])) for x in L[s:s + n]]
    sys.exit("FAIL: no Vinv in " + path)
args = sys.argv[1:]
for path, C in zip(args[::2], map(float, args[1::2])):
    rows = vinv(path)
    assert len(rows) == 256, len(rows)
    tot = sum((v[0] * v[4] - v[1] * v[3]) / 4 / 256 for v in rows)
    assert abs(tot - C / 9) < 1e-3 * C / 9, (path, tot, C / 9)
PY
grep -q '^"alpha"$' "$T/goal.msh" || fail "goal: alpha field missing"

# --- bad input: exit 2, one line naming the problem, nothing written
expect_fail() {  # expect_fail PATTERN ARGS...
  local pat=$1; shift
  rm -f "$T/bad.msh" "$T/bad.json"
  set +e
  size-solve -q "$@" -o "$T/bad.msh" 2>"$T/err"
  local rc=$?
  set -e
  [ $rc = 2 ] || fail "size-solve $* exited $rc, expected 2: $(cat "$T/err")"
  grep -q -- "$pat" "$T/err" || fail "message for $*: $(cat "$T/err")"
  [ ! -e "$T/bad.msh" ] && [ ! -e "$T/bad.json" ] || fail "output written for $*"
}
expect_fail "below the smallest" "$SHAPE" --complexity 50
expect_fail "exceeds" "$SHAPE" --complexity 1e9 --hmin 0.01
expect_fail "complexity" "$SHAPE"
expect_fail "excludes" "$SHAPE" --complexity 100 --growth 2
python3 "$SRC/tests/golden/refine/make_square.py" 4 "$T/plain.msh" bare
expect_fail "plain.msh: no cell field" "$T/plain.msh" --growth 1.5
# DWR on another mesh (a 12x12 grid) and a DWR file without the field
python3 "$SRC/tests/golden/refine/make_square.py" 12 "$T/sq12.msh"
python3 "$GOLD/add_view.py" "$T/sq12.msh" "$T/dwr12.msh" dwr B
expect_fail "dwr12.msh: DWR file is on another mesh" "$SHAPE" --dwr "$T/dwr12.msh" --growth 1.5
expect_fail "no scalar cell field \"dwr\"" "$SHAPE" --dwr "$SHAPE" --growth 1.5
expect_fail "outside the range" "$SHAPE" --dwr "$T/dwr.msh" --growth 40
# a negative indicator (adjoint writes |eta| >= 0): refused, naming the file and the cell (was exit
# 0, the cell taken as |-1| and refined the most)
python3 - "$T/dwr.msh" "$T/dwrneg.msh" <<'PY'
import sys
L = open(sys.argv[1]).read().split("\n")
i = L.index('"dwr"') - 2                      # $ElementData
j = i + 2 + int(L[i + 1])                      # count of real tags
k = j + 1 + int(L[j])                          # count of integer tags
first = k + 1 + int(L[k])                      # the first value line
tag, v = L[first].split()
L[first] = tag + " -1"
open(sys.argv[2], "w").write("\n".join(L))
PY
expect_fail "dwrneg.msh: field \"dwr\" is negative in cell [0-9]* (centroid (" "$SHAPE" --dwr "$T/dwrneg.msh" --growth 1.5
# a finite but absurd error model (model_A1 = 1e308 in one cell): named as such (it overflowed into
# "exceeds the largest reachable ...: 144 DOFs (lower the complexity or --hmin)": a CLI audit)
python3 - "$SHAPE" "$T/hugeA1.msh" <<'PY'
import sys
L = open(sys.argv[1]).read().split("\n")
i = L.index('"model_A1"') - 2
j = i + 2 + int(L[i + 1])
k = j + 1 + int(L[j])
first = k + 1 + int(L[k])
tag, v = L[first].split()
L[first] = tag + " 1e308"
open(sys.argv[2], "w").write("\n".join(L))
PY
expect_fail "hugeA1.msh: cell [0-9]* (centroid (.*)): the error constant B overflows (model A1 = 1e+308" "$T/hugeA1.msh" --complexity 4000
echo "size_solve: OK"
