#!/usr/bin/env bash
# golden_compare.py itself: equal within tolerance -> 0, a real difference -> 1, bad input -> 2.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
gc="python3 $S/tests/cli/golden_compare.py"
expect() {  # expect STATUS command...
  local want=$1
  shift
  set +e
  "$@" > "$T/out" 2>&1
  local rc=$?
  set -e
  [ $rc -eq "$want" ] || { echo "expected exit $want, got $rc: $*"; cat "$T/out"; exit 1; }
}
echo '{"a": 1.0, "b": {"c": [1, 2, 3], "s": "x"}, "timings": {"t": 1}, "command": "x"}' > "$T/g.json"
echo '{"a": 1.0000000001, "b": {"c": [1, 2, 3], "s": "x"}, "timings": {"t": 9}, "command": "y"}' > "$T/near.json"
echo '{"a": 1.001, "b": {"c": [1, 2, 3], "s": "x"}}' > "$T/far.json"
echo '{"a": 1.0, "b": {"c": [1, 2], "s": "x"}}' > "$T/short.json"
echo '{"a": 1.0, "b": {"c": [1, 2, 3], "s": "y"}}' > "$T/string.json"
expect 0 $gc "$T/near.json" "$T/g.json"
expect 1 $gc "$T/far.json" "$T/g.json"
grep -q "^  a: 1.001 != 1.0" "$T/out"
expect 0 $gc "$T/far.json" "$T/g.json" --rtol 1e-2
expect 0 $gc "$T/far.json" "$T/g.json" --ignore a
expect 1 $gc "$T/short.json" "$T/g.json"
expect 1 $gc "$T/string.json" "$T/g.json"
expect 1 $gc "$T/near.json" "$T/g.json" --keep timings
expect 2 $gc "$T/missing.json" "$T/g.json"
# meshes
g="$S/tests/golden/io/square2_fields.msh"
expect 0 $gc "$g" "$g" --rtol 0 --atol 0
sed 's/^4 0\.3333333333333333$/4 0.33334/' "$g" > "$T/h.msh"
expect 1 $gc "$T/h.msh" "$g"
grep -q "view 'h'" "$T/out"
expect 0 $gc "$T/h.msh" "$g" --rtol 1e-4
sed 's/^0\.5 0\.5 0$/0.5 0.50001 0/' "$g" > "$T/n.msh"
expect 1 $gc "$T/n.msh" "$g"
gc_help=$($gc --help); grep -q "atol" <<<"$gc_help"
echo "io_golden_compare: ok"
