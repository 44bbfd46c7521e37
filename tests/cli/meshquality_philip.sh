#!/usr/bin/env bash
# meshquality reports on every file of PHiLiP's fixtures as it is, and on each output mesh of
# step 2 against the frame PHiLiP computed on it at step 3 (the same mesh). One pair is
# compared with a stored golden report (rtol 1e-9).
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
D=$QUADAPT_SHARED_DIR/reference/philip-fixtures
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
n=0
for f in "$D"/*.msh; do
  meshquality --require quads "$f" > "$T/r.json"
  python3 - "$T/r.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["cells"] > 100 and r["quads"] == r["cells"] and abs(r["area"] - 1) < 1e-9, r
assert sorted(b["name"] for b in r["boundary"]) == ["bottom", "left", "right", "top"], r["boundary"]
assert r["physical"]["scaled_jacobian_min"] > 0
PY
  n=$((n + 1))
done
[ $n -eq 16 ] || { echo "expected 16 fixture files, found $n"; exit 1; }
for out in "$D"/output_*_2.msh; do
  case_=$(basename "$out" _2.msh)
  case_=${case_#output_}
  meshquality "$out" --frame "$D/input_${case_}_3.msh" > "$T/$case_.json"
  python3 - "$T/$case_.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
f, m = r["frame"], r["metric"]
assert f["cells"] == r["cells"] and f["cells_outside"] == 0, f
assert f["continuous_complexity"] > 0 and m["scaled_jacobian_min"] > 0 and 0 < m["edge_length"]["share_in_range"] < 1
PY
done
python3 "$S/tests/cli/golden_compare.py" "$T/ss15_fb_p1.json" "$S/tests/golden/io/meshquality_philip_ss15_fb_p1.json" --ignore mesh --ignore frame.file
echo "meshquality_philip: ok"
