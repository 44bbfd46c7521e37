#!/usr/bin/env bash
# CLI test of `refine`: uniform and fixed-fraction refinement, reports, errors (nothing written).
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v refine >/dev/null || { echo "FAIL: refine not built (tools must be on PATH)" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
json() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))$2)" "$1"; }

python3 "$SRC/tests/golden/refine/make_square.py" 4 "$T/sq4.msh"
python3 "$SRC/tests/golden/refine/make_square.py" 2 "$T/tri.msh" tri

# --- uniform: N -> 4N cells, (n+1)^2 -> (2n+1)^2 nodes, twice
refine -q "$T/sq4.msh" --uniform -o "$T/u1.msh"
[ "$(json "$T/u1.json" '["cells"]')" = 64 ] || fail "uniform: cells"
[ "$(json "$T/u1.json" '["nodes"]')" = 81 ] || fail "uniform: nodes"
[ "$(json "$T/u1.json" '["hanging_nodes"]')" = 0 ] || fail "uniform: hanging nodes"
refine -q "$T/u1.msh" --uniform -o "$T/u2.msh"
[ "$(json "$T/u2.json" '["cells"]')" = 256 ] || fail "uniform twice: cells"
[ "$(json "$T/u2.json" '["nodes"]')" = 289 ] || fail "uniform twice: nodes"
# boundary names survive, fields are dropped
for g in bottom right top left; do grep -q "\"$g\"" "$T/u2.msh" || fail "group $g lost"; done
! grep -q '^\$ElementData' "$T/u1.msh" || fail "uniform output still has fields"

# --- fixed fraction on B (largest on the diagonal): ceil(0.3 * 16) = 5 cells flagged
refine -q "$T/sq4.msh" --by B --keep-fields -o "$T/f1.msh"
[ "$(json "$T/f1.json" '["flagged"]')" = 5 ] || fail "fraction: flagged"
[ "$(json "$T/f1.json" '["added_by_balance"]')" = 0 ] || fail "conforming input needs no balancing"
[ "$(json "$T/f1.json" '["cells"]')" = 31 ] || fail "fraction: cells"
[ "$(json "$T/f1.json" '["hanging_nodes"]')" -gt 0 ] || fail "fraction: no hanging nodes"
grep -q '"B"' "$T/f1.msh" || fail "--keep-fields lost B"
! grep -q '"Vinv"' "$T/f1.msh" || fail "--keep-fields kept a 9-component field"
# second step on the non-conforming output: reads its hanging nodes, balances
refine -q "$T/f1.msh" --by B --fraction 0.5 -o "$T/f2.msh"
python3 - "$T/f2.json" <<'EOF'
import json, math, sys
r = json.load(open(sys.argv[1]))
assert r["cells_before"] == 31, r
assert r["flagged"] == math.ceil(0.5 * 31), r
assert r["split"] == r["flagged"] + r["added_by_balance"], r
assert r["cells"] == r["cells_before"] + 3 * r["split"], r
assert r["hanging_nodes_before"] > 0 and r["hanging_nodes"] > 0, r
assert r["options"]["by"] == "B" and r["options"]["fraction"] == 0.5, r
EOF
# and the result is again a valid input (2:1, all quads)
refine -q "$T/f2.msh" --uniform -o "$T/f3.msh"
[ "$(json "$T/f3.json" '["cells"]')" = $((4 * $(json "$T/f2.json" '["cells"]'))) ] || fail "f3 cells"

# --- bad input: exit 2, one line naming the file, nothing written
expect_fail() {  # expect_fail PATTERN ARGS...
  local pat=$1; shift
  rm -f "$T/bad.msh" "$T/bad.json"
  set +e
  refine -q "$@" -o "$T/bad.msh" 2>"$T/err"
  local rc=$?
  set -e
  [ $rc = 2 ] || fail "refine $* exited $rc, expected 2: $(cat "$T/err")"
  grep -q -- "$pat" "$T/err" || fail "refine $*: message '$(cat "$T/err")' lacks '$pat'"
  [ ! -e "$T/bad.msh" ] && [ ! -e "$T/bad.json" ] || fail "refine $* wrote an output"
}
expect_fail "--fraction: 0 is not in (0, 1]" "$T/sq4.msh" --by B --fraction 0
expect_fail "--fraction: 1.5 is not in (0, 1]" "$T/sq4.msh" --by B --fraction 1.5
expect_fail "--fraction: -0.2 is not in (0, 1]" "$T/sq4.msh" --by B --fraction -0.2
expect_fail "sq4.msh: no cell field 'A1'" "$T/sq4.msh" --by A1
expect_fail "u1.msh: no cell field 'B'" "$T/u1.msh" --by B
expect_fail "sq4.msh: field 'Vinv' has 9 components" "$T/sq4.msh" --by Vinv
expect_fail "tri.msh" "$T/tri.msh" --uniform
expect_fail "choose --uniform or --by" "$T/sq4.msh"
expect_fail "--uniform excludes --by" "$T/sq4.msh" --uniform --by B
# a field of the wrong length
python3 - "$T/sq4.msh" "$T/short.msh" <<'EOF'
import sys
s = open(sys.argv[1]).read().split("\n")
i = s.index('"B"')            # $ElementData header: name, 1, time, 3, step, ncomp, count
s[i + 6] = str(int(s[i + 6]) - 1)
del s[i + 7]                  # drop the first cell's value
open(sys.argv[2], "w").write("\n".join(s))
EOF
expect_fail "short.msh" "$T/short.msh" --by B
# never overwrite the input
set +e; refine -q "$T/sq4.msh" --uniform -o "$T/sq4.msh" 2>/dev/null; rc=$?; set -e
[ $rc = 2 ] || fail "overwriting the input: exit $rc"
python3 "$SRC/tests/golden/refine/make_square.py" 4 "$T/ref.msh"
cmp -s "$T/sq4.msh" "$T/ref.msh" || fail "input was modified"
echo "refine CLI: OK"
